# ratios.csv (post ratios) -> the range of the mean ratio r over the angle
# bins that hold contacts, and r over all contacts whatever their
# orientation (the bins' means weighted by their counts), for each run and
# for all runs (group "all").
NR == 1 {
	for (k = 1; k <= NF; k++)
		col[$k] = k
	next
}
$col["group"] == "all" && $col["count"] > 0 {
	run = $col["run"]
	r = $col["r"] + 0
	if (!(run in lo)) {
		order[++nrun] = run
		lo[run] = hi[run] = r
		ref[run] = $col["sigma_ref_Pa"]
	}
	if (r < lo[run]) lo[run] = r
	if (r > hi[run]) hi[run] = r
	n[run] += $col["count"]
	sum[run] += $col["count"] * r
	if (seen++ == 0) all_lo = all_hi = r
	if (r < all_lo) all_lo = r
	if (r > all_hi) all_hi = r
}
END {
	print "Micro-macro compressive stress ratio r = sigma_nc / sigma_a at the limit stress"
	print "(mean over the bonded contacts in compression in each 10-degree orientation bin)."
	print "Onate et al. 2015, Fig. 11: r between 0.55 and 0.65 for UCS and triaxial tests."
	print ""
	for (k = 1; k <= nrun; k++)
		printf "%-12s sigma_a = %7.2f MPa   r from %.3f to %.3f, all contacts %.3f\n", order[k], ref[order[k]] / 1e6, lo[order[k]], hi[order[k]], sum[order[k]] / n[order[k]]
	printf "%-12s                        r from %.3f to %.3f\n", "all tests", all_lo, all_hi
}
