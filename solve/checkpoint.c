/* /checkpoint in run.h5: the evolving engine state, enough to continue bit
 * for bit (solve --restart). What setup rebuilds deterministically from the
 * embedded assembly and the configuration (particle order, masses, bond
 * topology, gauge, frame, time-step bound) is not stored; the particle
 * order is kept only to check that. Layout in share/doc/solve.md. Datasets
 * are extendible and overwritten in place, so repeated checkpoints do not
 * grow the file; the `complete` attribute is 0 while one is being written,
 * and `checksum` (CRC-32 of the state it holds) is compared after a restart
 * has read it back, so damaged checkpoint data is refused, never continued. */
#include <inttypes.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>
#include <zlib.h>

#include "lib/err.h"
#include "lib/h5.h"
#include "solve/checkpoint.h"
#include "solve/contacts.h"
#include "solve/order.h"
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

/* The bonds' histories and forces as a checkpoint held them, read for its
 * checksum: one of an older layout (bond_h with a fourth column, the last
 * u_n, and bond_force with the torque per unit radius), or only the forces
 * of this layout, in the double precision of the file (written from the
 * single precision of pairlist.fb). */
enum { OLD_NHIST = 4, OLD_FCOLS = 6 };
typedef struct {
	double *h; /* [B][OLD_NHIST], or NULL: this layout */
	double *f; /* [B][OLD_FCOLS], or with this layout [rows][3]: this
	              rank's bonds' */
} old_bonds;

/* Whether contacts follow Yade's conventions (laws/material.h): they then
 * keep their start (contact_d0, platen<k>_start), which checkpoints hold
 * and checksum. */
static int yade_contacts(const engine *e) { return e->cs->mat.conventions == CONTACT_YADE; }

/* The checksum covers the state in a fixed order of segments. A rank
 * computes its part of each (crc_parts: its particles, bonds, contacts
 * and platen contacts; the scalars and the surface list on rank 0), and
 * the parts, combined in rank order (crc32_combine), give the checksum of
 * the whole, the same on any number of ranks. */
enum { CRC_SEGMENTS = 17 };
typedef struct {
	uLong crc[CRC_SEGMENTS];
	uint64_t len[CRC_SEGMENTS];
	int k; /* the segment being added to */
} crc_parts;

static void add(crc_parts *p, const void *data, size_t bytes)
{
	p->crc[p->k] = crc32_z(p->crc[p->k], data, bytes);
	p->len[p->k] += bytes;
}

/* The bytes [off, off + bytes) of each of n records of `stride` bytes from
 * base, each followed by its byte of tail when tail is not NULL, in order,
 * as add() of each would: in pieces of about CRC_PIECE bytes, each copied
 * together and checksummed on its own by the threads, then combined in
 * order (crc32_combine). */
enum { CRC_PIECE = 1 << 15 };
static void add_records(crc_parts *p, const void *base, size_t n, size_t stride, size_t off,
                        size_t bytes, const uint8_t *tail, int team)
{
	size_t row = bytes + (tail != NULL);
	size_t per = CRC_PIECE / row > 0 ? CRC_PIECE / row : 1;
	size_t pieces = (n + per - 1) / per;
	uLong *crc = xmalloc((pieces + 1) * sizeof *crc);
#define PIECE_ITEMS(k) (n - (k)*per < per ? n - (k)*per : per)
#pragma omp parallel num_threads(team)
	{
		unsigned char *buf = stride == row && !tail ? NULL : xmalloc(per * row);
#pragma omp for schedule(static)
		for (size_t k = 0; k < pieces; k++) {
			const unsigned char *r =
			    (const unsigned char *)base + k * per * stride + off;
			size_t m = PIECE_ITEMS(k);
			for (size_t q = 0; buf && q < m; q++) {
				memcpy(buf + q * row, r + q * stride, bytes);
				if (tail)
					buf[q * row + bytes] = tail[k * per + q];
			}
			crc[k] = crc32_z(0, buf ? buf : r, m * row);
		}
		free(buf);
	}
	for (size_t k = 0; k < pieces; k++) {
		z_off_t len = (z_off_t)(PIECE_ITEMS(k) * row);
		p->crc[p->k] = crc32_combine(p->crc[p->k], crc[k], len);
		p->len[p->k] += (uint64_t)len;
	}
#undef PIECE_ITEMS
	free(crc);
}

/* add() of n contiguous items of `bytes` bytes (add_records). */
static void add_array(crc_parts *p, const void *data, size_t n, size_t bytes, int team)
{
	add_records(p, data, n, bytes, 0, bytes, NULL, team);
}

/* Rows [k0, k0 + m) of three floats (ctx) as doubles, into buf: the values
 * a checkpoint holds of the bonds' forces (a ranks_fill, ranks.h). */
static void from_floats(void *ctx, size_t k0, size_t m, void *buf)
{
	const float *f = (const float *)ctx + 3 * k0;
	for (size_t k = 0; k < 3 * m; k++)
		((double *)buf)[k] = f[k];
}

/* add() of the rows of three floats from f as the checkpoint holds them
 * (from_floats), a piece at a time. */
static void add_widened(crc_parts *p, float *f, size_t rows)
{
	enum { ROWS = CRC_PIECE / (3 * sizeof(double)) };
	double buf[3 * ROWS];
	for (size_t r0 = 0; r0 < rows; r0 += ROWS) {
		size_t m = rows - r0 < ROWS ? rows - r0 : ROWS;
		from_floats(f, r0, m, buf);
		add(p, buf, 3 * m * sizeof *buf);
	}
}

/* Bonds (contacts 0) or contacts: the records' histories and states (ends,
 * their indices in the whole specimen, and histories), then the forces
 * (the constants, and with Yade's conventions the starts); three
 * segments. old: when not NULL, the bonds' h and f as a checkpoint held
 * them (old_bonds); else the forces the bonds keep, as a checkpoint holds
 * them. */
_Static_assert(offsetof(pair_rec, h) == offsetof(pair_rec, t) + 3 * sizeof(double),
               "pair_rec: t and h follow each other, as a bond's checksum takes them");
static void pairs_crc(crc_parts *p, const particles *P, const pairlist *l, int contacts, int yade,
                      const old_bonds *old, int team)
{
	if (contacts) {
		for (size_t b = 0; b < l->n; b++) {
			const pair_rec *r = &l->rec[b];
			int32_t ends[2] = {(int32_t)particle_global(P, (size_t)r->i),
			                   (int32_t)particle_global(P, (size_t)r->j)};
			add(p, ends, sizeof ends);
			add(p, r->t, sizeof r->t);
		}
	} else if (old && old->h) {
		for (size_t b = 0; b < l->n; b++) {
			add(p, l->rec[b].t, sizeof l->rec[b].t);
			add(p, old->h + OLD_NHIST * b, OLD_NHIST * sizeof *old->h);
			add(p, &l->state[b], sizeof *l->state);
		}
	} else { /* t, h and the state, as when the state ended the record */
		add_records(p, l->rec, l->n, sizeof *l->rec, offsetof(pair_rec, t),
		            (3 + LAW_NHIST) * sizeof(double), l->state, team);
	}
	p->k++;
	if (contacts) { /* their constants, as the contiguous rows of contact_k */
		add_records(p, l->rec, l->n, sizeof *l->rec, offsetof(pair_rec, h),
		            3 * sizeof(double), NULL, team);
		p->k++;
		if (yade)
			add_records(p, l->rec, l->n, sizeof *l->rec, offsetof(pair_rec, d0),
			            sizeof(double), NULL, team);
	} else if (old) {
		add(p, old->f, (old->h ? OLD_FCOLS : 3) * l->n * sizeof *old->f);
	} else {
		add_widened(p, l->fb, l->n);
	}
	p->k++;
}

/* This rank's parts: the lists of v and the particles [p0, p1); head: the
 * scalars (with the whole specimen's counts) and the surface list too. */
static void crc_of(engine *e, const pairs_view *v, size_t p0, size_t p1, size_t count[3], int head,
                   const old_bonds *old, crc_parts *p)
{
	memset(p, 0, sizeof *p);
	scalar s[64];
	int ns = head ? scalars(e, count, s) : 0;
	for (int k = 0; k < ns; k++) {
		int64_t v = s[k].i ? *s[k].i : s[k].n ? *s[k].n : s[k].z ? (int64_t)*s[k].z : 0;
		if (s[k].d)
			add(p, s[k].d, sizeof *s[k].d);
		else
			add(p, &v, sizeof v);
	}
	p->k++;
	const particles *P = &e->p;
	size_t n = p1 - p0;
	add_array(p, P->orig + p0, n, sizeof *P->orig, e->team);
	p->k++;
	const double *vec[] = {P->x + 3 * p0, P->v + 3 * p0, P->w + 3 * p0,
	                       P->x_ref + 3 * (p0 - P->own0)};
	for (int k = 0; k < 4; k++, p->k++)
		add_array(p, vec[k], 3 * n, sizeof *vec[k], e->team);
	add(p, P->flag + p0, n * sizeof *P->flag);
	p->k++;
	if (head) {
		add(p, e->bc.surf.idx, e->bc.surf.n * sizeof *e->bc.surf.idx);
		add(p, e->bc.surf.area, e->bc.surf.n * sizeof *e->bc.surf.area);
	}
	p->k++;
	pairs_crc(p, P, v->bonds, 0, 0, old, e->team);
	pairs_crc(p, P, v->contacts, 1, yade_contacts(e), NULL, e->team);
	for (int k = 0; k < 2; k++) {
		add(p, v->who[k], v->ncand[k] * sizeof *v->who[k]);
		p->k++;
		for (size_t q = 0; q < v->ncand[k]; q++)
			add(p, &v->pc[k][q],
			    yade_contacts(e) ? sizeof v->pc[k][q] : offsetof(platen_contact, u0));
		p->k++;
	}
}

/* The parts of n ranks ([n], in rank order) combined. */
static int64_t crc_combine(const crc_parts *p, int n)
{
	uLong c = crc32_z(0, Z_NULL, 0);
	for (int k = 0; k < CRC_SEGMENTS; k++)
		for (int q = 0; q < n; q++)
			c = crc32_combine(c, p[q].crc[k], (z_off_t)p[q].len[k]);
	return (int64_t)c;
}

/* Every rank's parts, in rank order, into all on rank 0. Collective. */
static void gather_parts(const crc_parts *mine, crc_parts *all)
{
	_Static_assert(sizeof *mine % sizeof(uint64_t) == 0 && sizeof(uLong) == sizeof(uint64_t),
	               "crc_parts: 64-bit words");
	ranks_gather_u64((const uint64_t *)mine, sizeof *mine / sizeof(uint64_t), (uint64_t *)all);
}

/* Whether dataset d has exactly n rows of cols columns (0: one-dimensional). */
static int shape_is(hid_t d, size_t n, size_t cols)
{
	hid_t sp = H5Dget_space(d);
	hsize_t dims[2] = {0, 0};
	int rank = H5Sget_simple_extent_ndims(sp);
	if (rank == (cols ? 2 : 1)) /* dims holds no more */
		H5Sget_simple_extent_dims(sp, dims, NULL);
	H5Sclose(sp);
	return rank == (cols ? 2 : 1) && dims[0] == n && (!cols || dims[1] == cols);
}

/* Open a dataset of rows x cols (cols 0: rank 1) for overwriting: the one
 * there if of that shape, else a new one (chunked), never one resized: in
 * a file several ranks write (parallel HDF5 1.10.8), shrinking a dataset
 * that rank 0 alone then writes (the surface list) made the other ranks
 * put its former rows back, so that a recovery copy held the previous
 * checkpoint's list and failed its checksum. */
static hid_t open_put(hid_t g, const char *name, hid_t type, size_t rows, size_t cols)
{
	if (h5_exists(g, name)) {
		hid_t d = H5Dopen2(g, name, H5P_DEFAULT);
		if (d >= 0 && shape_is(d, rows, cols))
			return d;
		if (d >= 0)
			H5Dclose(d);
		if (d < 0 || H5Ldelete(g, name, H5P_DEFAULT) < 0)
			return h5_write_dataset_error(g, name);
	}
	int rank = cols ? 2 : 1;
	hsize_t dims[2] = {rows, cols}, maxd[2] = {H5S_UNLIMITED, cols};
	hid_t sp = H5Screate_simple(rank, dims, maxd);
	hid_t pl = H5Pcreate(H5P_DATASET_CREATE);
	/* Chunks of at most one piece: HDF5 buffers a whole chunk. */
	size_t most = H5_PIECE_ELEMENTS / (cols ? cols : 1);
	hsize_t chunk[2] = {rows > most ? most : rows ? rows : 1, cols ? cols : 1};
	H5Pset_chunk(pl, rank, chunk);
	hid_t d = H5Dcreate2(g, name, type, sp, H5P_DEFAULT, pl, H5P_DEFAULT);
	H5Pclose(pl);
	H5Sclose(sp);
	if (d < 0)
		h5_write_dataset_error(g, name);
	return d;
}

/* Write or overwrite a whole dataset that every rank holds: rank 0's. */
static int put(hid_t g, const char *name, hid_t type, const void *data, size_t rows, size_t cols)
{
	hid_t d = open_put(g, name, type, rows, cols);
	if (d < 0)
		return -1;
	h5_settle(d); /* rank 0 alone looks up the chunks */
	int rc = rows && par_rank() == 0 ? h5_slab(d, type, 0, rows, cols, (void *)data, 1) : 0;
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

/* Open dataset `name` of g, which must have exactly n rows of cols columns
 * (0: one-dimensional), or -1 with the error set. */
static hid_t open_rows(hid_t g, const char *name, size_t n, size_t cols)
{
	if (!h5_exists(g, name))
		return err_set("%s: checkpoint dataset '%s': missing", h5_name(g), name);
	hid_t d = H5Dopen2(g, name, H5P_DEFAULT);
	if (!shape_is(d, n, cols)) {
		H5Dclose(d);
		return err_set("%s: checkpoint dataset '%s': wrong shape (expected %zu rows)",
		               h5_name(g), name, n);
	}
	if (!h5_stored_holds(d, (double)n * (double)(cols ? cols : 1))) {
		H5Dclose(d);
		return err_set("%s: checkpoint dataset '%s': %zu rows, more than the file holds (a "
		               "damaged file)",
		               h5_name(g), name, n);
	}
	return d;
}

/* Rows [first, first + rows) of one field of n records (the dataset must
 * have exactly n rows) into rec[0 .. rows). */
static int get_field(hid_t g, const field *f, pair_rec *rec, size_t first, size_t rows, size_t n)
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
 * values of the type into dst. */
static int get_rows(hid_t g, const char *name, hid_t type, void *dst, size_t first, size_t rows,
                    size_t n, size_t cols)
{
	hid_t d = open_rows(g, name, n, cols);
	if (d < 0)
		return -1;
	herr_t rc = rows ? h5_slab(d, type, first, rows, cols, dst, 0) : 0;
	H5Dclose(d);
	if (rc < 0)
		return err_set("%s: checkpoint dataset '%s': unreadable", h5_name(g), name);
	return 0;
}

#define FIELD(name, type, member, cols)                       \
	{                                                     \
		name, type, offsetof(pair_rec, member), cols, \
		    sizeof(((pair_rec *)0)->member) / (cols)  \
	}

/* And the bonds' states, an array (bond_state). */
static const field bond_fields[] = {
    FIELD("bond_t", T_F64, t, 3),
    FIELD("bond_h", T_F64, h, LAW_NHIST),
};
static const field contact_fields[] = {
    FIELD("contact_i", T_I32, i, 1),
    FIELD("contact_j", T_I32, j, 1),
    FIELD("contact_t", T_F64, t, 3),
    FIELD("contact_k", T_F64, h, 3),
};
/* With Yade's conventions only. */
static const field contact_start = FIELD("contact_d0", T_F64, d0, 1);

/* What a rank writes of a checkpoint dataset: rows of an array, or a
 * field of records, or its platen contacts (ranks_fill). */
typedef struct {
	const void *base;
	size_t row;
} array_rows;

static void from_array(void *ctx, size_t k0, size_t m, void *buf)
{
	const array_rows *a = ctx;
	memcpy(buf, (const unsigned char *)a->base + k0 * a->row, m * a->row);
}

typedef struct {
	const field *f;
	const pair_rec *rec;
	const particles *P; /* for a contact's end: its index in the whole
	                       specimen written; else NULL */
} field_rows;

static void from_field(void *ctx, size_t k0, size_t m, void *buf)
{
	const field_rows *r = ctx;
	size_t row = r->f->cols * r->f->size;
	for (size_t k = 0; k < m; k++) {
		const unsigned char *src = (const unsigned char *)&r->rec[k0 + k] + r->f->offset;
		unsigned char *dst = (unsigned char *)buf + k * row;
		if (r->P) {
			int32_t end;
			memcpy(&end, src, sizeof end);
			end = (int32_t)particle_global(r->P, (size_t)end);
			memcpy(dst, &end, sizeof end);
		} else {
			memcpy(dst, src, row);
		}
	}
}

/* A platen's contacts: t, kn, ks, cn (6 columns), or u0 (one). */
typedef struct {
	const platen_contact *pc;
	int start;
} platen_rows;

static void from_platen(void *ctx, size_t k0, size_t m, void *buf)
{
	const platen_rows *r = ctx;
	double *o = buf;
	for (size_t c = 0; c < m; c++) {
		const platen_contact *p = &r->pc[k0 + c];
		if (r->start) {
			o[c] = p->u0;
			continue;
		}
		double v[6] = {p->t[0], p->t[1], p->t[2], p->kn, p->ks, p->cn};
		memcpy(o + 6 * c, v, sizeof v);
	}
}

/* Dataset `name` of g from every rank's rows, in rank order (this rank's
 * `mine`, from fill), each rank writing its own. Collective. */
static int put_rows(engine *e, hid_t g, const char *name, hid_t type, size_t cols, size_t mine,
                    ranks_fill fill, void *ctx)
{
	hid_t d = open_put(g, name, type, ranks_total(mine), cols);
	if (d < 0)
		return -1;
	int rc = ranks_rows_put(e, d, type, cols, mine, fill, ctx);
	H5Dclose(d);
	return rc ? h5_write_dataset_error(g, name) : 0;
}

static int put_field_rows(engine *e, hid_t g, const field *f, const pairlist *l)
{
	int end = f == &contact_fields[0] || f == &contact_fields[1];
	field_rows r = {f, l->rec, end ? &e->p : NULL};
	return put_rows(e, g, f->name, h5type(f->type), f->cols > 1 ? f->cols : 0, l->n, from_field,
	                &r);
}

static int put_array(engine *e, hid_t g, const char *name, hid_t type, size_t cols,
                     const void *base, size_t mine)
{
	array_rows a = {base, (cols ? cols : 1) * H5Tget_size(type)};
	return put_rows(e, g, name, type, cols, mine, from_array, &a);
}

/* This rank's part of the whole specimen's lists: its bonds, the contacts
 * of its particles i (after those of earlier ranks' i in its list), its
 * platen contacts. */
static void own_part(const engine *e, pairs_view *v, pairlist *contacts)
{
	ranks_own_pairs(e, v);
	const pairlist *C = &e->pairs.contacts;
	size_t c0 = e->scratch.cfirst[e->ranks.blk0], c1 = e->scratch.cfirst[e->ranks.blk1];
	*contacts = (pairlist){.n = c1 - c0, .rec = C->rec + c0, .f = C->f + 6 * c0};
	v->contacts = contacts;
}

int checkpoint_write(engine *e, hid_t file)
{
	/* On several ranks every rank writes its own rows into the file they
	 * share (parallel HDF5), and rank 0's scalars. A failure on any rank
	 * ends the run (fatal), so the others need not be told. */
	int head = par_rank() == 0, rc = 0;
	hid_t g = h5_exists(file, "checkpoint") ? h5_open_group(file, "checkpoint")
	                                        : h5_group(file, "checkpoint");
	if (g < 0 || h5_attr_i64(g, "complete", 0)) {
		if (g >= 0)
			H5Gclose(g);
		return -1;
	}
	bonds_output_forces(e);
	pairs_view v;
	pairlist contacts;
	own_part(e, &v, &contacts);
	size_t count[3] = {ranks_total(v.contacts->n), ranks_total(v.ncand[0]),
	                   ranks_total(v.ncand[1])};
	scalar s[64];
	int ns = scalars(e, count, s);
	for (int k = 0; !rc && k < ns; k++)
		rc = s[k].d   ? h5_attr_f64(g, s[k].name, *s[k].d)
		     : s[k].i ? h5_attr_i64(g, s[k].name, *s[k].i)
		     : s[k].n ? h5_attr_i64(g, s[k].name, *s[k].n)
		              : h5_attr_i64(g, s[k].name, (int64_t)*s[k].z);
	const particles *P = &e->p;
	size_t p0, p1;
	ranks_own(e, &p0, &p1);
	rc = rc || put_array(e, g, "orig", H5T_NATIVE_INT32, 0, P->orig + p0, p1 - p0);
	const char *vn[] = {"x", "v", "w", "x_ref"};
	const double *vec[] = {P->x + 3 * p0, P->v + 3 * p0, P->w + 3 * p0,
	                       P->x_ref + 3 * (p0 - P->own0)};
	for (int k = 0; k < 4; k++)
		rc = rc || put_array(e, g, vn[k], H5T_NATIVE_DOUBLE, 3, vec[k], p1 - p0);
	/* Every rank holds the whole surface list. */
	rc = rc || put_array(e, g, "flag", H5T_NATIVE_UINT8, 0, P->flag + p0, p1 - p0) ||
	     put(g, "surface_particle", H5T_NATIVE_INT32, e->bc.surf.idx, e->bc.surf.n, 0) ||
	     put(g, "surface_area", H5T_NATIVE_DOUBLE, e->bc.surf.area, e->bc.surf.n, 0);
	for (int k = 0; k < 2; k++)
		rc = rc || put_field_rows(e, g, &bond_fields[k], v.bonds);
	rc = rc || put_array(e, g, "bond_state", H5T_NATIVE_UINT8, 0, v.bonds->state, v.bonds->n);
	rc = rc || put_rows(e, g, "bond_force", H5T_NATIVE_DOUBLE, 3, v.bonds->n, from_floats,
	                    v.bonds->fb);
	for (int k = 0; k < 4; k++)
		rc = rc || put_field_rows(e, g, &contact_fields[k], v.contacts);
	if (yade_contacts(e))
		rc = rc || put_field_rows(e, g, &contact_start, v.contacts);
	for (int k = 0; k < 2; k++) {
		char name[32];
		snprintf(name, sizeof name, "platen%d_particle", k);
		rc = rc || put_array(e, g, name, H5T_NATIVE_INT32, 0, v.who[k], v.ncand[k]);
		platen_rows r = {v.pc[k], 0};
		snprintf(name, sizeof name, "platen%d_contact", k);
		rc = rc || put_rows(e, g, name, H5T_NATIVE_DOUBLE, 6, v.ncand[k], from_platen, &r);
		r.start = 1;
		snprintf(name, sizeof name, "platen%d_start", k);
		if (yade_contacts(e))
			rc = rc || put_rows(e, g, name, H5T_NATIVE_DOUBLE, 0, v.ncand[k],
			                    from_platen, &r);
	}
	/* The checksum: each rank's parts, combined on rank 0 (whose value
	 * the attribute takes). */
	crc_parts mine, *all = head ? xmalloc((size_t)par_size() * sizeof *all) : NULL;
	crc_of(e, &v, p0, p1, count, head, NULL, &mine);
	gather_parts(&mine, all);
	rc = rc || h5_attr_i64(g, "checksum", head ? crc_combine(all, par_size()) : 0) ||
	     h5_attr_i64(g, "order_walk", e->plain_order ? 0 : ORDER_WALK) ||
	     h5_attr_i64(g, "complete", 1);
	H5Gclose(g);
	if (!rc && H5Fflush(file, H5F_SCOPE_GLOBAL) < 0)
		rc = h5_write_error(h5_name(file), "the checkpoint");
	free(all);
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

/* The bonds' histories (bond_h), and in *old the forces on i (bond_force)
 * as the file held them, for the checksum only (the engine computes the
 * bonds' forces again when an output needs them: bonds_output_forces):
 * this rank's rows of the forces, or an older checkpoint's arrays whole
 * (*is_old set). That holds a fourth
 * history column, the last u_n, in the slot the law names
 * (law.h_dropped), and the torque per unit radius after each force. */
static int read_bond_h_f(hid_t g, const engine *e, size_t first, size_t rows, size_t nb,
                         old_bonds *old, int *is_old)
{
	const pairlist *L = &e->pairs.bonds;
	*is_old = columns(g, "bond_h") == OLD_NHIST;
	if (*is_old) {
		if (h5_read_n(g, "bond_h", H5T_NATIVE_DOUBLE, (void **)&old->h, nb, OLD_NHIST) ||
		    h5_read_n(g, "bond_force", H5T_NATIVE_DOUBLE, (void **)&old->f, nb, OLD_FCOLS))
			return -1;
		for (size_t r = 0; r < rows; r++)
			for (int c = 0, k = 0; c < OLD_NHIST; c++)
				if (c != e->law->h_dropped)
					L->rec[r].h[k++] =
					    old->h[OLD_NHIST * (first + r) + (size_t)c];
	} else {
		old->f = xmalloc((3 * rows + 1) * sizeof *old->f);
		if (get_field(g, &bond_fields[1], L->rec, first, rows, nb) ||
		    get_rows(g, "bond_force", H5T_NATIVE_DOUBLE, old->f, first, rows, nb, 3))
			return -1;
	}
	return 0;
}

/* The first of the rows [lo, hi) of the sorted column contact_i (open as
 * d) whose particle is at least p (hi if none). */
static size_t first_contact_of(hid_t d, size_t lo, size_t hi, size_t p, int *rc)
{
	while (lo < hi && !*rc) {
		size_t mid = lo + (hi - lo) / 2;
		int32_t i;
		*rc = h5_slab(d, H5T_NATIVE_INT32, mid, 1, 0, &i, 0);
		if ((size_t)i < p)
			lo = mid + 1;
		else
			hi = mid;
	}
	return lo;
}

/* The checkpoint's nc contacts with an end of this rank's own, in the
 * file's order, which is that of their i: first those of earlier ranks' i
 * (sent by their ranks), then those of its own (a run of the file, read in
 * pieces). Their ends are indices in the whole specimen, and with the
 * engine's conventions their d0 is not set yet (hold_contacts). */
static int read_pairs(hid_t g, engine *e, size_t nc)
{
	pairlist *L = &e->pairs.contacts;
	size_t p0, p1, c0 = 0, c1 = nc;
	int split = ranks_own(e, &p0, &p1) && e->ranks.size > 1, rc = 0;
	/* nc, a count from the file, sizes the list only once the file is seen
	 * to hold that many contacts (open_rows). */
	hid_t d = open_rows(g, contact_fields[0].name, nc, 0);
	if (d < 0)
		return -1;
	if (split) {
		c0 = first_contact_of(d, 0, nc, p0, &rc);
		c1 = first_contact_of(d, c0, nc, p1, &rc);
	}
	H5Dclose(d);
	if (rc)
		return err_set("%s: checkpoint dataset 'contact_i': unreadable", h5_name(g));
	L->n = 0;
	if (c1 - c0 > L->cap || !L->rec) { /* none yet at a restart (engine_opts) */
		L->cap = c1 - c0;
		L->rec = pairlist_records(L->rec, 0, L->cap);
	}
	for (size_t at = c0; !rc && at < c1; at += PIECE) {
		size_t m = c1 - at < PIECE ? c1 - at : PIECE;
		pair_rec *piece = L->rec + (at - c0);
		memset(piece, 0, m * sizeof *piece);
		for (int k = 0; !rc && k < 4; k++)
			rc = get_field(g, &contact_fields[k], piece, at, m, nc);
		if (!rc && yade_contacts(e))
			rc = get_field(g, &contact_start, piece, at, m, nc);
		for (size_t q = 0; !rc && q < m; q++) {
			pair_rec *b = &piece[q];
			size_t i = (size_t)b->i, j = (size_t)b->j;
			if (b->i < 0 || b->j < 0 || i >= e->p.n || j >= e->p.n)
				rc = err_set("%s: checkpoint contact %zu: particle out of range",
				             h5_name(g), at + q);
			else if (i < p0 || i >= p1 || (q + at > c0 && b->i < b[-1].i))
				rc = err_set(
				    "%s: checkpoint contact %zu: not in the order of its first "
				    "particle",
				    h5_name(g), at + q);
		}
	}
	if (rc)
		return -1;
	L->n = c1 - c0;
	if (split) { /* those of earlier ranks' i with an own j first */
		pair_rec *in;
		size_t m = ranks_share_pairs(e, L->rec, L->n, &in);
		if (L->n + m > L->cap) {
			L->cap = L->n + m;
			L->rec = pairlist_records(L->rec, L->n, L->cap);
		}
		memmove(L->rec + m, L->rec, L->n * sizeof *L->rec);
		memcpy(L->rec, in, m * sizeof *in);
		L->n += m;
		free(in);
	}
	L->f = xrealloc(L->f, 6 * (L->cap + 1) * sizeof *L->f);
	L->ref = xrealloc(L->ref, 2 * (L->cap + 1) * sizeof *L->ref);
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
	if (S->n > P->n)
		return err_set("%s: checkpoint surface larger than the specimen", h5_name(g));
	if (S->n > S->cap)
		surface_room(S, S->n);
	if (get(g, "surface_particle", H5T_NATIVE_INT32, S->idx, S->n, 0) ||
	    get(g, "surface_area", H5T_NATIVE_DOUBLE, S->area, S->n, 0))
		return -1;
	size_t p0, p1;
	ranks_own(e, &p0, &p1);
	for (size_t i = P->lo; i < P->hi; i++)
		P->surf[i] = -1;
	for (size_t k = 0; k < S->n; k++) {
		size_t i = (size_t)S->idx[k];
		if (S->idx[k] < 0 || i >= P->n)
			return err_set("%s: checkpoint surface particle out of range", h5_name(g));
		if (i >= p0 && i < p1)
			P->surf[i] = (int32_t)k;
	}
	return 0;
}

/* The particles [a, a + m) of the window, the other ranks': their rows of
 * the checkpoint (index in the assembly, x, v, ω, flags), their radii from
 * the run file's assembly and their masses. */
static int read_others(hid_t g, hid_t f, engine *e, size_t a, size_t m)
{
	particles *P = &e->p;
	const int32_t *rows = P->glob + a;
	struct {
		const char *name;
		hid_t type;
		size_t cols;
		void *dst;
	} get[] = {{"orig", H5T_NATIVE_INT32, 0, P->orig + a},
	           {"x", H5T_NATIVE_DOUBLE, 3, P->x + 3 * a},
	           {"v", H5T_NATIVE_DOUBLE, 3, P->v + 3 * a},
	           {"w", H5T_NATIVE_DOUBLE, 3, P->w + 3 * a},
	           {"flag", H5T_NATIVE_UINT8, 0, P->flag + a}};
	for (size_t k = 0; k < sizeof get / sizeof get[0]; k++) {
		hid_t d = open_rows(g, get[k].name, P->n, get[k].cols);
		if (d < 0)
			return -1;
		int rc = h5_rows_at(d, get[k].type, rows, m, get[k].cols, get[k].dst);
		H5Dclose(d);
		if (rc)
			return err_set("%s: checkpoint dataset '%s': unreadable", h5_name(g),
			               get[k].name);
	}
	for (size_t i = a; i < a + m; i++)
		if (P->orig[i] < 0 || (size_t)P->orig[i] >= P->n)
			return err_set(
			    "%s: checkpoint dataset 'orig': value %d at row %d: expected an "
			    "index in the assembly below %zu",
			    h5_name(g), P->orig[i], P->glob[i], P->n);
	hid_t d = H5Dopen2(f, "particles/r", H5P_DEFAULT);
	int rc = d < 0 || h5_rows_at(d, H5T_NATIVE_DOUBLE, P->orig + a, m, 0, P->r + a);
	if (d >= 0)
		H5Dclose(d);
	if (rc)
		return err_set("%s: dataset '/particles/r': unreadable", h5_name(f));
	for (size_t i = a; i < a + m; i++)
		P->m[i] = particle_mass(e->cs->mat.density, P->r[i]);
	return 0;
}

/* The window made to hold the contacts' ends (window.h), the other ranks'
 * particles read, the contacts' ends renumbered and, with the engine's
 * conventions, their d0 (r_i + r_j) set. */
static int hold_contacts(hid_t g, hid_t f, engine *e)
{
	particles *P = &e->p;
	if (P->glob) {
		window_hold_contacts(e);
		if (read_others(g, f, e, P->lo, P->own0 - P->lo) ||
		    read_others(g, f, e, P->own1, P->hi - P->own1))
			return -1;
	}
	pairlist *L = &e->pairs.contacts;
	for (size_t c = 0; !yade_contacts(e) && c < L->n; c++)
		L->rec[c].d0 = P->r[L->rec[c].i] + P->r[L->rec[c].j];
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
	size_t n = P->n, nb = e->pairs.nbonds, p0, p1;
	ranks_own(e, &p0, &p1);
	size_t own = p1 - p0;
	/* This rank's bonds' rows (ranks.h). */
	pairlist *L = &e->pairs.bonds;
	size_t first = e->pairs.bond0, rows = L->n;
	old_bonds old = {NULL, NULL};
	int is_old = 0;
	/* Each rank checks the order of its own particles. */
	int32_t *orig = rc ? NULL : xmalloc((own + 1) * sizeof *orig);
	rc = rc || get_rows(g, "orig", H5T_NATIVE_INT32, orig, p0, own, n, 0);
	if (!rc && memcmp(orig, P->orig + p0, own * sizeof *orig))
		rc = err_set("%s: the checkpoint's particle order differs from this build's (not "
		             "restartable with this version)",
		             path);
	free(orig);
	if (!rc && (e->prog.stage < 0 || e->prog.stage >= e->cs->nstages))
		rc = err_set("%s: checkpoint stage %d out of range", path, e->prog.stage);
	rc = rc || get_rows(g, "x", H5T_NATIVE_DOUBLE, P->x + 3 * p0, p0, own, n, 3) ||
	     get_rows(g, "v", H5T_NATIVE_DOUBLE, P->v + 3 * p0, p0, own, n, 3) ||
	     get_rows(g, "w", H5T_NATIVE_DOUBLE, P->w + 3 * p0, p0, own, n, 3) ||
	     get_rows(g, "x_ref", H5T_NATIVE_DOUBLE, P->x_ref, p0, own, n, 3) ||
	     get_rows(g, "flag", H5T_NATIVE_UINT8, P->flag + p0, p0, own, n, 0) ||
	     get_field(g, &bond_fields[0], L->rec, first, rows, nb) ||
	     get_rows(g, "bond_state", H5T_NATIVE_UINT8, L->state, first, rows, nb, 0) ||
	     read_bond_h_f(g, e, first, rows, nb, &old, &is_old) || read_surface(g, e) ||
	     read_pairs(g, e, count[0]) || read_platens(g, e) || hold_contacts(g, f, e);
	for (size_t b = 0; !rc && b < rows; b++)
		if (L->state[b] > BOND_BROKEN_SHEAR)
			rc = err_set("%s: checkpoint dataset 'bond_state': value %d at row %zu: "
			             "expected a bond state from %d to %d",
			             path, L->state[b], first + b, BOND_INTACT, BOND_BROKEN_SHEAR);
	/* The checksum: the parts of each rank's particles, bonds and
	 * contacts (those of its own i, after the others in its list), and of
	 * the rest on rank 0 (the platen contacts, which every rank reads
	 * whole), combined on rank 0, whose failure stops every rank. */
	int head = par_rank() == 0;
	pairs_view v;
	ranks_own_pairs(e, &v);
	const pairlist *C = &e->pairs.contacts;
	size_t c0 = 0;
	while (c0 < C->n && (size_t)C->rec[c0].i < p0)
		c0++;
	pairlist contacts = {.n = C->n - c0, .rec = C->rec + c0, .f = C->f ? C->f + 6 * c0 : NULL};
	v.contacts = &contacts;
	if (!head)
		v.ncand[0] = v.ncand[1] = 0;
	old_bonds own_old = old;
	if (is_old && !rc) /* old's arrays are read */
		own_old = (old_bonds){old.h + OLD_NHIST * first, old.f + OLD_FCOLS * first};
	crc_parts mine, *all = head ? xmalloc((size_t)par_size() * sizeof *all) : NULL;
	if (!rc) {
		crc_of(e, &v, p0, p1, count, head, &own_old, &mine);
		gather_parts(&mine, all);
	}
	int64_t sum = 0;
	if (!rc && head &&
	    (h5_read_attr_i64(g, "checksum", &sum) || sum != crc_combine(all, par_size())))
		rc = err_set("%s: the checkpoint's data do not match its checksum (damaged, or "
		             "written by an older version): not restartable",
		             path);
	free(all);
	if (!rc) { /* what this rank keeps of the whole specimen's lists */
		bonds_restore(e);
		contacts_restore(e);
		platens_restore(e);
	}
	free(old.h), free(old.f);
	H5Gclose(g);
	return rc ? -1 : 0;
}

int checkpoint_plain_order(const char *path, int *plain)
{
	hid_t f = h5_open(path, RUN_FORMAT, 0);
	if (f < 0)
		return -1;
	int64_t walk = 0;
	int rc = 0;
	if (h5_exists(f, "checkpoint")) {
		hid_t g = h5_open_group(f, "checkpoint");
		rc = g < 0 ||
		     (H5Aexists(g, "order_walk") > 0 && h5_read_attr_i64(g, "order_walk", &walk));
		if (g >= 0)
			H5Gclose(g);
	}
	H5Fclose(f);
	if (!rc && walk != 0 && walk != ORDER_WALK)
		rc = err_set("%s: checkpoint attribute 'order_walk': value %" PRId64
		             ": expected 0 or %d (a checkpoint of another version of solve)",
		             path, walk, ORDER_WALK);
	*plain = !walk;
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
