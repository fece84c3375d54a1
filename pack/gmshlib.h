/* The gmsh C API (gmshc.h), opened with dlopen when a geometry is first
 * built rather than linked: gmsh brings some hundred shared libraries
 * (OpenCASCADE, FLTK, ...) whose loading costs about 0.13 s, and pack
 * starts twice (see main.c), or not at all past its options when they are
 * wrong. */
#ifndef PACK_GMSHLIB_H
#define PACK_GMSHLIB_H

#include <gmshc.h>

/* Every function pack calls. */
/* clang-format off */
#define GMSH_FUNCTIONS(X) \
	X(gmshFinalize) \
	X(gmshFree) \
	X(gmshInitialize) \
	X(gmshLoggerGetLastError) \
	X(gmshLoggerStart) \
	X(gmshLoggerStop) \
	X(gmshModelGeoAddCircleArc) \
	X(gmshModelGeoAddCurveLoop) \
	X(gmshModelGeoAddLine) \
	X(gmshModelGeoAddPlaneSurface) \
	X(gmshModelGeoAddPoint) \
	X(gmshModelGeoExtrude) \
	X(gmshModelGeoMeshSetTransfiniteCurve) \
	X(gmshModelGeoMeshSetTransfiniteSurface) \
	X(gmshModelGeoSynchronize) \
	X(gmshModelGetBoundary) \
	X(gmshModelGetEntities) \
	X(gmshModelMeshGenerate) \
	X(gmshModelMeshGetElementFaceNodes) \
	X(gmshModelMeshGetElementProperties) \
	X(gmshModelMeshGetElementTypes) \
	X(gmshModelMeshGetElementsByType) \
	X(gmshModelMeshGetNodes) \
	X(gmshOpen) \
	X(gmshOptionSetNumber) \
	X(gmshOptionSetString)
/* clang-format on */

typedef struct {
#define GMSH_POINTER(f) __typeof__(f) *f;
	GMSH_FUNCTIONS(GMSH_POINTER)
#undef GMSH_POINTER
} gmsh_library;

/* The functions of the loaded library, or NULL (with err_set) when it
 * cannot be loaded. Not thread-safe: call it from one thread. */
const gmsh_library *gmshlib_load(void);

#endif
