/* Driving one bond of a law by prescribed relative displacements, as the
 * engine does, without dynamics: the tests of the laws are written on top
 * of these few helpers. */
#ifndef DEM_TEST_LAWS_DRIVE_H
#define DEM_TEST_LAWS_DRIVE_H

#include <stdint.h>
#include <string.h>

#include "lib/cfg.h"
#include "lib/err.h"
#include "lib/states.h"
#include "solve/law.h"
#include "solve/laws/material.h"
#include "tests/check.h"

#define PI 3.14159265358979323846

/* Parse a material given as JSON text the way the engine reads a material
 * file (material_parse, then no key may be left unused) and keep the
 * parameters of its law, which must be L. NULL (and err_msg) on error. */
static inline law_params *drive_parse(const law *L, const char *json, const char *source)
{
	cfg *c = cfg_parse(json, source);
	if (!c)
		return NULL;
	material m;
	law_params *p = NULL;
	if (material_parse(c, &m) == 0 && cfg_check_unused(c) == 0) {
		if (m.law == L) {
			p = m.params;
			m.params = NULL;
		} else
			err_set("%s: law \"%s\": expected \"%s\"", source, m.law->name, L->name);
	}
	material_free(&m);
	cfg_free(c);
	return p;
}

/* The error message of a material that must not parse. */
static inline const char *drive_error(const law *L, const char *json, const char *source)
{
	law_params *p = drive_parse(L, json, source);
	if (p) {
		L->free(p);
		return "(parsed without error)";
	}
	return err_msg();
}

/* The normal displacement of the last force() call (0 for a new bond), for
 * energy(). */
static double drive_last_un;

/* A new bond between the two spheres of pair. */
static inline bond drive_bond(const law *L, const law_params *p, const law_pair *pair)
{
	bond b;
	memset(&b, 0, sizeof b);
	b.i = 0;
	b.j = 1;
	b.d0 = pair->d0;
	L->init(p, pair, &b);
	drive_last_un = 0;
	return b;
}

/* One call of force() with normal displacement un (opening positive), normal
 * velocity vn and tangential increment (dx, dy, dz). */
static inline law_out drive_step(const law *L, const law_params *p, const law_pair *pair, bond *b,
                                 double un, double vn, double dx, double dy, double dz)
{
	law_kin k = {.un = un, .vn = vn, .dus = {dx, dy, dz}};
	law_out o;
	memset(&o, 0x55, sizeof o);
	o.fn_viscous = o.e_damage = o.e_friction = 0; /* as the engine does */
	L->force(p, pair, b, &k, &o);
	drive_last_un = un;
	return o;
}

/* The elastic energy stored in the bond after the last drive_step. */
static inline double drive_energy(const law *L, const law_params *p, const law_pair *pair,
                                  const bond *b)
{
	return L->energy(p, pair, b, drive_last_un);
}

/* Normal path from un0 to un1 in n equal steps with no shear. Returns the
 * work done on the bond, the integral of fn dun (tension and opening both
 * positive) by the trapezoidal rule: exact for a piecewise-linear law when
 * every kink falls on a step. */
static inline double drive_normal(const law *L, const law_params *p, const law_pair *pair, bond *b,
                                  double un0, double un1, int n, double *fn_last)
{
	law_out o = drive_step(L, p, pair, b, un0, 0, 0, 0, 0);
	double w = 0, f0 = o.fn;
	for (int s = 1; s <= n; s++) {
		double u = un0 + (un1 - un0) * s / n;
		o = drive_step(L, p, pair, b, u, 0, 0, 0, 0);
		w += 0.5 * (f0 + o.fn) * ((un1 - un0) / n);
		f0 = o.fn;
	}
	if (fn_last)
		*fn_last = o.fn;
	return w;
}

/* Energy bookkeeping along a path: the work done on the bond by the
 * trapezoidal rule, fn dun + fs . dus (fs acts on i and j moves by dus
 * relative to i), and the dissipation the law reports. */
typedef struct {
	law_out last;
	double un, work, dissipated;
} drive_books;

static inline law_out drive_booked(const law *L, const law_params *p, const law_pair *pair, bond *b,
                                   drive_books *k, double un, double dx, double dy, double dz)
{
	law_out o = drive_step(L, p, pair, b, un, 0, dx, dy, dz);
	const double dus[3] = {dx, dy, dz};
	k->work += 0.5 * (k->last.fn + o.fn) * (un - k->un);
	for (int c = 0; c < 3; c++)
		k->work += 0.5 * (k->last.fs[c] + o.fs[c]) * dus[c];
	k->dissipated += o.e_damage + o.e_friction;
	k->last = o;
	k->un = un;
	return o;
}

/* drive_booked, returning the energy balance of the step: the work done less
 * the change of stored energy and the dissipation (zero for a law that
 * books its energy exactly). */
static inline double drive_balance(const law *L, const law_params *p, const law_pair *pair, bond *b,
                                   drive_books *k, double un, double dx, double dy, double dz)
{
	double e0 = drive_energy(L, p, pair, b), w0 = k->work, d0 = k->dissipated;
	drive_booked(L, p, pair, b, k, un, dx, dy, dz);
	return (k->work - w0) - (drive_energy(L, p, pair, b) - e0) - (k->dissipated - d0);
}

static inline double drive_fs(const law_out *o)
{
	return sqrt(o->fs[0] * o->fs[0] + o->fs[1] * o->fs[1] + o->fs[2] * o->fs[2]);
}

#endif
