# Sourced by ranks.sh and ranks_failures.sh, with bin, tmp and here set:
# Open MPI's settings for tests (as root; ranks that wait yield the cores
# to the others, more ranks than cores), a fresh TMP_DIR as the working
# directory, same() to compare two run files, and ucs_case to write the
# cement UCS both run.
share=$(cd "$here/../../share" && pwd)
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_mpi_yield_when_idle=1
rm -rf "$tmp"
mkdir -p "$tmp"
cd "$tmp"
same() { /usr/bin/python3 "$here/same_run.py" "$1" "$2"; }
# ucs_case CHECKPOINT_EVERY: a.h5, about 2 400 spheres (10 blocks of 256,
# two threads' shares on a rank), and ucs.json, a UCS of the paper's
# cement to its stress drop with a checkpoint every CHECKPOINT_EVERY steps.
ucs_case() {
	"$bin/pack" --quiet --diameter 0.011 --height 0.022 --radius 0.0005 --dist fuzz \
		--fuzz 0.3 a.h5
	cat > ucs.json <<JSON
{"test": "ucs", "assembly": "a.h5", "material": "$share/materials/cement.json",
 "damping": {"translational": 0.1, "rotational": 0.1},
 "output": {"history_every": 50, "snapshot_every": 250, "checkpoint_every": $1},
 "loading": [{"axial": {"mode": "strain_rate", "rate": 120.0}}],
 "stop": {"strain_axial": 0.03, "stress_drop": 0.7}}
JSON
}
