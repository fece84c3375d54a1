/* Micro-macro compressive stress ratios by contact orientation (Onate et
 * al. 2015, sec. 9 and Fig. 11).
 *
 * For every bonded contact (intact or damaged) in compression at one
 * snapshot:
 *   sigma_n = F_nc / A      F_nc = -fn > 0 the compressive normal force,
 *                           A the effective contact area A-bar (/bonds/area)
 *   tau     = |F_s| / A     the shear stress
 *   theta   = asin(|n . a|) the angle between the contact normal n (from
 *                           centre i to centre j, current positions) and
 *                           the plane normal to the loading axis a:
 *                           0 deg a horizontal normal, 90 deg along the load
 * Contacts are grouped in theta bins; per bin and per group (all bonded,
 * intact, damaged) the count, mean and standard deviation of sigma_n and
 * tau. The standard deviation is that of the population of contacts in the
 * bin (divisor N: every contact is counted, none sampled), computed in two
 * passes about the mean. The ratio of Fig. 11 is r = mean sigma_n /
 * sigma_a^l with sigma_a^l the macroscopic reference stress.
 *
 * Bins either have equal width in theta, or equal solid angle: the solid
 * angle of the band theta1..theta2 of a hemisphere is 2 pi (sin theta2 -
 * sin theta1), so n equal bands have edges asin(k/n). */
#ifndef DEM_POST_RATIOS_H
#define DEM_POST_RATIOS_H

#include <stddef.h>

#include "lib/runfile.h"
#include "post/frame.h"

enum { RATIO_ALL, RATIO_INTACT, RATIO_DAMAGED, RATIO_NGROUPS };
extern const char *const ratio_group_name[RATIO_NGROUPS];

typedef struct {
	int n;         /* number of bins */
	double *edges; /* [n + 1] deg, 0 .. 90 ascending */
} ratio_bins;

/* Bins of width w deg (the last one narrower when w does not divide 90). */
void ratio_bins_width(ratio_bins *b, double w);
/* n bins of equal solid angle. */
void ratio_bins_solid_angle(ratio_bins *b, int n);
void ratio_bins_free(ratio_bins *b);
/* The bin of angle theta (deg, 0..90); 90 is in the last bin. */
int ratio_bin_of(const ratio_bins *b, double theta);

typedef struct {
	size_t count;
	double sn_mean, sn_std;   /* Pa; NaN when count == 0 */
	double tau_mean, tau_std; /* Pa; NaN when count == 0 */
} ratio_stat;

/* Statistics of snapshot s: stat[g * bins->n + k] for group g, bin k.
 * theta is measured in frame f (post/frame.h). Returns the number of
 * bonded contacts in compression, or -1 with err_set() (a bond of zero area
 * or length). */
long ratios_compute(const dem_bonds *b, const dem_snapshot *s, const frame *f,
                    const ratio_bins *bins, ratio_stat *stat);

#endif
