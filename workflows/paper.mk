# The paper suite: every case of the source papers (cases.mk), the convergence study of the cement UCS, and the measured
# part of share/doc/validation.md regenerated from them (tools/validation).
#   make -C workflows paper          every case, the study, validation.md
#   make -C workflows convergence    the cement UCS at three sphere counts
# The study's runs (OUT/cement-ucs-<N>) are the cement-ucs case on its
# specimen packed with N spheres: 5 000, 20 000 and 42 000 (the paper's),
# or 2 000, 5 000 and 10 000 with QUICK=1.

PAPER_CASES := $(filter-out demo-%,$(CASES))

CONVERGENCE_COUNTS := $(if $(QUICK),2000 5000 10000,5000 20000 42000)
CONVERGENCE := $(foreach n,$(CONVERGENCE_COUNTS),cement-ucs-$(n))
$(foreach n,$(CONVERGENCE_COUNTS),$(eval cement-ucs-$(n).specimen := cement-1x2in) \
	$(eval cement-ucs-$(n).case := cement-ucs) $(eval cement-ucs-$(n).count := $(n)))

.PHONY: paper convergence
convergence: $(foreach r,$(CONVERGENCE),$(addprefix $(OUT)/$(r)/,assembly.h5 run.h5 summary.json \
	curve.csv))

paper: $(PAPER_CASES) convergence
	$(TOP)/tools/validation --runs $(OUT) $(addprefix --convergence ,$(CONVERGENCE)) \
		$(PAPER_CASES)
