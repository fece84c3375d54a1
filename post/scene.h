/* What post shows in ParaView, as VTK XML files (written atomically
 * through post/vtkio.h):
 *   particles  points with radius, material, id; from a snapshot also
 *              displacement (from the starting assembly), velocity,
 *              angular velocity, damage and broken bond count
 *   bonds      lines between bonded centres with state, forces, damage
 *   cracks     one disc per bond failure (post/cracks_vtk.c)
 *   platens    the two loading platens as discs
 *   geometry   the specimen boundary triangulation
 * Particle damage D_i is the mean over the bonds of particle i of d_b,
 * with d_b = 1 for a broken bond and max(d_n, d_s) otherwise (0 when the
 * particle has no bond). A particle's stress (Pa, tension positive, as
 * Yade's bodyStressTensors) is (1/V_i) Σ_b l_ib ⊗ f_ib over its bonds,
 * with V_i = 4/3 π r_i³, l_ib the branch from its centre to the bond's
 * contact point and f_ib the bond's force on it (the forces a snapshot
 * holds: non-bonded contacts are not in it); with its mean (p = tr σ / 3)
 * and von Mises (q = sqrt(3/2 s:s), s the deviator of the symmetric part)
 * invariants. Platens sit at the particle extents along the
 * loading axis (min of h - r, max of h + r in post/frame.h terms), the
 * faces the specimen presses on, with a radius 1.2 times the specimen's. */
#ifndef DEM_POST_SCENE_H
#define DEM_POST_SCENE_H

#include "lib/runfile.h"
#include "post/frame.h"
#include "post/vtkio.h"

/* Field data every file written next carries (the frame's time, strain,
 * stress, ...), or n = 0 for none; the arrays must outlive those writes. */
void scene_fields(const vtkio_array *fd, int n);
/* Write m to path (.vtu or .vtp by its extension) atomically; fatal on
 * failure. */
void scene_put(const char *path, const vtkio_mesh *m);

/* s == NULL: the assembly as packed (no bonds, no motion). */
void scene_particles(const char *path, const dem_assembly *a, const dem_bonds *b,
                     const dem_snapshot *s);
void scene_bonds(const char *path, const dem_bonds *b, const dem_snapshot *s);
void scene_platens(const char *path, const frame *f, const dem_assembly *a, const dem_snapshot *s);
void scene_geometry(const char *path, const dem_geometry *g);

/* Points of an n-gon of radius r about centre c in the plane normal to the
 * unit vector normal: appends 3 n doubles to x. */
void scene_disc(double *x, const double c[3], const double normal[3], double r, int n);

#endif
