/* The particles a rank holds (engine.h, particles): its own and the other
 * ranks' particles it reads, a window of indices (window.c).
 *
 * In setup a rank holds its share of the particles' order (order.h) and
 * the other ranks' particles within the bond range; once the particles
 * are split among the ranks (window_start), besides its own particles,
 * the other ends of its crossing bonds (bonds.h) for the whole run, and
 * the other ends of its contacts and its ghosts (ranks.h), renewed at each
 * neighbour rebuild (window_set) and, at a restart, when the checkpoint's
 * contacts are read (window_hold_contacts). The others are numbered next
 * to its own, those of lower index before them and those of higher index
 * after them, each side in the order of their indices: every list sorted
 * by particle (bonds, contacts, the crossing slots, the halo) keeps the
 * order one process gives it, and its own particles keep their index in
 * the whole specimen. What a rank writes or sends of a particle index (the
 * checkpoint's contacts, the diagnoses, the rank of a particle) is the
 * index in the whole specimen (particle_global). */
#ifndef DEM_WINDOW_H
#define DEM_WINDOW_H

#include <stddef.h>
#include <stdint.h>

typedef struct engine engine;
typedef struct particles particles;

/* An array of items of `size` bytes addressed by the indices [lo, hi),
 * zeroed (the pointer returned is that of index 0: its memory starts at
 * index lo), and its release. */
void *window_array(size_t lo, size_t hi, size_t size);
void window_array_free(void *a, size_t lo, size_t size);
/* The particles' arrays (not x_ref) for the window [lo, hi) of a specimen of n
 * particles (zero, no particle on a platen or the surface), glob NULL. */
void particles_alloc(particles *P, size_t n, size_t lo, size_t hi);
void particles_free(particles *P);
/* The same for a rank's own particles [p0, p1) as its window. */
void particles_alloc_own(particles *P, size_t n, size_t p0, size_t p1);
/* Particle i's position, velocity, spin, radius, mass and index in the
 * assembly as a row of PARTICLE_ROW doubles (what a rank sends of a
 * particle another rank is to hold), and back. */
enum { PARTICLE_R = 9, PARTICLE_M, PARTICLE_ORIG, PARTICLE_ROW };
void particle_row(const particles *P, size_t i, double *row);
void particle_set_row(particles *P, size_t i, const double *row);
/* The window's index of the specimen's particle g, or -1 if this rank does
 * not hold it. */
int64_t window_local(const particles *P, size_t g);
/* With several ranks, once setup has split the particles: the window of
 * this rank's own particles and the other ends of its crossing bonds and
 * contacts; the others' arrays freed. */
void window_start(engine *e);
/* Hold the specimen's particles want[0..n) (increasing, other ranks') as
 * well as the own ones and the other ends of the crossing bonds: a new
 * window, the particles kept from the old one copied into it and every
 * list renumbered; the contacts with an end no longer held dropped (the
 * neighbour rebuild replaces them), their number returned. The arrays of
 * the particles new to the window are the caller's to fill. */
size_t window_set(engine *e, const int32_t *want, size_t n);
/* Hold the other ranks' particles within `reach` of the box around this
 * rank's own (ranks_share_ghosts) as well: their number. Collective. */
size_t window_ghosts(engine *e, double reach);
/* Hold the ends of the contacts (e->pairs.contacts, as read from a
 * checkpoint: their ends given by their index in the whole specimen) as
 * well as the own particles and the other ends of the crossing bonds: a
 * new window (window_set), the contacts' ends turned into its indices. The
 * arrays of the other ranks' particles are the caller's to fill. */
void window_hold_contacts(engine *e);

#endif
