/* The specimen: a built-in shape or any geometry gmsh reads, turned into a
 * closed, outward-oriented boundary triangulation through the gmsh C API. */
#ifndef PACK_GEOMETRY_H
#define PACK_GEOMETRY_H

#include "lib/assembly.h"

typedef enum { SHAPE_CYLINDER, SHAPE_DISC, SHAPE_BOX, SHAPE_FILE } shape_kind;

typedef struct {
	shape_kind kind;
	double diameter;  /* m, cylinder and disc */
	double height;    /* m, cylinder height, disc thickness */
	double size[3];   /* m, box edges along x, y, z */
	const char *file; /* SHAPE_FILE: .geo, .step/.stp, .brep, .msh, .stl, ... */
	double scale;     /* SHAPE_FILE: factor applied to the file's coordinates */
} geometry_spec;

/* A built-in shape's fields known without meshing it: shape, sizes,
 * volume, bounding box and axis (no boundary: nvert = ntri = 0). Returns
 * 0, or -1 for a file, leaving g untouched. */
int geometry_extent(const geometry_spec *s, dem_geometry *g);

/* Fill every field of g. Built-in shapes have their axis along z and are
 * centred on the origin; their volume is exact, while a file's volume is
 * the one its triangulation encloses. STEP files are read in metres
 * whatever unit they were written in; other formats carry no unit and are
 * multiplied by `scale`. Returns 0, or -1 with err_set() naming the file
 * and what is wrong (unreadable, no closed volume, ...). */
int geometry_build(const geometry_spec *s, dem_geometry *g);
/* Whether file is a STEP file (.step or .stp, any case): read in metres,
 * --scale does not apply. */
int geometry_is_step(const char *file);

/* Volume of the part of the specimen farther than w from its boundary
 * (m^3), exact for the built-in shapes; for a file, -1 (not known in
 * closed form). */
double geometry_inner_volume(const dem_geometry *g, double w);

#endif
