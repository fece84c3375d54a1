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
CALIBRATIONS := $(basename $(notdir $(wildcard $(SHARE)/calibration/*.json)))
# Runs side by side [0: one per core].
CAL_JOBS ?= 0

.PHONY: calibrations bench-calibrate $(addprefix calibrate-,$(CALIBRATIONS))
calibrations: $(addprefix calibrate-,$(CALIBRATIONS))

$(foreach c,$(CALIBRATIONS),$(eval calibrate-$(c): $(OUT)/calibrate-$(c)/material.json ; \
	@echo "calibrate-$(c): results in $(OUT)/calibrate-$(c)"))

$(OUT)/calibrate-%/material.json: $(SHARE)/calibration/%.json | $(BIN)/calibrate
	$(BIN)/calibrate --bin $(BIN) --jobs $(CAL_JOBS) --out $(@D) $< > $(@D).txt || \
		{ rc=$$?; cat $(@D).txt; [ $$rc -eq 4 ] || exit $$rc; \
		  echo "calibrate-$*: not every target met: see $(@D)/report.md"; }

bench-calibrate:
	cd $(TOP) && tools/bench-calibrate --bin $(BIN)
