/* Writing VTK XML files through the VTK library (post/vtkio.cpp, the only
 * C++ of post). A mesh is plain arrays: points, cells of one kind and named
 * point and cell arrays. Files are binary, zlib-compressed, appended XML:
 * .vtu (unstructured grid) or .vtp (polygonal data), readable by ParaView
 * and by any VTK reader. */
#ifndef DEM_POST_VTKIO_H
#define DEM_POST_VTKIO_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef enum { VTKIO_F64, VTKIO_I32, VTKIO_I64, VTKIO_U8 } vtkio_type;

typedef struct {
	const char *name;
	vtkio_type type;
	int ncomp;        /* 1 for scalars, 3 for vectors */
	const void *data; /* [tuples][ncomp] */
} vtkio_array;

/* Cells: one vertex per point, lines (two points each) or polygons. */
typedef enum { VTKIO_VERTS, VTKIO_LINES, VTKIO_POLYS } vtkio_cells;

typedef struct {
	size_t npoints;
	const double *x; /* [npoints][3] */
	vtkio_cells kind;
	size_t ncells;            /* ignored for VTKIO_VERTS (one per point) */
	const int64_t *offsets;   /* [ncells + 1] into conn; NULL for VTKIO_VERTS */
	const int64_t *conn;      /* point indices; NULL for VTKIO_VERTS */
	const vtkio_array *pdata; /* point arrays, [npoints] tuples each */
	int npdata;
	const vtkio_array *cdata; /* cell arrays, [ncells] tuples each */
	int ncdata;
	const vtkio_array *fdata; /* field data: one tuple each (the frame's time, ...) */
	int nfdata;
} vtkio_mesh;

/* Ready for files written on several threads at once: VTK sets up its
 * object factory at the first object it makes, and not under a lock, so
 * one of each kind is made here first, on the calling thread. */
void vtkio_threads(void);

/* Write m to path as an unstructured grid (.vtu) or polygonal data (.vtp).
 * path is written as given (callers pass a temporary name). Returns 0, or
 * -1 when the file cannot be written (the caller reports it). */
int vtkio_write_vtu(const char *path, const vtkio_mesh *m);
int vtkio_write_vtp(const char *path, const vtkio_mesh *m);

#ifdef __cplusplus
}
#endif

#endif
