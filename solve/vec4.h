/* Four doubles as one of GCC's generic vectors, and the transpose of four
 * of them: the vector units of whatever CPU a function is compiled for
 * (clones.h, or a target attribute) do the work, and values are only
 * moved, so results are the same on every CPU. */
#ifndef DEM_VEC4_H
#define DEM_VEC4_H

/* Four doubles, read and written at any 8-byte boundary. */
typedef double vec4 __attribute__((vector_size(32), aligned(8)));

/* The transpose of the rows a[0..4): out[c] holds a[0..4)[c]. */
static inline void vec4_transpose(const vec4 a[4], vec4 out[4])
{
	vec4 t0 = __builtin_shufflevector(a[0], a[1], 0, 4, 2, 6),
	     t1 = __builtin_shufflevector(a[0], a[1], 1, 5, 3, 7),
	     t2 = __builtin_shufflevector(a[2], a[3], 0, 4, 2, 6),
	     t3 = __builtin_shufflevector(a[2], a[3], 1, 5, 3, 7);
	out[0] = __builtin_shufflevector(t0, t2, 0, 1, 4, 5);
	out[1] = __builtin_shufflevector(t1, t3, 0, 1, 4, 5);
	out[2] = __builtin_shufflevector(t0, t2, 2, 3, 6, 7);
	out[3] = __builtin_shufflevector(t1, t3, 2, 3, 6, 7);
}

#endif
