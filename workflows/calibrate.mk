# Calibrations (share/doc/calibrate.md): share/calibration/<name>.json gives
# $(OUT)/calibrate-<name>/ with material.json, report.md, report.json,
# path.csv, log.csv and the figures. The runs are kept in its log.csv, so a
# calibration made again (the file changed, or it was interrupted) repeats
# only the runs that changed. A calibration that ends without meeting every
# target (exit status 4) still leaves its material and report: make goes on
# and says so.
#   make -C workflows calibrate-<name>     one calibration
#   make -C workflows calibrations         every shipped one
#   make -C workflows bench-calibrate      the speed benchmark (tools/bench-calibrate)
#   make -C workflows calibrate-table45    002's Table 4.5 (tools/calibrate-table45):
#                                          TABLE45_RADII (mm), TABLE45_JOBS
CALIBRATIONS := $(basename $(notdir $(wildcard $(SHARE)/calibration/*.json)))
# Runs side by side [0: one per core].
CAL_JOBS ?= 0

# 002 Table 4.5: one calibration per radius, one solve at a time by default
# (the 0.5 mm one is about 2e5 spheres: hours on two cores).
TABLE45_RADII ?= 1.25 1 0.75 0.5
TABLE45_JOBS ?= 1

.PHONY: calibrations bench-calibrate calibrate-table45 $(addprefix calibrate-,$(CALIBRATIONS))
calibrations: $(addprefix calibrate-,$(CALIBRATIONS))

$(foreach c,$(CALIBRATIONS),$(eval calibrate-$(c): $(OUT)/calibrate-$(c)/material.json ; \
	@echo "calibrate-$(c): results in $(OUT)/calibrate-$(c)"))

$(OUT)/calibrate-%/material.json: $(SHARE)/calibration/%.json | $(BIN)/calibrate
	$(BIN)/calibrate --bin $(BIN) --jobs $(CAL_JOBS) --out $(@D) $< > $(@D).txt || \
		{ rc=$$?; cat $(@D).txt; [ $$rc -eq 4 ] || exit $$rc; \
		  echo "calibrate-$*: not every target met: see $(@D)/report.md"; }

bench-calibrate:
	cd $(TOP) && tools/bench-calibrate --bin $(BIN)

calibrate-table45: | $(BIN)/calibrate
	cd $(TOP) && tools/calibrate-table45 --bin $(BIN) --out $(OUT)/calibrate-table45 \
		--radii "$(TABLE45_RADII)" --jobs $(TABLE45_JOBS)
