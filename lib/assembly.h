/* The assembly file (assembly.h5), written by pack and read by solve and
 * post: spheres, the specimen geometry and the packing report. The layout is
 * specified in share/doc/format.md; this is its only reader and writer. */
#ifndef DEM_ASSEMBLY_H
#define DEM_ASSEMBLY_H

#include <stddef.h>
#include <stdint.h>

#include <hdf5.h>

#include "lib/prov.h"

#define ASSEMBLY_FORMAT "dem-assembly"

/* The specimen. Built-in shapes have their axis along z and are centred on
 * `center`; the boundary triangulation is kept for every shape so inside
 * and distance queries need no gmsh at solve time. */
typedef struct {
	char shape[32];                  /* "cylinder", "disc", "box" or "file" */
	char source[512];                /* the geometry file for "file", else "" */
	double center[3];                /* m */
	double axis[3];                  /* unit vector of the loading axis */
	double diameter;                 /* m (cylinder, disc; 0 otherwise) */
	double height;                   /* m (cylinder; disc thickness; box size[2]) */
	double size[3];                  /* m, box edge lengths (0 otherwise) */
	double bbox_min[3], bbox_max[3]; /* m */
	double volume;                   /* m^3 */
	double area;                     /* m^2, boundary surface */
	size_t nvert, ntri;
	double *vert; /* [nvert][3] m */
	int32_t *tri; /* [ntri][3] vertex indices, outward normals */
} dem_geometry;

/* What pack measured of the assembly (share/doc/format.md, /report). */
typedef struct {
	double solid_fraction;        /* sphere volume / specimen volume */
	double solid_fraction_core;   /* more than 2 mean diameters from the boundary */
	double wall_deficit;          /* delta* in mean diameters */
	double mean_radius;           /* m */
	double beta;                  /* interaction range used for coordination */
	double coordination;          /* bonds per sphere within (1+beta)(ri+rj) */
	double coordination_core;     /* of the spheres in the core */
	double coordination_boundary; /* of the spheres less than half a mean diameter deep */
	double unbonded;              /* spheres without a bond (a count) */
	double alpha;                 /* 40 P / N_c (Eq. 22 of Onate et al. 2015) */
	double fabric_anisotropy;     /* of <n x n> over core contacts */
	double overlap_max;           /* relative to the smaller radius */
	double overlap_mean;
	double wall_overlap_max; /* protrusion beyond the boundary / radius */
	double time;             /* s, wall time of pack */
	double time_geometry;    /* s, of which: geometry and its search tree */
	double time_cell;        /* s, periodic cell */
	double time_fill;        /* s, tiling and wall-band repair */
	double time_report;      /* s, this report */
	size_t nprofile;         /* solid fraction profile phi(w) */
	double *profile_w;       /* m, distance to the boundary (bin centre) */
	double *profile_phi;
	size_t npsd;               /* size distribution, cumulative */
	double *psd_size;          /* m, diameter */
	double *psd_target_number; /* fractions passing, by number and by volume */
	double *psd_target_volume;
	double *psd_number;
	double *psd_volume;
} dem_report;

typedef struct {
	dem_provenance prov;
	size_t n;
	int piece;       /* x and r hold rows [first, first + held) only
	                    (assembly_read_part), else all n */
	char file[1024]; /* with a piece: the file it is of */
	size_t first, held;
	double *x;         /* [n or held][3] m */
	double *r;         /* [n or held] m */
	int32_t *material; /* [n] material index (0 for a single material),
	                      or NULL (assembly_read_part) */
	dem_geometry geom;
	dem_report report;
} dem_assembly;

int assembly_write(const char *path, const dem_assembly *a);
/* As assembly_write, with before(ctx) called once the file is complete and
 * before it replaces `path` (to write files that go with it): if before
 * fails, the file is discarded and whatever was at `path` stays. */
int assembly_write_with(const char *path, const dem_assembly *a, int (*before)(void *), void *ctx);
int assembly_read(const char *path, dem_assembly *a);
/* The same, but of the particles only the positions and radii of part
 * `part` of `parts` even parts of the rows (a->first, a->held): a piece
 * of a large assembly for each of `parts` processes. */
int assembly_read_part(const char *path, int part, int parts, dem_assembly *a);
/* The same from an open file whose format was checked (h5_open, or
 * h5_open_image); the file stays open. */
int assembly_read_file(hid_t file, dem_assembly *a);
void assembly_free(dem_assembly *a);

/* Particles (with the assembly's provenance as attributes of /particles),
 * geometry and report as groups of an open file: shared with run.h5, which
 * embeds the assembly it started from. Of a piece, the particles are
 * copied from its file (a->file) a chunk at a time. */
int assembly_write_groups(hid_t file, const dem_assembly *a);
int assembly_read_groups(hid_t file, dem_assembly *a);
int assembly_read_groups_part(hid_t file, int part, int parts, dem_assembly *a);

#endif
