/* The Morton key interleaves the coordinates' bits (x lowest) over all 21
 * bits of each, and the sort breaks ties by index: pack and solve both lay
 * their spheres out in this order, which decides the bits of their
 * results. */
#include <stdint.h>

#include "lib/morton.h"
#include "tests/check.h"

int main(void)
{
	CHECK(morton_key((const uint64_t[3]){1, 0, 0}) == 1);
	CHECK(morton_key((const uint64_t[3]){0, 1, 0}) == 2);
	CHECK(morton_key((const uint64_t[3]){0, 0, 1}) == 4);
	/* In octal, one digit per bit level: z 4, y 2, x 1. */
	CHECK(morton_key((const uint64_t[3]){2, 0, 3}) == 054);
	uint64_t top = (uint64_t)1 << (MORTON_BITS - 1), all = ((uint64_t)1 << MORTON_BITS) - 1;
	CHECK(morton_key((const uint64_t[3]){0, 0, top}) == (uint64_t)1 << (3 * MORTON_BITS - 1));
	CHECK(morton_key((const uint64_t[3]){all, all, all}) ==
	      ((uint64_t)1 << 3 * MORTON_BITS) - 1);
	CHECK(morton_key((const uint64_t[3]){all + 1, 0, 0}) == 0);

	uint64_t key[6] = {7, 3, 7, 0, 3, 7};
	size_t order[6], want[6] = {3, 1, 4, 0, 2, 5};
	morton_sort(key, 6, order);
	int same = 1;
	for (int k = 0; k < 6; k++)
		same &= order[k] == want[k];
	CHECK(same);
	morton_sort(key, 0, order);
	return check_done();
}
