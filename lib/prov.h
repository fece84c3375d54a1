/* Provenance carried by every file: which program and version made it, when,
 * from which full configuration and random seed. Stored as root attributes
 * next to `format` and `format_version` (share/doc/format.md). */
#ifndef DEM_PROV_H
#define DEM_PROV_H

#include <hdf5.h>
#include <stdint.h>

typedef struct {
	char *program; /* "pack", "solve", ... */
	char *version; /* toolchain version, e.g. "0.1.0" */
	char *created; /* ISO 8601 UTC time, e.g. "2026-11-22T10:00:00Z" */
	char *config;  /* the full configuration (JSON text) */
	uint64_t seed; /* random seed (0 when none was used) */
} dem_provenance;

/* Fill with this program's name and version and the current time; config
 * is copied. */
void prov_init(dem_provenance *p, const char *program, const char *config, uint64_t seed);
void prov_free(dem_provenance *p);
/* Write the provenance attributes on an object (the file root, with
 * `format` unless format is NULL). */
int prov_write(hid_t file, const char *format, const dem_provenance *p);
int prov_read(hid_t file, dem_provenance *p);

#endif
