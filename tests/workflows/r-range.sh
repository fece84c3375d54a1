#!/bin/sh
# workflows/r-range.awk on a hand-made ratios.csv: per run the range of r
# over the bins holding contacts (empty bins and the intact/damaged groups
# ignored), r over all contacts weighted by the bins' counts, and the range
# over all runs.
# Usage: r-range.sh SOURCE_DIR
set -eu
h=run,snapshot,step,t_s,strain_axial,stress_axial_Pa,sigma_ref_Pa,group,theta_min_deg,theta_max_deg,count,sigma_n_mean_Pa,sigma_n_std_Pa,r,r_std,tau_mean_Pa,tau_std_Pa
out=$(awk -F, -f "$1/workflows/r-range.awk" <<EOF2
$h
UCS,1,1,0,0,2e7,2e7,all,0,10,0,,,,,,
UCS,1,1,0,0,2e7,2e7,all,10,20,10,4e6,0,0.2,0,0,0
UCS,1,1,0,0,2e7,2e7,all,80,90,30,1.6e7,0,0.8,0,0,0
UCS,1,1,0,0,2e7,2e7,intact,80,90,30,1.6e7,0,0.95,0,0,0
TX,1,1,0,0,4e7,4e7,all,40,50,5,2e7,0,0.5,0,0,0
TX,1,1,0,0,4e7,4e7,all,50,60,15,2.8e7,0,0.7,0,0,0
EOF2
)
echo "$out"
echo "$out" | grep -q "^UCS  *sigma_a =   20.00 MPa   r from 0.200 to 0.800, all contacts 0.650$"
echo "$out" | grep -q "^TX  *sigma_a =   40.00 MPa   r from 0.500 to 0.700, all contacts 0.650$"
echo "$out" | grep -q "^all tests  *r from 0.200 to 0.800$"
