/* A LAMMPS data file of bonded spheres (read by LAMMPS's read_data, units
 * si) and the bond table that goes beside it; share/doc/post.md says how
 * to use them. The data file lists every bond still bonded (intact or
 * damaged) in its Bonds section, of bond type 1; the table lists every
 * bond with its reference length and state, broken ones too. */
#ifndef DEM_POST_LAMMPS_H
#define DEM_POST_LAMMPS_H

#include <stddef.h>
#include <stdint.h>

#include "lib/runfile.h"

/* The atom style the Atoms section is written for:
 *   bpm/sphere (BPM package):     id molecule type diameter density x y z
 *   hybrid sphere bond (older):   id type x y z diameter density molecule */
typedef enum { LAMMPS_BPM_SPHERE, LAMMPS_HYBRID } lammps_style;

typedef struct {
	const char *comment; /* the first line, which read_data skips */
	lammps_style style;
	size_t n;
	const double *x;         /* [n][3] m, centres */
	const double *r;         /* [n] m, radii */
	const int32_t *material; /* [n] material index: atom type = index + 1 */
	double density;          /* kg/m^3, of every sphere */
	const double *v, *w;     /* [n][3] m/s and rad/s; NULL: no Velocities section */
	double margin;           /* m, between the spheres' extent and the box */
	const dem_bonds *bonds;  /* i, j (0-based particle indices) and d0 */
	const uint8_t *state;    /* [bonds->n] BOND_*; NULL: every bond intact */
} lammps_data;

/* The atom style's name as atom_style takes it. */
const char *lammps_style_name(lammps_style s);
/* The number of bonds the data file lists (those not broken). */
size_t lammps_bonded(const lammps_data *d);
/* Write the data file and the bond table (CSV) atomically; fatal on
 * failure. */
void lammps_write_data(const char *path, const lammps_data *d);
void lammps_write_bonds(const char *path, const lammps_data *d);

#endif
