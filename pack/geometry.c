/* Specimen geometry through the gmsh C API.
 *
 * Built-in shapes are made in gmsh's built-in kernel by extruding a base
 * (disc or rectangle) along z with one structured layer, so the lateral
 * surface is exact along the axis. A circle is cut into CIRCLE_SEGMENTS
 * chords: the sagitta R (1 - cos(pi/N)) is 1.9e-4 R and the polygon's area
 * deficit 2.6e-4, far below the packing's own resolution. Cap interiors
 * use large triangles (size R/4), as flat faces need no refinement.
 *
 * Files are opened with gmsh; when they hold no mesh one is generated in 2D
 * with sizes refined on curved boundaries. The boundary is then the faces
 * that belong to one volume element only (a volume mesh), the boundary
 * surfaces of the union of all volumes (a CAD solid), or every surface
 * element (a surface mesh); pack/trimesh_close.cpp checks it is closed and
 * orients it. */
#include <errno.h>
#include <math.h>
#include <omp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <unistd.h>

#include "lib/err.h"
#include "pack/geometry.h"
#include "pack/gmshlib.h"
#include "pack/trimesh.h"

#define CIRCLE_SEGMENTS 160
#define CURVATURE_SEGMENTS 96 /* elements per 2 pi on curved CAD boundaries */

static const gmsh_library *G; /* set by geometry_build */

/* gmsh's CAD kernels print some errors on stdout themselves; the message
 * that matters reaches us through gmsh's logger. */
static int quiet_begin(void)
{
	fflush(stdout);
	int saved = dup(STDOUT_FILENO);
	FILE *null = fopen("/dev/null", "w");
	if (null) {
		dup2(fileno(null), STDOUT_FILENO);
		fclose(null);
	}
	return saved;
}

static void quiet_end(int saved)
{
	fflush(stdout);
	if (saved >= 0) {
		dup2(saved, STDOUT_FILENO);
		close(saved);
	}
}

static int gmsh_failed(const char *what)
{
	char *msg = NULL;
	int ierr;
	G->gmshLoggerGetLastError(&msg, &ierr);
	err_set("%s: %s", what, msg && msg[0] ? msg : "gmsh failed");
	G->gmshFree(msg);
	return -1;
}

/* A prism of height h along z (base at z = -h/2) over the base surface. */
static int extrude_base(int surf, double h)
{
	int ierr, dt[2] = {2, surf}, layers = 1, *out = NULL;
	double heights = 1;
	size_t nout;
	G->gmshModelGeoExtrude(dt, 2, 0, 0, h, &out, &nout, &layers, 1, &heights, 1, 0, &ierr);
	G->gmshFree(out);
	return ierr;
}

static int make_cylinder(double diameter, double height)
{
	int ierr = 0, p[4], arc[4];
	double r = 0.5 * diameter, z = -0.5 * height;
	int c = G->gmshModelGeoAddPoint(0, 0, z, r, -1, &ierr);
	for (int k = 0; k < 4; k++)
		p[k] = G->gmshModelGeoAddPoint(r * cos(k * M_PI / 2), r * sin(k * M_PI / 2), z, r,
		                               -1, &ierr);
	for (int k = 0; k < 4; k++) {
		arc[k] = G->gmshModelGeoAddCircleArc(p[k], c, p[(k + 1) % 4], -1, 0, 0, 0, &ierr);
		G->gmshModelGeoMeshSetTransfiniteCurve(arc[k], CIRCLE_SEGMENTS / 4 + 1,
		                                       "Progression", 1, &ierr);
	}
	int loop = G->gmshModelGeoAddCurveLoop(arc, 4, -1, 0, &ierr);
	int surf = G->gmshModelGeoAddPlaneSurface(&loop, 1, -1, &ierr);
	ierr = ierr || extrude_base(surf, height);
	G->gmshOptionSetNumber("Mesh.MeshSizeMax", r / 4, &ierr);
	return ierr;
}

static int make_box(const double size[3])
{
	int ierr = 0, p[4], line[4];
	double x = 0.5 * size[0], y = 0.5 * size[1], z = -0.5 * size[2];
	static const double sx[4] = {-1, 1, 1, -1}, sy[4] = {-1, -1, 1, 1};
	for (int k = 0; k < 4; k++)
		p[k] = G->gmshModelGeoAddPoint(sx[k] * x, sy[k] * y, z, 0, -1, &ierr);
	for (int k = 0; k < 4; k++) {
		line[k] = G->gmshModelGeoAddLine(p[k], p[(k + 1) % 4], -1, &ierr);
		G->gmshModelGeoMeshSetTransfiniteCurve(line[k], 2, "Progression", 1, &ierr);
	}
	int loop = G->gmshModelGeoAddCurveLoop(line, 4, -1, 0, &ierr);
	int surf = G->gmshModelGeoAddPlaneSurface(&loop, 1, -1, &ierr);
	G->gmshModelGeoMeshSetTransfiniteSurface(surf, "Left", NULL, 0, &ierr);
	return ierr || extrude_base(surf, size[2]);
}

static int make_builtin(const geometry_spec *s)
{
	int ierr;
	G->gmshOptionSetNumber("Mesh.MeshSizeExtendFromBoundary", 0, &ierr);
	G->gmshOptionSetNumber("Mesh.MeshSizeFromPoints", 0, &ierr);
	int rc = s->kind == SHAPE_BOX ? make_box(s->size) : make_cylinder(s->diameter, s->height);
	G->gmshModelGeoSynchronize(&ierr);
	if (rc || ierr)
		return gmsh_failed("gmsh: building the built-in shape");
	G->gmshModelMeshGenerate(2, &ierr);
	return ierr ? gmsh_failed("gmsh: meshing the built-in shape") : 0;
}

/* A geometry file may end the program itself (gmsh's "Exit;" command):
 * while gmsh reads one, an exit is reported as the error it is. */
static const char *reading;

static void exit_while_reading(void)
{
	if (reading) {
		fprintf(stderr,
		        "%s: %s: the geometry file ended the program while gmsh read it (an "
		        "'Exit' command?): expected a geometry to fill\n",
		        err_program_name(), reading);
		_exit(1);
	}
}

static int open_file(const char *path)
{
	FILE *f = fopen(path, "rb");
	if (!f)
		return err_set("%s: cannot open: %s", path, strerror(errno));
	fclose(f);
	int ierr;
	G->gmshOptionSetString("Geometry.OCCTargetUnit", "M", &ierr);
	static int registered;
	if (!registered)
		registered = !atexit(exit_while_reading);
	int saved = quiet_begin();
	reading = path;
	G->gmshOpen(path, &ierr);
	reading = NULL;
	quiet_end(saved);
	if (ierr)
		return gmsh_failed(path);
	size_t *tags = NULL, ntags = 0;
	double *xyz = NULL, *par = NULL;
	size_t nxyz, npar;
	G->gmshModelMeshGetNodes(&tags, &ntags, &xyz, &nxyz, &par, &npar, -1, -1, 0, 0, &ierr);
	G->gmshFree(tags);
	G->gmshFree(xyz);
	G->gmshFree(par);
	if (ntags > 0)
		return 0;
	G->gmshOptionSetNumber("Mesh.MeshSizeFromCurvature", CURVATURE_SEGMENTS, &ierr);
	G->gmshOptionSetNumber("Mesh.MinimumCirclePoints", CURVATURE_SEGMENTS, &ierr);
	saved = quiet_begin();
	G->gmshModelMeshGenerate(2, &ierr);
	quiet_end(saved);
	return ierr ? gmsh_failed(path) : 0;
}

static void push_face(size_t **faces, size_t *nfaces, size_t *cap, const size_t *corner,
                      int ncorner)
{
	if (*nfaces + 2 > *cap) {
		*cap = 2 * *cap + 64;
		*faces = xrealloc(*faces, 3 * *cap * sizeof **faces);
	}
	size_t *o = *faces + 3 * *nfaces;
	memcpy(o, corner, 3 * sizeof *o);
	(*nfaces)++;
	if (ncorner == 4) { /* split a quadrangle along its diagonal 0-2 */
		size_t q[3] = {corner[0], corner[2], corner[3]};
		memcpy(o + 3, q, sizeof q);
		(*nfaces)++;
	}
}

/* Append the faces (corner nodes) of every element of dimension dim (2 or
 * 3) on entity tag (-1: all) to a list of node-tag triangles. A surface
 * element is its own face; quadrangles are split in two. */
static void collect_faces(int dim, int tag, size_t **faces, size_t *nfaces, size_t *cap)
{
	int ierr, *types = NULL;
	size_t ntypes;
	G->gmshModelMeshGetElementTypes(&types, &ntypes, dim, tag, &ierr);
	for (size_t k = 0; k < ntypes; k++) {
		char *name = NULL;
		double *local = NULL;
		size_t nlocal;
		int edim, order, nnodes, nprimary;
		G->gmshModelMeshGetElementProperties(types[k], &name, &edim, &order, &nnodes,
		                                     &local, &nlocal, &nprimary, &ierr);
		G->gmshFree(name);
		G->gmshFree(local);
		if (dim == 2) {
			size_t *etags = NULL, ne, *nodes = NULL, nn;
			G->gmshModelMeshGetElementsByType(types[k], &etags, &ne, &nodes, &nn, tag,
			                                  0, 1, &ierr);
			for (size_t e = 0; !ierr && (nprimary == 3 || nprimary == 4) && e < ne; e++)
				push_face(faces, nfaces, cap, nodes + e * (size_t)nnodes, nprimary);
			G->gmshFree(etags);
			G->gmshFree(nodes);
			continue;
		}
		for (int corners = 3; corners <= 4; corners++) {
			size_t *nodes = NULL, nn = 0;
			G->gmshModelMeshGetElementFaceNodes(types[k], corners, &nodes, &nn, tag, 1,
			                                    0, 1, &ierr);
			for (size_t f = 0; !ierr && f + (size_t)corners <= nn; f += (size_t)corners)
				push_face(faces, nfaces, cap, nodes + f, corners);
			G->gmshFree(nodes);
		}
	}
	G->gmshFree(types);
}

typedef struct {
	size_t key[3]; /* node tags, sorted */
	size_t idx;
} face_key;

static int cmp_face_key(const void *a, const void *b)
{
	const face_key *u = a, *v = b;
	for (int k = 0; k < 3; k++)
		if (u->key[k] != v->key[k])
			return u->key[k] < v->key[k] ? -1 : 1;
	return (u->idx > v->idx) - (u->idx < v->idx);
}

/* Keep the faces that occur exactly once: the boundary of a volume mesh. */
static size_t keep_unshared(size_t *faces, size_t n)
{
	face_key *fk = xmalloc(n * sizeof *fk + 1);
	for (size_t i = 0; i < n; i++) {
		size_t *k = fk[i].key;
		memcpy(k, faces + 3 * i, 3 * sizeof *k);
		for (int a = 0; a < 2; a++)
			for (int b = a + 1; b < 3; b++)
				if (k[b] < k[a]) {
					size_t t = k[a];
					k[a] = k[b];
					k[b] = t;
				}
		fk[i].idx = i;
	}
	qsort(fk, n, sizeof *fk, cmp_face_key);
	uint8_t *keep = xcalloc(n + 1, 1);
	for (size_t i = 0; i < n;) {
		size_t j = i + 1;
		while (j < n && memcmp(fk[i].key, fk[j].key, sizeof fk[i].key) == 0)
			j++;
		keep[fk[i].idx] = j - i == 1;
		i = j;
	}
	size_t m = 0;
	for (size_t i = 0; i < n; i++)
		if (keep[i])
			memmove(faces + 3 * m++, faces + 3 * i, 3 * sizeof *faces);
	free(fk);
	free(keep);
	return m;
}

/* The boundary triangles of the current gmsh model, as node tags. */
static void boundary_faces(size_t **faces, size_t *nfaces)
{
	int ierr, *vols = NULL;
	size_t nvols, cap = 0;
	*faces = NULL;
	*nfaces = 0;
	collect_faces(3, -1, faces, nfaces, &cap);
	if (*nfaces > 0) {
		*nfaces = keep_unshared(*faces, *nfaces);
		return;
	}
	G->gmshModelGetEntities(&vols, &nvols, 3, &ierr);
	if (nvols > 0) {
		int *bnd = NULL;
		size_t nbnd;
		G->gmshModelGetBoundary(vols, nvols, &bnd, &nbnd, 1, 0, 0, &ierr);
		for (size_t k = 0; k + 1 < nbnd; k += 2)
			collect_faces(2, abs(bnd[k + 1]), faces, nfaces, &cap);
		G->gmshFree(bnd);
	} else {
		collect_faces(2, -1, faces, nfaces, &cap);
	}
	G->gmshFree(vols);
}

int geometry_is_step(const char *file)
{
	const char *dot = strrchr(file, '.');
	return dot && (!strcasecmp(dot, ".step") || !strcasecmp(dot, ".stp"));
}

/* Node tags to a compact vertex array. */
static int to_trimesh(const size_t *faces, size_t nfaces, double scale, trimesh *m)
{
	int ierr;
	size_t *tags = NULL, ntags;
	double *xyz = NULL, *par = NULL;
	size_t nxyz, npar;
	G->gmshModelMeshGetNodes(&tags, &ntags, &xyz, &nxyz, &par, &npar, -1, -1, 0, 0, &ierr);
	size_t maxtag = 0;
	for (size_t i = 0; i < ntags; i++)
		maxtag = tags[i] > maxtag ? tags[i] : maxtag;
	int64_t *slot = xmalloc((maxtag + 1) * sizeof *slot);
	for (size_t i = 0; i <= maxtag; i++)
		slot[i] = -1;
	for (size_t i = 0; i < ntags; i++)
		slot[tags[i]] = (int64_t)i;
	m->nvert = ntags;
	m->vert = xmalloc(3 * ntags * sizeof *m->vert + 1);
	for (size_t i = 0; i < 3 * ntags; i++)
		m->vert[i] = scale * xyz[i];
	m->ntri = nfaces;
	m->tri = xmalloc(3 * nfaces * sizeof *m->tri + 1);
	int rc = 0;
	for (size_t k = 0; k < 3 * nfaces; k++) {
		if (faces[k] > maxtag || slot[faces[k]] < 0) {
			rc = err_set("gmsh: element refers to missing node %zu", faces[k]);
			break;
		}
		m->tri[k] = (int32_t)slot[faces[k]];
	}
	free(slot);
	G->gmshFree(tags);
	G->gmshFree(xyz);
	G->gmshFree(par);
	return rc;
}

int geometry_extent(const geometry_spec *s, dem_geometry *g)
{
	if (s->kind == SHAPE_FILE)
		return -1;
	memset(g, 0, sizeof *g);
	double edge[3];
	if (s->kind == SHAPE_BOX) {
		snprintf(g->shape, sizeof g->shape, "box");
		memcpy(g->size, s->size, sizeof g->size);
		memcpy(edge, s->size, sizeof edge);
		g->height = s->size[2];
		g->volume = s->size[0] * s->size[1] * s->size[2];
	} else {
		snprintf(g->shape, sizeof g->shape, "%s",
		         s->kind == SHAPE_DISC ? "disc" : "cylinder");
		g->diameter = edge[0] = edge[1] = s->diameter;
		g->height = edge[2] = s->height;
		g->volume = M_PI * 0.25 * s->diameter * s->diameter * s->height;
	}
	for (int k = 0; k < 3; k++) {
		g->bbox_max[k] = 0.5 * edge[k];
		g->bbox_min[k] = -g->bbox_max[k];
	}
	g->axis[2] = 1;
	return 0;
}

int geometry_build(const geometry_spec *s, dem_geometry *g)
{
	memset(g, 0, sizeof *g);
	const char *what = s->kind == SHAPE_FILE ? s->file : "built-in shape";
	if (!(G = gmshlib_load()))
		return -1;
	int ierr, threads = omp_get_max_threads();
	G->gmshInitialize(0, NULL, 0, &ierr);
	G->gmshOptionSetNumber("General.Terminal", 0, &ierr);
	G->gmshOptionSetNumber("General.NumThreads", 1, &ierr);
	G->gmshLoggerStart(&ierr);
	int rc = s->kind == SHAPE_FILE ? open_file(s->file) : make_builtin(s);
	trimesh m = {0};
	if (rc == 0) {
		size_t *faces, nfaces;
		boundary_faces(&faces, &nfaces);
		double scale = s->kind == SHAPE_FILE && !geometry_is_step(s->file) ? s->scale : 1;
		rc = to_trimesh(faces, nfaces, scale, &m);
		free(faces);
	}
	G->gmshLoggerStop(&ierr);
	G->gmshFinalize(&ierr);
	/* gmsh sets the OpenMP thread count of the whole process: restore it. */
	omp_set_num_threads(threads);
	if (rc || trimesh_close(&m, what)) {
		trimesh_free(&m);
		return -1;
	}
	double volume;
	trimesh_measure(&m, &volume, &g->area, g->bbox_min, g->bbox_max);
	if (!(volume > 0)) {
		trimesh_free(&m);
		return err_set("%s: the boundary encloses no volume", what);
	}
	double area = g->area;
	if (geometry_extent(s, g) == 0) {
		g->area = area;
	} else {
		g->axis[2] = 1;
		snprintf(g->shape, sizeof g->shape, "file");
		snprintf(g->source, sizeof g->source, "%s", s->file);
		g->volume = volume;
		g->height = g->bbox_max[2] - g->bbox_min[2];
		for (int k = 0; k < 3; k++)
			g->center[k] = 0.5 * (g->bbox_min[k] + g->bbox_max[k]);
	}
	g->nvert = m.nvert;
	g->vert = m.vert;
	g->ntri = m.ntri;
	g->tri = m.tri;
	return 0;
}

double geometry_inner_volume(const dem_geometry *g, double w)
{
	if (strcmp(g->shape, "box") == 0) {
		double v = 1;
		for (int k = 0; k < 3; k++)
			v *= fmax(0, g->size[k] - 2 * w);
		return v;
	}
	if (strcmp(g->shape, "cylinder") == 0 || strcmp(g->shape, "disc") == 0) {
		double r = fmax(0, 0.5 * g->diameter - w), h = fmax(0, g->height - 2 * w);
		return M_PI * r * r * h;
	}
	return -1;
}
