#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "lib/assembly.h"
#include "lib/err.h"
#include "lib/h5.h"

static int write_geometry(hid_t file, const dem_geometry *g)
{
	hid_t h = h5_group(file, "geometry");
	if (h < 0)
		return -1;
	int rc = h5_attr_str(h, "shape", g->shape) || h5_attr_str(h, "source", g->source) ||
	         h5_attr_f64v(h, "center", g->center, 3) || h5_attr_f64v(h, "axis", g->axis, 3) ||
	         h5_attr_f64(h, "diameter", g->diameter) || h5_attr_f64(h, "height", g->height) ||
	         h5_attr_f64v(h, "size", g->size, 3) ||
	         h5_attr_f64v(h, "bbox_min", g->bbox_min, 3) ||
	         h5_attr_f64v(h, "bbox_max", g->bbox_max, 3) ||
	         h5_attr_f64(h, "volume", g->volume) || h5_attr_f64(h, "area", g->area) ||
	         h5_write(h, "vertices", H5T_NATIVE_DOUBLE, g->vert, g->nvert, 3, "m") ||
	         h5_write(h, "triangles", H5T_NATIVE_INT32, g->tri, g->ntri, 3, NULL) ||
	         h5_index(h, "vertex", g->nvert, 0) || h5_index(h, "triangle", g->ntri, 0) ||
	         h5_index(h, "xyz", 3, 0) || h5_index(h, "corner", 3, 0) ||
	         h5_attach(h, "vertices", (const char *[]){"vertex", "xyz"}, 2) ||
	         h5_attach(h, "triangles", (const char *[]){"triangle", "corner"}, 2);
	H5Gclose(h);
	return rc ? -1 : 0;
}

static int read_string_attr(hid_t h, const char *name, char *out, size_t n)
{
	char *s = h5_read_attr_str(h, name);
	if (!s)
		return -1;
	snprintf(out, n, "%s", s);
	free(s);
	return 0;
}

static int read_geometry(hid_t file, dem_geometry *g)
{
	hid_t h = h5_open_group(file, "geometry");
	if (h < 0)
		return -1;
	int rc =
	    read_string_attr(h, "shape", g->shape, sizeof g->shape) ||
	    read_string_attr(h, "source", g->source, sizeof g->source) ||
	    h5_read_attr_f64v(h, "center", g->center, 3) ||
	    h5_read_attr_f64v(h, "axis", g->axis, 3) ||
	    h5_read_attr_f64(h, "diameter", &g->diameter) ||
	    h5_read_attr_f64(h, "height", &g->height) || h5_read_attr_f64v(h, "size", g->size, 3) ||
	    h5_read_attr_f64v(h, "bbox_min", g->bbox_min, 3) ||
	    h5_read_attr_f64v(h, "bbox_max", g->bbox_max, 3) ||
	    h5_read_attr_f64(h, "volume", &g->volume) || h5_read_attr_f64(h, "area", &g->area) ||
	    h5_read(h, "vertices", H5T_NATIVE_DOUBLE, (void **)&g->vert, &g->nvert, 3) ||
	    h5_read(h, "triangles", H5T_NATIVE_INT32, (void **)&g->tri, &g->ntri, 3);
	H5Gclose(h);
	if (rc)
		return -1;
	for (size_t k = 0; k < 3 * g->ntri; k++)
		if (g->tri[k] < 0 || (size_t)g->tri[k] >= g->nvert)
			return err_set(
			    "%s: dataset '/geometry/triangles': vertex index %d out of range "
			    "[0, %zu)",
			    h5_name(file), g->tri[k], g->nvert);
	return 0;
}

/* The report's scalars, in file order, with their attribute names. Files
 * written before the REPORT_SCALARS_LATER ones existed lack them; they read
 * as NaN. */
#define REPORT_SCALARS(X)      \
	X(solid_fraction)      \
	X(solid_fraction_core) \
	X(wall_deficit)        \
	X(mean_radius)         \
	X(beta)                \
	X(coordination)        \
	X(alpha)               \
	X(fabric_anisotropy)   \
	X(overlap_max)         \
	X(overlap_mean)        \
	X(wall_overlap_max)    \
	X(time)                \
	X(time_geometry)       \
	X(time_cell)           \
	X(time_fill)           \
	X(time_report)
#define REPORT_SCALARS_LATER(X)  \
	X(coordination_core)     \
	X(coordination_boundary) \
	X(unbonded)

static int write_report(hid_t file, const dem_report *r)
{
	hid_t h = h5_group(file, "report");
	if (h < 0)
		return -1;
	int rc = 0;
#define WRITE_SCALAR(name) rc = rc || h5_attr_f64(h, #name, r->name);
	REPORT_SCALARS(WRITE_SCALAR)
	REPORT_SCALARS_LATER(WRITE_SCALAR)
#undef WRITE_SCALAR
	rc = rc || h5_write(h, "profile_w", H5T_NATIVE_DOUBLE, r->profile_w, r->nprofile, 0, "m") ||
	     h5_write(h, "profile_phi", H5T_NATIVE_DOUBLE, r->profile_phi, r->nprofile, 0, NULL) ||
	     h5_write(h, "psd_size", H5T_NATIVE_DOUBLE, r->psd_size, r->npsd, 0, "m") ||
	     h5_write(h, "psd_target_number", H5T_NATIVE_DOUBLE, r->psd_target_number, r->npsd, 0,
	              NULL) ||
	     h5_write(h, "psd_target_volume", H5T_NATIVE_DOUBLE, r->psd_target_volume, r->npsd, 0,
	              NULL) ||
	     h5_write(h, "psd_number", H5T_NATIVE_DOUBLE, r->psd_number, r->npsd, 0, NULL) ||
	     h5_write(h, "psd_volume", H5T_NATIVE_DOUBLE, r->psd_volume, r->npsd, 0, NULL);
	/* Each table's first column is the coordinate of its rows. */
	rc = rc || h5_scale(h, "profile_w") || h5_scale(h, "psd_size");
	static const char *const over_size[] = {"psd_target_number", "psd_target_volume",
	                                        "psd_number", "psd_volume"};
	rc = rc || h5_attach(h, "profile_phi", (const char *[]){"profile_w"}, 1);
	for (int k = 0; !rc && k < 4; k++)
		rc = h5_attach(h, over_size[k], (const char *[]){"psd_size"}, 1);
	H5Gclose(h);
	return rc ? -1 : 0;
}

static int read_report(hid_t file, dem_report *r)
{
	hid_t h = h5_open_group(file, "report");
	if (h < 0)
		return -1;
	int rc = 0;
#define READ_SCALAR(name) rc = rc || h5_read_attr_f64(h, #name, &r->name);
	REPORT_SCALARS(READ_SCALAR)
#undef READ_SCALAR
#define READ_LATER(name)                                         \
	if (H5Aexists(h, #name) > 0)                             \
		rc = rc || h5_read_attr_f64(h, #name, &r->name); \
	else                                                     \
		r->name = NAN;
	REPORT_SCALARS_LATER(READ_LATER)
#undef READ_LATER
	rc = rc ||
	     h5_read(h, "profile_w", H5T_NATIVE_DOUBLE, (void **)&r->profile_w, &r->nprofile, 0) ||
	     h5_read_n(h, "profile_phi", H5T_NATIVE_DOUBLE, (void **)&r->profile_phi, r->nprofile,
	               0) ||
	     h5_read(h, "psd_size", H5T_NATIVE_DOUBLE, (void **)&r->psd_size, &r->npsd, 0) ||
	     h5_read_n(h, "psd_target_number", H5T_NATIVE_DOUBLE, (void **)&r->psd_target_number,
	               r->npsd, 0) ||
	     h5_read_n(h, "psd_target_volume", H5T_NATIVE_DOUBLE, (void **)&r->psd_target_volume,
	               r->npsd, 0) ||
	     h5_read_n(h, "psd_number", H5T_NATIVE_DOUBLE, (void **)&r->psd_number, r->npsd, 0) ||
	     h5_read_n(h, "psd_volume", H5T_NATIVE_DOUBLE, (void **)&r->psd_volume, r->npsd, 0);
	H5Gclose(h);
	return rc ? -1 : 0;
}

/* Rows of a dataset of another file (h5_fill), read one reader at a time
 * (HDF5 serves one thread). */
typedef struct {
	hid_t d, type;
	size_t cols;
	int failed;
} from_file;

static void read_rows(void *ctx, size_t at, size_t m, void *buf)
{
	from_file *f = ctx;
	int rc;
#pragma omp critical(dem_hdf5)
	rc = h5_slab(f->d, f->type, at, m, f->cols, buf, 0);
	if (rc)
#pragma omp atomic write
		f->failed = 1;
}

/* Dataset `name` of n rows and cols columns written into p: from data, or
 * (data NULL) copied from the dataset of that name in src. */
static int write_or_copy(hid_t p, hid_t src, const char *name, hid_t type, const void *data,
                         size_t n, size_t cols, const char *unit)
{
	if (data)
		return h5_write(p, name, type, data, n, cols, unit);
	from_file f = {H5Dopen2(src, name, H5P_DEFAULT), type, cols, 0};
	if (f.d < 0)
		return err_set("%s: dataset '%s': cannot open", h5_name(src), name);
	h5_rows r;
	int rc = h5_rows_open(&r, p, name, type, n, cols, unit);
	rc = rc || h5_rows_fill(&r, read_rows, &f);
	rc = h5_rows_close(&r) || rc;
	H5Dclose(f.d);
	if (!rc && f.failed)
		rc = err_set("%s: dataset '%s': unreadable", h5_name(src), name);
	return rc ? -1 : 0;
}

int assembly_write_groups(hid_t file, const dem_assembly *a)
{
	hid_t src = -1;
	if (a->piece) {
		hid_t f = h5_open(a->file, ASSEMBLY_FORMAT, 0);
		src = f < 0 ? -1 : h5_open_group(f, "particles");
		if (f >= 0)
			H5Fclose(f); /* the group keeps the file open */
		if (src < 0)
			return -1;
	}
	hid_t p = h5_group(file, "particles");
	if (p < 0) {
		if (src >= 0)
			H5Gclose(src);
		return -1;
	}
	const int whole = !a->piece;
	int rc = prov_write(p, NULL, &a->prov) ||
	         write_or_copy(p, src, "x", H5T_NATIVE_DOUBLE, whole ? a->x : NULL, a->n, 3, "m") ||
	         write_or_copy(p, src, "r", H5T_NATIVE_DOUBLE, whole ? a->r : NULL, a->n, 0, "m") ||
	         write_or_copy(p, src, "material", H5T_NATIVE_INT32, whole ? a->material : NULL,
	                       a->n, 0, NULL) ||
	         h5_index(p, "particle", a->n, 0) || h5_index(p, "xyz", 3, 0) ||
	         h5_attach(p, "x", (const char *[]){"particle", "xyz"}, 2) ||
	         h5_attach(p, "r", (const char *[]){"particle"}, 1) ||
	         h5_attach(p, "material", (const char *[]){"particle"}, 1);
	H5Gclose(p);
	if (src >= 0)
		H5Gclose(src);
	if (rc || write_geometry(file, &a->geom) || write_report(file, &a->report))
		return -1;
	return 0;
}

/* Whether a sphere of radius r at x is larger than the geometry's bounding
 * box or lies outside it by more than its diameter (a damaged file; pack's
 * spheres have their centres inside). A geometry without a box passes. */
static int outside(const dem_geometry *g, const double x[3], double r)
{
	double size = 0;
	for (int k = 0; k < 3; k++) {
		if (!(g->bbox_max[k] > g->bbox_min[k]))
			return 0;
		size = fmax(size, g->bbox_max[k] - g->bbox_min[k]);
	}
	if (r > size)
		return 1;
	for (int k = 0; k < 3; k++)
		if (x[k] < g->bbox_min[k] - 2 * r || x[k] > g->bbox_max[k] + 2 * r)
			return 1;
	return 0;
}

int assembly_read_groups_part(hid_t file, int part, int parts, dem_assembly *a)
{
	hid_t p = h5_open_group(file, "particles");
	if (p < 0)
		return -1;
	size_t first, held, n;
	int rc = prov_read(p, &a->prov) ||
	         h5_read_part(p, "x", H5T_NATIVE_DOUBLE, (void **)&a->x, &a->n, 3, part, parts,
	                      &a->first, &a->held) ||
	         h5_read_part(p, "r", H5T_NATIVE_DOUBLE, (void **)&a->r, &n, 0, part, parts, &first,
	                      &held);
	if (!rc && n != a->n)
		rc = err_set("%s: dataset 'r': has %zu rows, expected %zu", h5_name(p), n, a->n);
	a->piece = parts > 1;
	if (!rc && !a->piece)
		rc = h5_read_n(p, "material", H5T_NATIVE_INT32, (void **)&a->material, a->n, 0);
	H5Gclose(p);
	if (rc || read_geometry(file, &a->geom) || read_report(file, &a->report))
		return -1;
	for (size_t k = 0; k < a->held; k++) {
		size_t i = a->first + k;
		const double *x = a->x + 3 * k, r = a->r[k];
		if (!(r > 0 && isfinite(r)))
			return err_set(
			    "%s: dataset '/particles/r': value %g at row %zu: expected a "
			    "finite positive radius (m)",
			    h5_name(file), r, i);
		if (!isfinite(x[0] + x[1] + x[2]))
			return err_set(
			    "%s: dataset '/particles/x': row %zu is (%g, %g, %g): expected a "
			    "finite position (m)",
			    h5_name(file), i, x[0], x[1], x[2]);
		if (outside(&a->geom, x, r))
			return err_set(
			    "%s: particle %zu (radius %g m at (%g, %g, %g) m) does not fit "
			    "the geometry's bounding box [%g, %g] x [%g, %g] x [%g, %g] m: "
			    "expected the spheres of the specimen",
			    h5_name(file), i, r, x[0], x[1], x[2], a->geom.bbox_min[0],
			    a->geom.bbox_max[0], a->geom.bbox_min[1], a->geom.bbox_max[1],
			    a->geom.bbox_min[2], a->geom.bbox_max[2]);
	}
	return 0;
}

int assembly_read_groups(hid_t file, dem_assembly *a)
{
	return assembly_read_groups_part(file, 0, 1, a);
}

int assembly_write_with(const char *path, const dem_assembly *a, int (*before)(void *), void *ctx)
{
	char tmp[4096];
	hid_t f = h5_create(path, tmp, sizeof tmp);
	if (f < 0)
		return -1;
	if (prov_write(f, ASSEMBLY_FORMAT, &a->prov) || assembly_write_groups(f, a) ||
	    (before && before(ctx))) {
		h5_discard(f, tmp);
		return -1;
	}
	return h5_commit(f, tmp, path);
}

int assembly_write(const char *path, const dem_assembly *a)
{
	return assembly_write_with(path, a, NULL, NULL);
}

int assembly_read_file(hid_t file, dem_assembly *a)
{
	memset(a, 0, sizeof *a);
	if (assembly_read_groups(file, a)) {
		assembly_free(a);
		return -1;
	}
	return 0;
}

int assembly_read(const char *path, dem_assembly *a) { return assembly_read_part(path, 0, 1, a); }

int assembly_read_part(const char *path, int part, int parts, dem_assembly *a)
{
	memset(a, 0, sizeof *a);
	hid_t f = h5_open(path, ASSEMBLY_FORMAT, 0);
	if (f < 0)
		return -1;
	int rc = assembly_read_groups_part(f, part, parts, a);
	H5Fclose(f);
	snprintf(a->file, sizeof a->file, "%s", path);
	if (rc)
		assembly_free(a);
	return rc;
}

void assembly_free(dem_assembly *a)
{
	prov_free(&a->prov);
	free(a->x);
	free(a->r);
	free(a->material);
	free(a->geom.vert);
	free(a->geom.tri);
	dem_report *r = &a->report;
	free(r->profile_w);
	free(r->profile_phi);
	free(r->psd_size);
	free(r->psd_target_number);
	free(r->psd_target_volume);
	free(r->psd_number);
	free(r->psd_volume);
	memset(a, 0, sizeof *a);
}
