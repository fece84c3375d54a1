/* Reading back what post wrote, through the VTK library (tests only):
 * VTK XML files (.vtu, .vtp) and PNG images. C interface over
 * tests/post/vtkread.cpp. */
#ifndef DEM_TESTS_POST_VTKREAD_H
#define DEM_TESTS_POST_VTKREAD_H

#ifdef __cplusplus
extern "C" {
#endif

typedef struct vtkr vtkr;

/* Open a .vtu or .vtp file; NULL when VTK cannot read it. */
vtkr *vtkr_open(const char *path);
void vtkr_close(vtkr *r);
long vtkr_npoints(const vtkr *r);
long vtkr_ncells(const vtkr *r);
void vtkr_point(const vtkr *r, long k, double x[3]);
int vtkr_cell_type(const vtkr *r, long c); /* VTK_VERTEX 1, VTK_LINE 3, VTK_POLYGON 7 */
int vtkr_cell_size(const vtkr *r, long c);
long vtkr_cell_point(const vtkr *r, long c, int k);

/* Arrays on points (where 'p'), cells ('c') or the whole data set (field
 * data, 'f'): the number of components,
 * or -1 when there is no array of that name; *ntuples gets its length. */
int vtkr_array(const vtkr *r, char where, const char *name, long *ntuples);
double vtkr_value(const vtkr *r, char where, const char *name, long tuple, int comp);

/* A PNG image: its size, the number of distinct colours and how many
 * pixels are within 40 (per channel) of each of the n colours rgb[k]
 * (0xRRGGBB), in count[k]. Returns 0, or -1 if the file is no PNG. */
int vtkr_png(const char *path, int *width, int *height, long *colours, const unsigned *rgb,
             long *count, int n);

#ifdef __cplusplus
}
#endif

#endif
