# Parametric studies (share/doc/studies.md): one case run at every point of
# one or two varied parameters, optionally repeated over packing seeds.
#   make -C workflows study STUDY=<name>   share/studies/<name>.json (or an absolute
#                                          path to a study file): every point, then the table
# Outputs in OUT/studies/<name>/: points.mk (the points, from post study),
# one directory per point with its material.json, case.json, specimen.json
# (yade.args and spheres.txt for Yade's packing) and the files of a case
# (assembly.h5, run.h5, summary.json, curve.csv, ...); then runs.csv,
# study.csv, response.png and curves.png (post study --table).
#
# post study rewrites a point's files only when their content changes, and
# pack and solve list what they read in depfiles: a changed value re-runs
# only the points it changes, a material value only solve and post, a
# specimen value pack too; make -j runs points side by side. The points
# are made with make -k, so a failed point (reported, the stage that
# failed in its stage.failed, solve's diagnosis in run.failed.h5) does not
# stop the others; the table is then made of the rest, the failed point
# marked, and make exits non-zero. A failed point runs again at the next
# make, as a failed case does.

STUDY ?=
STUDIES := $(OUT)/studies

ifneq ($(STUDY),)
ifneq ($(filter-out /%,$(filter %.json %/%,$(STUDY))),)
$(error STUDY=$(STUDY): a relative path (make -C changes directory): give a shipped study's \
	name (STUDY=tiny) or an absolute path (STUDY=$$PWD/$(STUDY)))
endif
STUDY_FILE := $(if $(filter /%,$(STUDY)),$(STUDY),$(SHARE)/studies/$(STUDY).json)
ifeq ($(wildcard $(STUDY_FILE)),)
$(error STUDY=$(STUDY): no study file $(STUDY_FILE): expected one of $(basename $(notdir \
	$(wildcard $(SHARE)/studies/*.json))) or an absolute path)
endif
STUDY_NAME := $(basename $(notdir $(STUDY_FILE)))
STUDY_DIR := $(STUDIES)/$(STUDY_NAME)
STUDY_POINTS :=
include $(STUDY_DIR)/points.mk

$(STUDY_DIR)/points.mk: $(STUDY_FILE) | $(BIN)/post
	$(BIN)/post study --out $(STUDY_DIR) $(STUDY_FILE)

# A point's files, named so that make does not take its assembly and run
# for intermediate files and delete them; the table reads its results.
STUDY_RESULTS := $(foreach p,$(STUDY_POINTS),$(addprefix $(STUDY_DIR)/$(p)/,summary.json curve.csv))
STUDY_OUTPUTS := $(STUDY_RESULTS) $(foreach p,$(STUDY_POINTS),$(addprefix $(STUDY_DIR)/$(p)/,assembly.h5 run.h5))
endif

.PHONY: study study-points study-table
study:
	@[ -n "$(STUDY)" ] || { echo "study: expected STUDY=<name> (share/studies/<name>.json)" >&2; exit 2; }
	+@rc=0; $(MAKE) --no-print-directory -k study-points || rc=$$?; \
	$(MAKE) --no-print-directory study-table || exit $$?; \
	[ $$rc -eq 0 ] || echo "study $(STUDY_NAME): some points failed: marked in $(STUDY_DIR)/runs.csv" >&2; \
	[ $$rc -eq 0 ] && echo "study $(STUDY_NAME): results in $(STUDY_DIR)"; exit $$rc

study-points: $(STUDY_OUTPUTS)

# The table and figures of whatever the points left: made again when a
# point's results, or its failure, change.
study-table: $(STUDY_DIR)/study.csv

$(STUDY_DIR)/study.csv: $(STUDY_DIR)/points.mk $(wildcard $(STUDY_RESULTS) \
		$(foreach p,$(STUDY_POINTS),$(STUDY_DIR)/$(p)/stage.failed)) | $(BIN)/post
	$(BIN)/post study --table --out $(STUDY_DIR) $(STUDY_FILE)

# A point's stages; summary.json and curve.csv come from the Makefile's
# rules for every run. These rules' stems are shorter than the Makefile's,
# so make takes them for the points. A stage that fails writes its name to
# the point's stage.failed (solve also keeps its diagnosis in
# run.failed.h5), for the table; one that completes removes them. An
# interrupted solve (status 3) has not failed: its run becomes the recovery
# copy run.h5.ckpt, which the next make continues (as in the Makefile).
failed_stage = { rc=$$?; echo $(1) > $(@D)/stage.failed; exit $$rc; }

$(STUDIES)/%/spheres.txt: $(STUDIES)/%/yade.args
	$(TOP)/tools/yade-pack $$(cat $<) $@ > $(@D)/yade.txt || $(call failed_stage,yade-pack)
	rm -f $(@D)/stage.failed

$(STUDIES)/%/assembly.h5: $(STUDIES)/%/specimen.json | $(BIN)/pack
	$(BIN)/pack --config $< --threads $(THREADS) --depfile $(@D)/assembly.d $@ \
		> $(@D)/pack.txt || $(call failed_stage,pack)
	rm -f $(@D)/stage.failed

$(STUDIES)/%/run.h5: SHELL := $(TOP)/workflows/solve-shell
$(STUDIES)/%/run.h5: $(STUDIES)/%/assembly.h5 $(STUDIES)/%/case.json | $(BIN)/solve
	@echo "== study point $*"
	@rm -f $(@D)/report.json
	$(strip $(MPIRUN) $(BIN)/solve) --assembly $< --output $@ --depfile $(@D)/run.d \
		--report $(@D)/report.json --threads $(THREADS) $(@D)/case.json \
		|| $(TOP)/workflows/after-solve $$? $@ $(@D)/stage.failed
	rm -f $(@D)/run.failed.h5 $(@D)/stage.failed

-include $(wildcard $(STUDIES)/*/*/assembly.d $(STUDIES)/*/*/run.d)
