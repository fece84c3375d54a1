/* /checkpoint in run.h5: the evolving engine state, enough to continue bit
 * for bit (solve --restart). What setup rebuilds deterministically from the
 * embedded assembly and the configuration (particle order, masses, bond
 * topology, gauge, frame, time-step bound) is not stored; the particle
 * order is kept only to check that. Layout in share/doc/solve.md. Datasets
 * are extendible and overwritten in place, so repeated checkpoints do not
 * grow the file; the `complete` attribute is 0 while one is being written,
 * and `checksum` (CRC-32 of the state it holds) is compared after a restart
 * has read it back, so damaged checkpoint data is refused, never continued. */
#include <stddef.h>
#include <stdlib.h>
#include <string.h>
#include <zlib.h>

#include "lib/err.h"
#include "lib/h5.h"
#include "solve/checkpoint.h"
#include "solve/contacts.h"
#include "solve/pairlist.h"
#include "solve/par.h"
#include "solve/ranks.h"

typedef struct {
	const char *name;
	double *d;
	int64_t *i;
	int *n;
	size_t *z;
} scalar;

/* Every scalar of the state, by name: the one table for writing and reading
 * (the counts of the whole specimen's contacts and platen contacts in
 * count[3]). */
static int scalars(engine *e, size_t count[3], scalar *s)
{
	scalar t[] = {
	    {"t", &e->clock.t, 0, 0, 0},
	    {"dt", &e->clock.dt, 0, 0, 0},
	    {"dt_crit", &e->clock.dt_crit, 0, 0, 0},
	    {"stage_t", &e->prog.stage_t, 0, 0, 0},
	    {"stage_strain0", &e->prog.stage_strain0, 0, 0, 0},
	    {"stage_stress0", &e->prog.stage_stress0, 0, 0, 0},
	    {"stage_pressure0", &e->prog.stage_pressure0, 0, 0, 0},
	    {"stage_peak", &e->prog.stage_peak, 0, 0, 0},
	    {"peak", &e->prog.peak, 0, 0, 0},
	    {"pressure", &e->prog.pressure, 0, 0, 0},
	    {"energy_damped", &e->energy.damped, 0, 0, 0},
	    {"energy_friction", &e->energy.friction, 0, 0, 0},
	    {"energy_fracture", &e->energy.fracture, 0, 0, 0},
	    {"energy_work", &e->energy.work, 0, 0, 0},
	    {"energy_initial", &e->energy.initial, 0, 0, 0},
	    {"energy_kinetic", &e->energy.kinetic, 0, 0, 0},
	    {"snapshot_strain", &e->out.last_snapshot_strain, 0, 0, 0},
	    {"platen_z0", &e->bc.pl.z[0], 0, 0, 0},
	    {"platen_z1", &e->bc.pl.z[1], 0, 0, 0},
	    {"platen_v0", &e->bc.pl.vel[0], 0, 0, 0},
	    {"platen_v1", &e->bc.pl.vel[1], 0, 0, 0},
	    {"platen_load0", &e->bc.pl.load[0], 0, 0, 0},
	    {"platen_load1", &e->bc.pl.load[1], 0, 0, 0},
	    {"platen_k0", &e->bc.pl.ksum[0], 0, 0, 0},
	    {"platen_k1", &e->bc.pl.ksum[1], 0, 0, 0},
	    {"platen_zref0", &e->bc.pl.z_ref[0], 0, 0, 0},
	    {"platen_zref1", &e->bc.pl.z_ref[1], 0, 0, 0},
	    {"lateral_area", &e->bc.surf.lateral_area, 0, 0, 0},
	    {"surface_radius", &e->bc.surf.radius, 0, 0, 0},
	    {"surface_volume", &e->bc.surf.volume, 0, 0, 0},
	    {"step", 0, &e->clock.step, 0, 0},
	    {"stage_step", 0, &e->prog.stage_step, 0, 0},
	    {"surface_updated", 0, &e->bc.surf.updated, 0, 0},
	    {"rebuilds", 0, &e->pairs.rebuilds, 0, 0},
	    {"stage", 0, 0, &e->prog.stage, 0},
	    {"layers_selected", 0, 0, &e->prog.layers_selected, 0},
	    {"drop_armed", 0, 0, &e->prog.drop_armed, 0},
	    {"rebuild", 0, 0, &e->pairs.rebuild, 0},
	    {"platens_active", 0, 0, &e->bc.pl.active, 0},
	    {"history_rows", 0, 0, 0, &e->out.history_rows},
	    {"crack_rows", 0, 0, 0, &e->out.crack_rows},
	    {"snapshot_strain_next", 0, 0, 0, &e->out.snapshot_strain_next},
	    {"surface_n", 0, 0, 0, &e->bc.surf.n},
	    {"contacts_n", 0, 0, 0, &count[0]},
	    {"platen_n0", 0, 0, 0, &count[1]},
	    {"platen_n1", 0, 0, 0, &count[2]},
	};
	int n = (int)(sizeof t / sizeof t[0]);
	if (s)
		memcpy(s, t, sizeof t);
	return n;
}

/* CRC-32 of the checkpointed state as it is in memory, in a fixed order:
 * the same function after writing and after reading back. */
static uLong crc(uLong c, const void *p, size_t bytes) { return crc32_z(c, p, bytes); }

/* The bonds' histories and forces as checkpoints before this layout held
 * them (bond_h with a fourth column, the last u_n, and bond_force with the
 * torque per unit radius), read for their checksum. */
enum { OLD_NHIST = 4, OLD_FCOLS = 6 };
typedef struct {
	double *h; /* [B][OLD_NHIST] */
	double *f; /* [B][OLD_FCOLS] */
} old_bonds;

/* Whether contacts follow Yade's conventions (laws/material.h): they then
 * keep their start (contact_d0, platen<k>_start), which checkpoints hold
 * and checksum. */
static int yade_contacts(const engine *e) { return e->cs->mat.conventions == CONTACT_YADE; }

/* old: when not NULL, the bonds' h and f as an old checkpoint held them. */
static uLong pairs_crc(uLong c, const pairlist *l, int contacts, const old_bonds *old)
{
	for (size_t b = 0; b < l->n; b++) {
		const bond *r = &l->rec[b];
		if (contacts) {
			c = crc(c, &r->i, sizeof r->i);
			c = crc(c, &r->j, sizeof r->j);
		}
		c = crc(c, r->t, sizeof r->t);
		if (!contacts) {
			c = old ? crc(c, old->h + OLD_NHIST * b, OLD_NHIST * sizeof *old->h)
			        : crc(c, r->h, sizeof r->h);
			c = crc(c, &r->state, sizeof r->state);
		}
	}
	if (contacts) { /* their constants, as the contiguous rows of contact_k */
		for (size_t b = 0; b < l->n; b++)
			c = crc(c, l->rec[b].h, 3 * sizeof *l->rec[b].h);
		return c;
	}
	return old ? crc(c, old->f, OLD_FCOLS * l->n * sizeof *old->f)
	           : crc(c, l->f, (size_t)l->fcols * l->n * sizeof *l->f);
}

static int64_t state_crc(engine *e, const pairs_view *v, const old_bonds *old)
{
	uLong c = crc32_z(0, Z_NULL, 0);
	scalar s[64];
	size_t count[3] = {v->contacts->n, v->ncand[0], v->ncand[1]};
	int ns = scalars(e, count, s);
	for (int k = 0; k < ns; k++) {
		int64_t v = s[k].i ? *s[k].i : s[k].n ? *s[k].n : s[k].z ? (int64_t)*s[k].z : 0;
		c = s[k].d ? crc(c, s[k].d, sizeof *s[k].d) : crc(c, &v, sizeof v);
	}
	const particles *P = &e->p;
	size_t n = P->n;
	c = crc(c, P->orig, n * sizeof *P->orig);
	const double *vec[] = {P->x, P->v, P->w, P->x_ref};
	for (int k = 0; k < 4; k++)
		c = crc(c, vec[k], 3 * n * sizeof *vec[k]);
	c = crc(c, P->flag, n * sizeof *P->flag);
	c = crc(c, e->bc.surf.idx, e->bc.surf.n * sizeof *e->bc.surf.idx);
	c = crc(c, e->bc.surf.area, e->bc.surf.n * sizeof *e->bc.surf.area);
	c = pairs_crc(c, v->bonds, 0, old);
	c = pairs_crc(c, v->contacts, 1, NULL);
	for (size_t b = 0; yade_contacts(e) && b < v->contacts->n; b++)
		c = crc(c, &v->contacts->rec[b].d0, sizeof(double));
	for (int k = 0; k < 2; k++) {
		c = crc(c, v->who[k], v->ncand[k] * sizeof *v->who[k]);
		for (size_t q = 0; q < v->ncand[k]; q++)
			c = crc(c, &v->pc[k][q],
			        yade_contacts(e) ? sizeof v->pc[k][q]
			                         : offsetof(platen_contact, u0));
	}
	return (int64_t)c;
}

/* Open a dataset of rows x cols (cols 0: rank 1) for overwriting, creating
 * it (chunked, extendible) the first time. */
static hid_t open_put(hid_t g, const char *name, hid_t type, size_t rows, size_t cols)
{
	int rank = cols ? 2 : 1;
	hsize_t dims[2] = {rows, cols}, maxd[2] = {H5S_UNLIMITED, cols};
	hid_t d;
	if (h5_exists(g, name)) {
		d = H5Dopen2(g, name, H5P_DEFAULT);
		if (d >= 0 && H5Dset_extent(d, dims) < 0) {
			H5Dclose(d);
			d = -1;
		}
	} else {
		hid_t sp = H5Screate_simple(rank, dims, maxd);
		hid_t pl = H5Pcreate(H5P_DATASET_CREATE);
		/* Chunks of at most one piece: HDF5 buffers a whole chunk. */
		size_t most = H5_PIECE_ELEMENTS / (cols ? cols : 1);
		hsize_t chunk[2] = {rows > most ? most : rows ? rows : 1, cols ? cols : 1};
		H5Pset_chunk(pl, rank, chunk);
		d = H5Dcreate2(g, name, type, sp, H5P_DEFAULT, pl, H5P_DEFAULT);
		H5Pclose(pl);
		H5Sclose(sp);
	}
	if (d < 0)
		h5_write_dataset_error(g, name);
	return d;
}

/* Write or overwrite a whole dataset. */
static int put(hid_t g, const char *name, hid_t type, const void *data, size_t rows, size_t cols)
{
	hid_t d = open_put(g, name, type, rows, cols);
	if (d < 0)
		return -1;
	herr_t rc = rows ? H5Dwrite(d, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data) : 0;
	H5Dclose(d);
	if (rc < 0)
		return h5_write_dataset_error(g, name);
	return 0;
}

/* A field of the bond records (cols elements of size bytes at offset). */
enum { T_F64, T_I32, T_U8 };
typedef struct {
	const char *name;
	int type; /* T_* */
	size_t offset, cols, size;
} field;

static hid_t h5type(int t)
{
	return t == T_F64 ? H5T_NATIVE_DOUBLE : t == T_I32 ? H5T_NATIVE_INT32 : H5T_NATIVE_UINT8;
}

enum { PIECE = 16384 };

/* Write one field of n records, a piece at a time (no copy of the whole). */
static int put_field(hid_t g, const field *f, const bond *rec, size_t n)
{
	hid_t d = open_put(g, f->name, h5type(f->type), n, f->cols > 1 ? f->cols : 0);
	if (d < 0)
		return -1;
	size_t row = f->cols * f->size;
	unsigned char *buf = xmalloc(PIECE * row);
	herr_t rc = 0;
	for (size_t at = 0; rc >= 0 && at < n; at += PIECE) {
		size_t m = n - at < PIECE ? n - at : PIECE;
		for (size_t k = 0; k < m; k++)
			memcpy(buf + k * row, (const unsigned char *)&rec[at + k] + f->offset, row);
		rc = h5_slab(d, h5type(f->type), at, m, f->cols > 1 ? f->cols : 0, buf, 1);
	}
	free(buf);
	H5Dclose(d);
	if (rc < 0)
		return h5_write_dataset_error(g, f->name);
	return 0;
}

/* Open dataset `name` of g, which must have exactly n rows of cols columns
 * (0: one-dimensional), or -1 with the error set. */
static hid_t open_rows(hid_t g, const char *name, size_t n, size_t cols)
{
	if (!h5_exists(g, name))
		return err_set("%s: checkpoint dataset '%s': missing", h5_name(g), name);
	hid_t d = H5Dopen2(g, name, H5P_DEFAULT);
	hid_t sp = H5Dget_space(d);
	hsize_t dims[2] = {0, 0};
	int rank = H5Sget_simple_extent_ndims(sp);
	if (rank == (cols ? 2 : 1)) /* dims holds no more */
		H5Sget_simple_extent_dims(sp, dims, NULL);
	H5Sclose(sp);
	if (rank != (cols ? 2 : 1) || dims[0] != n || (cols && dims[1] != cols)) {
		H5Dclose(d);
		return err_set("%s: checkpoint dataset '%s': wrong shape (expected %zu rows)",
		               h5_name(g), name, n);
	}
	return d;
}

/* Rows [first, first + rows) of one field of n records (the dataset must
 * have exactly n rows) into rec[0 .. rows). */
static int get_field(hid_t g, const field *f, bond *rec, size_t first, size_t rows, size_t n)
{
	size_t cols = f->cols > 1 ? f->cols : 0;
	hid_t d = open_rows(g, f->name, n, cols);
	if (d < 0)
		return -1;
	size_t row = f->cols * f->size;
	unsigned char *buf = xmalloc(PIECE * row);
	herr_t rc = 0;
	for (size_t at = 0; rc >= 0 && at < rows; at += PIECE) {
		size_t m = rows - at < PIECE ? rows - at : PIECE;
		rc = h5_slab(d, h5type(f->type), first + at, m, cols, buf, 0);
		for (size_t k = 0; rc >= 0 && k < m; k++)
			memcpy((unsigned char *)&rec[at + k] + f->offset, buf + k * row, row);
	}
	free(buf);
	H5Dclose(d);
	if (rc < 0)
		return err_set("%s: checkpoint dataset '%s': unreadable", h5_name(g), f->name);
	return 0;
}

/* Rows [first, first + rows) of a dataset of exactly n rows of cols
 * doubles into dst. */
static int get_rows(hid_t g, const char *name, double *dst, size_t first, size_t rows, size_t n,
                    size_t cols)
{
	hid_t d = open_rows(g, name, n, cols);
	if (d < 0)
		return -1;
	herr_t rc = rows ? h5_slab(d, H5T_NATIVE_DOUBLE, first, rows, cols, dst, 0) : 0;
	H5Dclose(d);
	if (rc < 0)
		return err_set("%s: checkpoint dataset '%s': unreadable", h5_name(g), name);
	return 0;
}

#define FIELD(name, type, member, cols)                                                        \
	{                                                                                      \
		name, type, offsetof(bond, member), cols, sizeof(((bond *)0)->member) / (cols) \
	}

static const field bond_fields[] = {
    FIELD("bond_t", T_F64, t, 3),
    FIELD("bond_h", T_F64, h, LAW_NHIST),
    FIELD("bond_state", T_U8, state, 1),
};
static const field contact_fields[] = {
    FIELD("contact_i", T_I32, i, 1),
    FIELD("contact_j", T_I32, j, 1),
    FIELD("contact_t", T_F64, t, 3),
    FIELD("contact_k", T_F64, h, 3),
};
/* With Yade's conventions only. */
static const field contact_start = FIELD("contact_d0", T_F64, d0, 1);

static int put_fields(hid_t g, const field *f, int nf, const pairlist *l)
{
	for (int k = 0; k < nf; k++)
		if (put_field(g, &f[k], l->rec, l->n))
			return -1;
	return 0;
}

static int write_platens(hid_t g, const engine *e, const pairs_view *v)
{
	int rc = 0;
	for (int k = 0; !rc && k < 2; k++) {
		size_t n = v->ncand[k];
		double *pc = xmalloc((6 * n + 1) * sizeof *pc);
		for (size_t c = 0; c < n; c++) {
			const platen_contact *p = &v->pc[k][c];
			double v[6] = {p->t[0], p->t[1], p->t[2], p->kn, p->ks, p->cn};
			memcpy(pc + 6 * c, v, sizeof v);
		}
		char who[32], con[32];
		snprintf(who, sizeof who, "platen%d_particle", k);
		snprintf(con, sizeof con, "platen%d_contact", k);
		rc = put(g, who, H5T_NATIVE_INT32, v->who[k], n, 0) ||
		     put(g, con, H5T_NATIVE_DOUBLE, pc, n, 6);
		if (!rc && yade_contacts(e)) {
			for (size_t c = 0; c < n; c++)
				pc[c] = v->pc[k][c].u0;
			snprintf(con, sizeof con, "platen%d_start", k);
			rc = put(g, con, H5T_NATIVE_DOUBLE, pc, n, 0);
		}
		free(pc);
	}
	return rc;
}

int checkpoint_write(engine *e, hid_t file)
{
	hid_t g = h5_exists(file, "checkpoint") ? h5_open_group(file, "checkpoint")
	                                        : h5_group(file, "checkpoint");
	if (g < 0)
		return -1;
	int rc = h5_attr_i64(g, "complete", 0);
	pairs_view v;
	ranks_pairs(e, &v);
	size_t count[3] = {v.contacts->n, v.ncand[0], v.ncand[1]};
	scalar s[64];
	int ns = scalars(e, count, s);
	for (int k = 0; !rc && k < ns; k++)
		rc = s[k].d   ? h5_attr_f64(g, s[k].name, *s[k].d)
		     : s[k].i ? h5_attr_i64(g, s[k].name, *s[k].i)
		     : s[k].n ? h5_attr_i64(g, s[k].name, *s[k].n)
		              : h5_attr_i64(g, s[k].name, (int64_t)*s[k].z);
	const particles *P = &e->p;
	size_t n = P->n;
	rc = rc || put(g, "orig", H5T_NATIVE_INT32, P->orig, n, 0) ||
	     put(g, "x", H5T_NATIVE_DOUBLE, P->x, n, 3) ||
	     put(g, "v", H5T_NATIVE_DOUBLE, P->v, n, 3) ||
	     put(g, "w", H5T_NATIVE_DOUBLE, P->w, n, 3) ||
	     put(g, "x_ref", H5T_NATIVE_DOUBLE, P->x_ref, n, 3) ||
	     put(g, "flag", H5T_NATIVE_UINT8, P->flag, n, 0) ||
	     put(g, "surface_particle", H5T_NATIVE_INT32, e->bc.surf.idx, e->bc.surf.n, 0) ||
	     put(g, "surface_area", H5T_NATIVE_DOUBLE, e->bc.surf.area, e->bc.surf.n, 0) ||
	     put_fields(g, bond_fields, 3, v.bonds) ||
	     put(g, "bond_force", H5T_NATIVE_DOUBLE, v.bonds->f, v.bonds->n, 3) ||
	     put_fields(g, contact_fields, 4, v.contacts) ||
	     (yade_contacts(e) && put_field(g, &contact_start, v.contacts->rec, v.contacts->n)) ||
	     write_platens(g, e, &v) || h5_attr_i64(g, "checksum", state_crc(e, &v, NULL)) ||
	     h5_attr_i64(g, "complete", 1);
	H5Gclose(g);
	if (!rc && H5Fflush(file, H5F_SCOPE_GLOBAL) < 0)
		rc = h5_write_error(h5_name(file), "the checkpoint");
	return rc ? -1 : 0;
}

/* Read a dataset of exactly rows x cols into dst. */
static int get(hid_t g, const char *name, hid_t type, void *dst, size_t rows, size_t cols)
{
	void *buf;
	if (h5_read_n(g, name, type, &buf, rows, cols))
		return -1;
	memcpy(dst, buf, rows * (cols ? cols : 1) * H5Tget_size(type));
	free(buf);
	return 0;
}

/* The columns of a two-dimensional dataset, or 0. */
static size_t columns(hid_t g, const char *name)
{
	hsize_t dims[2] = {0, 0};
	hid_t d = H5Dopen2(g, name, H5P_DEFAULT);
	if (d < 0)
		return 0;
	hid_t s = H5Dget_space(d);
	int nd = H5Sget_simple_extent_ndims(s);
	if (nd == 2)
		H5Sget_simple_extent_dims(s, dims, NULL);
	H5Sclose(s);
	H5Dclose(d);
	return nd == 2 ? (size_t)dims[1] : 0;
}

/* The bonds' histories (bond_h) and forces on i (bond_force). An older
 * checkpoint's (*is_old set; its arrays kept in *old for the checksum)
 * holds a fourth history column, the last u_n, in the slot the law names
 * (law.h_dropped), and the torque per unit radius after each force. */
static int read_bond_h_f(hid_t g, const engine *e, size_t first, size_t rows, size_t nb,
                         old_bonds *old, int *is_old)
{
	const pairlist *L = &e->pairs.bonds;
	*is_old = columns(g, "bond_h") == OLD_NHIST;
	if (!*is_old)
		return get_field(g, &bond_fields[1], L->rec, first, rows, nb) ||
		       get_rows(g, "bond_force", L->f, first, rows, nb, 3);
	if (h5_read_n(g, "bond_h", H5T_NATIVE_DOUBLE, (void **)&old->h, nb, OLD_NHIST) ||
	    h5_read_n(g, "bond_force", H5T_NATIVE_DOUBLE, (void **)&old->f, nb, OLD_FCOLS))
		return -1;
	for (size_t r = 0; r < rows; r++) {
		size_t b = first + r;
		for (int c = 0, k = 0; c < OLD_NHIST; c++)
			if (c != e->law->h_dropped)
				L->rec[r].h[k++] = old->h[OLD_NHIST * b + (size_t)c];
		memcpy(L->f + 3 * r, old->f + OLD_FCOLS * b, 3 * sizeof *L->f);
	}
	return 0;
}

/* The checkpoint's nc contacts, read in pieces: on rank 0, which checks the
 * checksum over them, all of them; on another rank those with an end of
 * its own (contacts_restore keeps what each rank lists). */
static int read_pairs(hid_t g, engine *e, size_t nc)
{
	pairlist *L = &e->pairs.contacts;
	size_t p0, p1;
	int all = !ranks_own(e, &p0, &p1) || par_rank() == 0;
	bond *piece = xmalloc(PIECE * sizeof *piece);
	int rc = 0;
	L->n = 0;
	for (size_t at = 0; !rc && at < nc; at += PIECE) {
		size_t m = nc - at < PIECE ? nc - at : PIECE;
		memset(piece, 0, m * sizeof *piece);
		for (int k = 0; !rc && k < 4; k++)
			rc = get_field(g, &contact_fields[k], piece, at, m, nc);
		if (!rc && yade_contacts(e))
			rc = get_field(g, &contact_start, piece, at, m, nc);
		for (size_t q = 0; !rc && q < m; q++) {
			bond *b = &piece[q];
			size_t i = (size_t)b->i, j = (size_t)b->j;
			if (b->i < 0 || b->j < 0 || i >= e->p.n || j >= e->p.n)
				rc = err_set("%s: checkpoint contact %zu: particle out of range",
				             h5_name(g), at + q);
			else if (all || (i >= p0 && i < p1) || (j >= p0 && j < p1)) {
				if (L->n == L->cap) {
					L->cap = 2 * L->cap + 1024;
					L->rec = xrealloc(L->rec, L->cap * sizeof *L->rec);
					L->f = xrealloc(L->f, 6 * L->cap * sizeof *L->f);
					L->ref = xrealloc(L->ref, 2 * L->cap * sizeof *L->ref);
				}
				if (!yade_contacts(e))
					b->d0 = e->p.r[i] + e->p.r[j];
				b->state = BOND_BROKEN_TENSION;
				L->rec[L->n++] = *b;
			}
		}
	}
	free(piece);
	if (rc)
		return -1;
	L->fcols = 6;
	memset(L->f, 0, 6 * L->n * sizeof *L->f);
	return 0;
}

static int read_platens(hid_t g, engine *e)
{
	particles *P = &e->p;
	for (int k = 0; k < 2; k++) {
		size_t n = e->bc.pl.ncand[k];
		char who[32], con[32];
		snprintf(who, sizeof who, "platen%d_particle", k);
		snprintf(con, sizeof con, "platen%d_contact", k);
		/* Read before the lists are sized by n, a count from the file. */
		double *pc = NULL;
		int32_t *ids = NULL;
		if (h5_read_n(g, who, H5T_NATIVE_INT32, (void **)&ids, n, 0) ||
		    h5_read_n(g, con, H5T_NATIVE_DOUBLE, (void **)&pc, n, 6)) {
			free(ids);
			return -1;
		}
		if (n > e->bc.pl.cap[k]) {
			e->bc.pl.cap[k] = n;
			e->bc.pl.pc[k] = xrealloc(e->bc.pl.pc[k], n * sizeof *e->bc.pl.pc[k]);
			e->bc.pl.pc_old[k] =
			    xrealloc(e->bc.pl.pc_old[k], n * sizeof *e->bc.pl.pc_old[k]);
			e->bc.pl.who[k] = xrealloc(e->bc.pl.who[k], n * sizeof *e->bc.pl.who[k]);
		}
		if (n)
			memcpy(e->bc.pl.who[k], ids, n * sizeof *ids);
		free(ids);
		int rc = 0;
		for (size_t i = 0; i < P->n; i++)
			P->pslot[k][i] = -1;
		for (size_t c = 0; !rc && c < n; c++) {
			int32_t p = e->bc.pl.who[k][c];
			if (p < 0 || (size_t)p >= P->n) {
				rc = err_set("%s: checkpoint platen contact: particle out of range",
				             h5_name(g));
				break;
			}
			platen_contact *q = &e->bc.pl.pc[k][c];
			memcpy(q->t, pc + 6 * c, sizeof q->t);
			q->kn = pc[6 * c + 3];
			q->ks = pc[6 * c + 4];
			q->cn = pc[6 * c + 5];
			q->u0 = 0;
			P->pslot[k][p] = (int32_t)c;
		}
		if (!rc && n && yade_contacts(e)) {
			snprintf(con, sizeof con, "platen%d_start", k);
			rc = get(g, con, H5T_NATIVE_DOUBLE, pc, n, 0);
			for (size_t c = 0; !rc && c < n; c++)
				e->bc.pl.pc[k][c].u0 = pc[c];
		}
		free(pc);
		if (rc)
			return -1;
	}
	return 0;
}

static int read_surface(hid_t g, engine *e)
{
	surface *S = &e->bc.surf;
	particles *P = &e->p;
	if (S->n > S->cap)
		return err_set("%s: checkpoint surface larger than its bins", h5_name(g));
	if (get(g, "surface_particle", H5T_NATIVE_INT32, S->idx, S->n, 0) ||
	    get(g, "surface_area", H5T_NATIVE_DOUBLE, S->area, S->n, 0))
		return -1;
	for (size_t i = 0; i < P->n; i++)
		P->surf[i] = -1;
	for (size_t k = 0; k < S->n; k++) {
		if (S->idx[k] < 0 || (size_t)S->idx[k] >= P->n)
			return err_set("%s: checkpoint surface particle out of range", h5_name(g));
		P->surf[S->idx[k]] = (int32_t)k;
	}
	return 0;
}

int checkpoint_read_file(engine *e, hid_t f)
{
	char path[1024];
	snprintf(path, sizeof path, "%s", h5_name(f));
	if (!h5_exists(f, "checkpoint"))
		return err_set(
		    "%s: no checkpoint to restart from (the run stopped before its first "
		    "one)",
		    path);
	hid_t g = h5_open_group(f, "checkpoint");
	int64_t complete = 0;
	int rc = h5_read_attr_i64(g, "complete", &complete);
	if (!rc && !complete)
		rc = err_set(
		    "%s: the checkpoint is incomplete (the program was killed while writing "
		    "it)",
		    path);
	size_t count[3] = {0, 0, 0};
	scalar s[64];
	int ns = scalars(e, count, s);
	for (int k = 0; !rc && k < ns; k++) {
		int64_t v;
		if (s[k].d)
			rc = h5_read_attr_f64(g, s[k].name, s[k].d);
		else if (!(rc = h5_read_attr_i64(g, s[k].name, &v))) {
			if (s[k].i)
				*s[k].i = v;
			else if (s[k].n)
				*s[k].n = (int)v;
			else
				*s[k].z = (size_t)v;
		}
	}
	for (int k = 0; k < 2; k++)
		e->bc.pl.ncand[k] = count[1 + k];
	particles *P = &e->p;
	size_t n = P->n, nb = e->pairs.nbonds;
	/* This rank's bonds' rows (ranks.h). Rank 0, whose bonds come first,
	 * reads every bond's after its own and checks the checksum (whose
	 * failure stops every rank), then keeps its own
	 * (ranks_release_output). */
	pairlist *L = &e->pairs.bonds;
	size_t first = e->pairs.bond0, rows = L->n;
	int whole = par_rank() == 0;
	if (whole && rows < nb) {
		L->rec = xrealloc(L->rec, (nb + 1) * sizeof *L->rec);
		L->f = xrealloc(L->f, (3 * nb + 1) * sizeof *L->f);
		memset(L->rec + rows, 0, (nb - rows) * sizeof *L->rec);
		L->cap = rows = nb;
	}
	old_bonds old = {NULL, NULL};
	int is_old = 0;
	int32_t *orig = rc ? NULL : xmalloc((n + 1) * sizeof *orig);
	rc = rc || get(g, "orig", H5T_NATIVE_INT32, orig, n, 0);
	if (!rc && memcmp(orig, P->orig, n * sizeof *orig))
		rc = err_set("%s: the checkpoint's particle order differs from this build's (not "
		             "restartable with this version)",
		             path);
	free(orig);
	if (!rc && (e->prog.stage < 0 || e->prog.stage >= e->cs->nstages))
		rc = err_set("%s: checkpoint stage %d out of range", path, e->prog.stage);
	rc = rc || get(g, "x", H5T_NATIVE_DOUBLE, P->x, n, 3) ||
	     get(g, "v", H5T_NATIVE_DOUBLE, P->v, n, 3) ||
	     get(g, "w", H5T_NATIVE_DOUBLE, P->w, n, 3) ||
	     get(g, "x_ref", H5T_NATIVE_DOUBLE, P->x_ref, n, 3) ||
	     get(g, "flag", H5T_NATIVE_UINT8, P->flag, n, 0) ||
	     get_field(g, &bond_fields[0], L->rec, first, rows, nb) ||
	     get_field(g, &bond_fields[2], L->rec, first, rows, nb) ||
	     read_bond_h_f(g, e, first, rows, nb, &old, &is_old) || read_surface(g, e) ||
	     read_pairs(g, e, count[0]) || read_platens(g, e);
	for (size_t b = 0; !rc && b < rows; b++)
		if (L->rec[b].state > BOND_BROKEN_SHEAR)
			rc = err_set("%s: checkpoint dataset 'bond_state': value %d at row %zu: "
			             "expected a bond state from %d to %d",
			             path, L->rec[b].state, first + b, BOND_INTACT,
			             BOND_BROKEN_SHEAR);
	int64_t sum = 0;
	pairs_view v;
	ranks_own_pairs(e, &v); /* as read: the whole specimen's */
	pairlist all = {.n = nb, .rec = L->rec, .f = L->f, .fcols = 3};
	v.bonds = &all;
	if (!rc && whole &&
	    (h5_read_attr_i64(g, "checksum", &sum) ||
	     sum != state_crc(e, &v, is_old ? &old : NULL)))
		rc = err_set("%s: the checkpoint's data do not match its checksum (damaged, or "
		             "written by an older version): not restartable",
		             path);
	if (!rc) { /* what this rank keeps of the whole specimen's lists */
		contacts_restore(e);
		platens_restore(e);
		ranks_release_output(e);
	}
	free(old.h), free(old.f);
	H5Gclose(g);
	return rc ? -1 : 0;
}

int checkpoint_read(engine *e, const char *path)
{
	hid_t f = h5_open(path, RUN_FORMAT, 0);
	if (f < 0)
		return -1;
	int rc = checkpoint_read_file(e, f);
	H5Fclose(f);
	return rc;
}
