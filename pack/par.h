/* Below PAR_MIN spheres a loop runs on one thread: the work of one pass
 * over a few thousand spheres is smaller than the cost of waking threads
 * for it, all the more on a machine shared with other work. (Results do
 * not depend on it: every parallel sum is taken in fixed blocks.) */
#ifndef PACK_PAR_H
#define PACK_PAR_H

#define PAR_MIN 8192

#endif
