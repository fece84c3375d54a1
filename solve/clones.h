/* Multiversioning of the hot loops (the bond, contact and particle blocks
 * and the laws' batch loops): see DEM_VECTOR_CLONES. */
#ifndef DEM_CLONES_H
#define DEM_CLONES_H

/* The functions that compute a block (bonds, contacts, particles) and the
 * laws' batch loops are compiled three times, for x86-64 with AVX-512
 * (x86-64-v4), with AVX2 (v3) and for any x86-64, and the CPU picks one at
 * start; so the default build, which must run on any x86-64, uses the
 * vector units of the CPU it runs on. Results are the same to the bit on
 * every CPU: C17 does not let the compiler fuse a multiply and an add, and
 * no sum is reordered. Builds for this machine only (-march=native,
 * DEM_NATIVE) need one version; GCC makes the versions (clang, for the fuzz
 * targets, does not combine them with flatten). The versions are tuned as
 * -march=native tunes for recent Intel cores: 256-bit vectors and gather
 * instructions (CMakeLists.txt). A helper they call is compiled for any
 * x86-64 unless it is inlined: the hot ones are always_inline. */
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__) && \
    !defined(DEM_NATIVE_BUILD) && !defined(__SANITIZE_ADDRESS__)
#define DEM_VECTOR_CLONES \
	__attribute__((target_clones("arch=x86-64-v4", "arch=x86-64-v3", "default")))
#else
#define DEM_VECTOR_CLONES
#endif

/* The laws' fused loops (law.force_pairs, LAW_PAIRS_VERSIONS in
 * kinematics.h) and the particles' (integrate_free, solve/step.c) have one
 * version more (DEM_VERSIONS), for x86-64 with AVX-512 and 512-bit vectors
 * (DEM_WIDE_VECTORS), which AMD's cores with AVX-512 (Zen 4 and later)
 * run, at their full clock: on a Zen 5 the bond phase runs about 7 %
 * faster with it, the particles' a sixth (share/doc/solve.md). Intel's
 * keep the 256-bit vectors GCC tunes them for (512-bit ones lower the
 * clock of several of them). The lanes are computed alike, so the results
 * are the same to the bit. */
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__) && \
    !defined(__SANITIZE_ADDRESS__)
#ifdef DEM_NATIVE_BUILD
#define DEM_WIDE_VECTORS __attribute__((target("prefer-vector-width=512")))
#else
#define DEM_WIDE_VECTORS __attribute__((target("arch=x86-64-v4,prefer-vector-width=512")))
#endif
/* Whether this CPU runs the DEM_WIDE_VECTORS versions. */
static inline int dem_wide_vectors(void)
{
	return __builtin_cpu_is("amd") && __builtin_cpu_supports("x86-64-v4");
}
#endif

/* The function NAME PARAMS returning RET (RETURN: return, or nothing for
 * void) from BODY, an always-inline function called with ARGS (NAME's
 * parameters): the versions of DEM_VECTOR_CLONES and, where the compiler
 * makes it, the 512-bit one, which NAME calls on the CPUs that run it
 * (dem_wide_vectors). */
#ifdef DEM_WIDE_VECTORS
#define DEM_VERSIONS(RET, RETURN, NAME, PARAMS, ARGS, BODY)                                  \
	DEM_WIDE_VECTORS __attribute__((flatten, noinline)) static RET NAME##_wide PARAMS    \
	{                                                                                    \
		RETURN BODY ARGS;                                                            \
	}                                                                                    \
	DEM_VECTOR_CLONES __attribute__((flatten, noinline)) static RET NAME##_narrow PARAMS \
	{                                                                                    \
		RETURN BODY ARGS;                                                            \
	}                                                                                    \
	static RET NAME PARAMS                                                               \
	{                                                                                    \
		if (dem_wide_vectors()) {                                                    \
			RETURN NAME##_wide ARGS;                                             \
		} else {                                                                     \
			RETURN NAME##_narrow ARGS;                                           \
		}                                                                            \
	}
#else
#define DEM_VERSIONS(RET, RETURN, NAME, PARAMS, ARGS, BODY)                         \
	DEM_VECTOR_CLONES __attribute__((flatten, noinline)) static RET NAME PARAMS \
	{                                                                           \
		RETURN BODY ARGS;                                                   \
	}
#endif

#endif
