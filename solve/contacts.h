/* Non-bonded contacts from a Verlet list (contacts.c). */
#ifndef DEM_CONTACTS_H
#define DEM_CONTACTS_H

typedef struct engine engine;

/* Rebuild the contact list (and the platens' candidates) from the current
 * positions. */
void contacts_rebuild(engine *e);
/* After a checkpoint has replaced the contact list with the whole
 * specimen's: keep those of this rank's particles (ranks.h), and index
 * them. */
void contacts_restore(engine *e);
/* Index the contact list by the particle block of each contact's i. */
void contacts_index_blocks(engine *e);
/* This step's contact forces, inside the step's parallel region. */
void contacts_forces(engine *e, int measure);

#endif
