# The paper suite: every case of the source papers (cases.mk) with its
# summary.json, the convergence study of the cement UCS, and the measured
# part of share/doc/validation.md regenerated from them (tools/validation).
#   make -C workflows paper          every case, the study, validation.md
#   make -C workflows convergence    the cement UCS at three sphere counts
#   make -C workflows OUT/CASE/summary.json
# With QUICK=1 the cases use the small variant and the study 2 000, 5 000
# and 10 000 spheres (instead of 5 000, 20 000 and 42 000, the paper's).

PAPER_CASES := $(filter-out demo-%,$(CASES))

# summary.json of any run (post summary, share/doc/post.md).
$(OUT)/%/summary.json: $(OUT)/%/run.h5
	$(BIN)/post summary --out $(@D) $<

# The convergence study: the cement UCS case on its specimen refined.
CONVERGENCE_COUNTS := $(if $(QUICK),2000 5000 10000,5000 20000 42000)
CONVERGENCE := $(foreach n,$(CONVERGENCE_COUNTS),convergence/cement-ucs-$(n))

$(OUT)/convergence/cement-ucs-%/assembly.h5: $(SHARE)/specimens/cement-1x2in.json
	@mkdir -p $(@D)
	$(BIN)/pack --config $< --count $* $(if $(SEED),--seed $(SEED)) --threads $(THREADS) \
		$@ > $(@D)/pack.txt

$(OUT)/convergence/cement-ucs-%/run.h5: $(OUT)/convergence/cement-ucs-%/assembly.h5 \
		$(SHARE)/cases/cement-ucs.json $(SHARE)/materials/cement.json
	$(BIN)/solve --quiet --assembly $< --output $@ --report $(@D)/report.json \
		--threads $(THREADS) $(SHARE)/cases/cement-ucs.json

.PHONY: paper convergence
convergence: $(foreach r,$(CONVERGENCE),$(addprefix $(OUT)/$(r)/,assembly.h5 run.h5 summary.json curve.csv))

paper: $(PAPER_CASES) $(foreach c,$(PAPER_CASES),$(OUT)/$(c)/summary.json) convergence
	$(TOP)/tools/validation --runs $(OUT) $(addprefix --convergence ,$(CONVERGENCE)) \
		$(PAPER_CASES)
