/* Exact sums of doubles (xsum.h). */
#include <math.h>
#include <string.h>

#include "lib/xsum.h"

static const uint64_t M32 = 0xffffffffu;

void xsum_clear(xsum *s) { memset(s, 0, sizeof *s); }

void xsum_add(xsum *s, double x)
{
	if (x == 0)
		return;
	if (!isfinite(x)) {
		s->d[isnan(x) ? XSUM_NAN : x > 0 ? XSUM_PINF : XSUM_NINF]++;
		return;
	}
	uint64_t bits;
	memcpy(&bits, &x, sizeof bits);
	int e = (int)(bits >> 52 & 0x7ff);
	uint64_t m = bits & (((uint64_t)1 << 52) - 1);
	/* x = m 2^(p - 1074): a subnormal has p = 0, a normal number its
	 * implicit bit and p = e - 1. */
	int p = 0;
	if (e) {
		m |= (uint64_t)1 << 52;
		p = e - 1;
	}
	int k = p / 32, sh = p % 32;
	uint64_t lo = (m & M32) << sh, hi = (m >> 32) << sh;
	int64_t d0 = (int64_t)(lo & M32), d1 = (int64_t)((lo >> 32) + (hi & M32)),
	        d2 = (int64_t)(hi >> 32);
	if (bits >> 63) {
		d0 = -d0;
		d1 = -d1;
		d2 = -d2;
	}
	s->d[k] += d0;
	s->d[k + 1] += d1;
	s->d[k + 2] += d2;
}

void xsum_normalize(xsum *s)
{
	for (int k = 0; k < XSUM_DIGITS - 1; k++) {
		int64_t carry = s->d[k] >> 32; /* floor division: the digit stays >= 0 */
		s->d[k] -= carry * ((int64_t)1 << 32);
		s->d[k + 1] += carry;
	}
}

void xsum_merge(xsum *a, const xsum *b)
{
	for (int k = 0; k < DEM_XSUM_WORDS; k++)
		a->d[k] += b->d[k];
}

double xsum_round(const xsum *s)
{
	if (s->d[XSUM_NAN] || (s->d[XSUM_PINF] && s->d[XSUM_NINF]))
		return NAN;
	if (s->d[XSUM_PINF])
		return INFINITY;
	if (s->d[XSUM_NINF])
		return -INFINITY;
	/* Most of a step's sums are of nothing on most steps (the measuring
	 * sums, the contacts' when none touch): no digit to carry. */
	int64_t any = 0;
	for (int k = 0; k < XSUM_DIGITS; k++)
		any |= s->d[k];
	if (!any)
		return 0;
	xsum t = *s;
	xsum_normalize(&t);
	double sign = 1;
	if (t.d[XSUM_DIGITS - 1] < 0) {
		for (int k = 0; k < XSUM_DIGITS; k++)
			t.d[k] = -t.d[k];
		xsum_normalize(&t);
		sign = -1;
	}
	int top = XSUM_DIGITS - 1;
	while (top >= 0 && !t.d[top])
		top--;
	if (top < 0)
		return 0;
	/* The 64 bits below the leading one of the magnitude, from bit e0 up
	 * (e0 < 0 when the magnitude has fewer than 64 bits), and whether any
	 * bit below them is set. The top digit may exceed 32 bits. */
	uint64_t w = (uint64_t)t.d[top];
	int nb = 0;
	while (nb < 64 && w >> nb)
		nb++;
	int64_t len = 32 * (int64_t)top + nb, e0 = len - 64;
	uint64_t win = 0;
	int sticky = 0;
	for (int k = top; k >= 0; k--) {
		uint64_t dk = (uint64_t)t.d[k];
		int64_t off = 32 * (int64_t)k - e0;
		if (off >= 64)
			continue; /* cannot happen below the top digit */
		if (off >= 0)
			win |= dk << off;
		else if (off > -64) {
			win |= dk >> -off;
			sticky |= (dk & (((uint64_t)1 << -off) - 1)) != 0;
		} else
			sticky |= dk != 0;
	}
	/* Round the 64-bit window to 53 bits, to nearest, ties to even. */
	uint64_t q = win >> 11, rest = win & 0x7ff;
	if (rest > 0x400 || (rest == 0x400 && (sticky || (q & 1))))
		q++;
	return sign * ldexp((double)q, (int)(e0 + 11 - 1074));
}
