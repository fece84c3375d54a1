"""Checks of a run file read with h5py and xarray (share/doc/format.md):
the history opens with t as its coordinate, units are CF's `units`,
integers are integers, the crack log and the bond table have their row
dimensions, and /snapshots holds every field over time, equal to the
snapshots' own datasets. A run of format 2 continued by this build keeps
its layout (the `unit` attributes, float64 steps) and gains the snapshot
series. Usage: python.py RUN.h5 [VERSION] (default 3)"""
import sys

import h5py
import numpy as np
import xarray as xr

path = sys.argv[1]
version = int(sys.argv[2]) if len(sys.argv) > 2 else 3
failures = []


def check(ok, what):
    if not ok:
        failures.append(what)
        print("FAIL:", what, file=sys.stderr)


f = h5py.File(path, "r")
check(f.attrs["format_version"] == version, "format_version %d" % version)
status = f.attrs["status"]
check(status == b"complete" or status.startswith(b"stopped: "), "status %r" % status)


def check_series():
    """The snapshots over time: one read gives a field at every snapshot."""
    s = xr.open_dataset(path, group="snapshots", engine="h5netcdf")
    names = sorted(k for k in f["snapshots"] if k.isdigit())
    check(len(names) == 4, "snapshots %r" % names)
    check(s.x.dims == ("t", "particle", "xyz"), "snapshot x dims %r" % (s.x.dims,))
    check(s.bond_fs.dims == ("t", "bond", "xyz"), "snapshot bond_fs dims")
    check(s.sizes["t"] == len(names), "one t per snapshot")
    check(s.step.dtype == np.int64, "snapshot step dtype")
    check(s.x.attrs.get("units") == "m" and s.t.attrs.get("units") == "s", "snapshot units")
    x = s.x.values  # [snapshot, particle, 3] in one read
    state = f["snapshots/bond_state"][:]
    for k, name in enumerate(names):
        g = f["snapshots/" + name]
        check(int(s.step[k]) == g.attrs["step"] == int(name), "step of snapshot %s" % name)
        check(float(s.t[k]) == g.attrs["t"], "t of snapshot %s" % name)
        check(np.array_equal(x[k], g["x"][:]), "x of snapshot %s" % name)
        check(np.array_equal(state[k], g["bond_state"][:]), "bond_state of %s" % name)
        check(np.array_equal(s.bond_fn.values[k], g["bond_fn"][:]), "bond_fn of %s" % name)
    # A time series of one particle, and of the broken bonds.
    z = s.x.isel(particle=0, xyz=2).values
    check(z.shape == (len(names),) and bool(np.all(np.isfinite(z))), "one particle's z")
    check(not np.array_equal(x[0], x[-1]), "the particles moved")
    broken = (state >= 2).sum(axis=1)
    check(broken[0] == 0 and broken[-1] > 0, "broken bonds over time %r" % broken)
    return names


if version == 2:
    check_series()
    check(f["history/step"].dtype == np.float64, "format 2 history step")
    check("unit" in f["history/stress_axial"].attrs, "format 2 unit attribute")
    if failures:
        sys.exit("%d check(s) failed" % len(failures))
    print("ok: format 2 run continued, %d snapshots" % f["snapshots/t"].shape[0])
    sys.exit(0)

# History: the rows are the dimension t, t its coordinate.
h = xr.open_dataset(path, group="history", engine="h5netcdf")
check(h.stress_axial.dims == ("t",), "history dims %r" % (h.stress_axial.dims,))
check("t" in h.coords and h.t.size == f["history/t"].shape[0], "history coordinate t")
check(bool(np.all(np.diff(h.t.values) > 0)), "history t increasing")
check(h.t.attrs.get("units") == "s", "history t units %r" % h.t.attrs.get("units"))
check(h.stress_axial.attrs.get("units") == "Pa", "stress_axial units")
check(h.rate.attrs.get("units") == "1/s", "rate units")
check(h.step.dtype == np.int64, "history step dtype %s" % h.step.dtype)
check(h.stage.dtype == np.int32, "history stage dtype %s" % h.stage.dtype)
for name in ("bonds_intact", "bonds_damaged", "bonds_broken_tension",
             "bonds_broken_shear", "contacts", "contacts_platen"):
    check(h[name].dtype == np.int64, "history %s dtype %s" % (name, h[name].dtype))
check(int(h.bonds_intact[0]) > 0, "bonds at the start")
check(int(h.step[0]) == 0 and int(h.step[1]) == 100, "history steps %r" % h.step.values[:2])
check(bool(np.all(h.stage.values == 1)), "one stage")
columns = f["history"].attrs["columns"].decode().split(",")
check(set(columns) <= set(h.variables), "every column read")
check(np.array_equal(h.stress_axial.values, f["history/stress_axial"][:]), "history values")
check(float(h.stress_axial[-1]) > 0, "the specimen is loaded")

# No dataset carries the old name of the attribute.
old = []
f.visititems(lambda n, o: old.append(n) if "unit" in o.attrs else None)
check(not old, "datasets with a `unit` attribute: %r" % old[:5])

# Cracks: rows are the dimension crack, t a coordinate.
c = xr.open_dataset(path, group="cracks", engine="h5netcdf")
n = f["cracks/t"].shape[0]
check(n > 0, "the run has cracks")
check(c.fn.dims == ("crack",) and c.sizes["crack"] == n, "crack dimension")
check(c.x.dims == ("crack", "xyz"), "crack x dims %r" % (c.x.dims,))
check("t" in c.coords and c.t.attrs.get("units") == "s", "crack coordinate t")
check(c.step.dtype == np.int64 and c.i.dtype == np.int32, "crack integer types")
check(bool(np.all(np.diff(c.t.values) >= 0)), "cracks in order of failure")

# Bonds and particles: rows are the dimensions bond and particle.
b = xr.open_dataset(path, group="bonds", engine="h5netcdf")
check(b.d0.dims == ("bond",) and b.d0.attrs.get("units") == "m", "bond table")
check(b.i.dtype == np.int32 and b.sizes["bond"] == f["bonds/i"].shape[0], "bond index")
p = xr.open_dataset(path, group="particles", engine="h5netcdf")
check(p.x.dims == ("particle", "xyz") and p.r.attrs.get("units") == "m", "particles")

names = check_series()
one = xr.open_dataset(path, group="snapshots/" + names[-1], engine="h5netcdf")
check(one.x.dims == ("particle", "xyz"), "a single snapshot's dims")

if failures:
    sys.exit("%d check(s) failed" % len(failures))
print("ok: history %d rows, %d cracks, %d snapshots" % (h.sizes["t"], n, len(names)))
