/* The states of a bond and the failure modes of a crack: what the contact
 * laws set and the run file stores (lib/runfile.h, share/doc/format.md).
 * Their own header so a law knows them without the file format (and HDF5). */
#ifndef DEM_STATES_H
#define DEM_STATES_H

/* State of a bond, as stored in snapshots. */
enum { BOND_INTACT = 0, BOND_DAMAGED = 1, BOND_BROKEN_TENSION = 2, BOND_BROKEN_SHEAR = 3 };
/* Failure mode of a crack. */
enum { CRACK_TENSION = 1, CRACK_SHEAR = 2 };

#endif
