/* Below PAR_MIN spheres a loop runs on one thread: one pass over a
 * thousand or two spheres costs less than waking the threads for it.
 * (Results do not depend on it: every parallel sum is taken in fixed
 * blocks.) */
#ifndef PACK_PAR_H
#define PACK_PAR_H

#define PAR_MIN 2048

#endif
