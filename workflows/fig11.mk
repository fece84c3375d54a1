# The micro-macro compressive stress ratio study of Fig. 11 of Onate et al.
# 2015 (seeds/000, sec. 9): the cement UCS and the four cement triaxial tests;
# at each run's macroscopic limit (peak axial) stress, r = sigma_nc / sigma_a
# averaged over the bonded contacts in compression, by the angle of the
# contact normal to the plane normal to the loading axis. The paper finds r
# between 0.55 and 0.65 for every test.

FIG11_CASES := cement-ucs cement-triaxial-500psi cement-triaxial-1000psi \
	cement-triaxial-2000psi cement-triaxial-4000psi
FIG11_LABELS := UCS,500 psi,1000 psi,2000 psi,4000 psi
FIG11_RUNS := $(foreach c,$(FIG11_CASES),$(OUT)/$(c)/run.h5)

.PHONY: fig11
fig11: $(OUT)/fig11/fig11.png $(OUT)/fig11/r-range.txt
	@echo "fig11: results in $(OUT)/fig11"

$(OUT)/fig11/ratios.csv: $(FIG11_RUNS)
	@mkdir -p $(@D)
	$(BIN)/post ratios --out $(@D) --labels '$(FIG11_LABELS)' $^

$(OUT)/fig11/fig11.png: $(OUT)/fig11/ratios.csv
	cp $(@D)/ratios.png $@

# The range of r over the orientation bins holding contacts, per test and
# over all of them, beside the paper's 0.55-0.65.
$(OUT)/fig11/r-range.txt: $(OUT)/fig11/ratios.csv $(TOP)/workflows/r-range.awk
	awk -F, -f $(TOP)/workflows/r-range.awk $< > $@
