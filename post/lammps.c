#include <math.h>
#include <stdio.h>

#include "lib/states.h"
#include "post/lammps.h"
#include "post/output.h"

/* LAMMPS numbers its atoms and bonds from 1; numbers are written with 17
 * significant digits, so read_data reads back the very doubles. */
#define NUM "%.17g"

const char *lammps_style_name(lammps_style s)
{
	return s == LAMMPS_BPM_SPHERE ? "bpm/sphere" : "hybrid sphere bond";
}

static int bonded(const lammps_data *d, size_t b)
{
	return !d->state || d->state[b] < BOND_BROKEN_TENSION;
}

size_t lammps_bonded(const lammps_data *d)
{
	size_t n = 0;
	for (size_t b = 0; b < d->bonds->n; b++)
		n += (size_t)bonded(d, b);
	return n;
}

static void write_box(FILE *f, const lammps_data *d)
{
	static const char *const axis[3] = {"x", "y", "z"};
	for (int k = 0; k < 3; k++) {
		double lo = INFINITY, hi = -INFINITY;
		for (size_t i = 0; i < d->n; i++) {
			lo = fmin(lo, d->x[3 * i + k] - d->r[i]);
			hi = fmax(hi, d->x[3 * i + k] + d->r[i]);
		}
		fprintf(f, NUM " " NUM " %slo %shi\n", lo - d->margin, hi + d->margin, axis[k],
		        axis[k]);
	}
}

/* Molecule ID 1 for every sphere: the specimen is one body. */
static void write_atoms(FILE *f, const lammps_data *d)
{
	fprintf(f, "\nAtoms # %s\n\n", d->style == LAMMPS_BPM_SPHERE ? "bpm/sphere" : "hybrid");
	for (size_t i = 0; i < d->n; i++) {
		const double *x = d->x + 3 * i;
		int type = d->material[i] + 1;
		double diameter = 2 * d->r[i];
		if (d->style == LAMMPS_BPM_SPHERE)
			fprintf(f, "%zu 1 %d " NUM " " NUM " " NUM " " NUM " " NUM "\n", i + 1,
			        type, diameter, d->density, x[0], x[1], x[2]);
		else
			fprintf(f, "%zu %d " NUM " " NUM " " NUM " " NUM " " NUM " 1\n", i + 1,
			        type, x[0], x[1], x[2], diameter, d->density);
	}
}

/* Both styles read "id vx vy vz wx wy wz". */
static void write_velocities(FILE *f, const lammps_data *d)
{
	fputs("\nVelocities\n\n", f);
	for (size_t i = 0; i < d->n; i++) {
		const double *v = d->v + 3 * i, *w = d->w + 3 * i;
		fprintf(f, "%zu " NUM " " NUM " " NUM " " NUM " " NUM " " NUM "\n", i + 1, v[0],
		        v[1], v[2], w[0], w[1], w[2]);
	}
}

static void write_bonds(FILE *f, const lammps_data *d)
{
	fputs("\nBonds\n\n", f);
	size_t id = 0;
	for (size_t b = 0; b < d->bonds->n; b++)
		if (bonded(d, b))
			fprintf(f, "%zu 1 %d %d\n", ++id, d->bonds->i[b] + 1, d->bonds->j[b] + 1);
}

void lammps_write_data(const char *path, const lammps_data *d)
{
	int types = 1;
	for (size_t i = 0; i < d->n; i++)
		types = d->material[i] + 1 > types ? d->material[i] + 1 : types;
	size_t nb = lammps_bonded(d);
	out_text o;
	out_text_open(&o, path);
	fprintf(o.f, "%s\n\n", d->comment);
	fprintf(o.f, "%zu atoms\n%d atom types\n%zu bonds\n1 bond types\n\n", d->n, types, nb);
	write_box(o.f, d);
	write_atoms(o.f, d);
	if (d->v)
		write_velocities(o.f, d);
	/* read_data refuses a Bonds section when the header says 0 bonds. */
	if (nb)
		write_bonds(o.f, d);
	out_text_commit(&o);
}

void lammps_write_bonds(const char *path, const lammps_data *d)
{
	static const char *const names[] = {"intact", "damaged", "broken_tension", "broken_shear"};
	out_text o;
	out_text_open(&o, path);
	fputs("bond,atom_i,atom_j,lammps_bond,reference_length_m,length_m,state\n", o.f);
	size_t id = 0;
	for (size_t b = 0; b < d->bonds->n; b++) {
		int32_t i = d->bonds->i[b], j = d->bonds->j[b];
		double len2 = 0;
		for (int k = 0; k < 3; k++) {
			double dx = d->x[3 * (size_t)j + k] - d->x[3 * (size_t)i + k];
			len2 += dx * dx;
		}
		int st = d->state ? d->state[b] : BOND_INTACT;
		fprintf(o.f, "%zu,%d,%d,", b, i + 1, j + 1);
		if (bonded(d, b))
			fprintf(o.f, "%zu", ++id);
		fprintf(o.f, "," NUM "," NUM ",%s\n", d->bonds->d0[b], sqrt(len2),
		        st <= BOND_BROKEN_SHEAR ? names[st] : "unknown");
	}
	out_text_commit(&o);
}
