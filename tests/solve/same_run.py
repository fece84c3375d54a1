"""Whether two run files hold the same run, bit for bit: every dataset and
attribute the same but those that record when and how fast it ran (the
creation time, the history's wall-clock rate) and HDF5's own bookkeeping of
dimension scales (object references).

With --chunks, the bond table's and the snapshots' datasets must also be
stored the same: the same chunks, each with its filter mask and its
compressed bytes.

Usage: same_run.py [--chunks] A.h5 B.h5   (exit status 0 when the same, 1 if
not)"""
import sys

import h5py
import numpy as np

SKIP_ATTRS = {"created", "REFERENCE_LIST", "DIMENSION_LIST"}
SKIP_DATA = {"/history/rate"}


def items(f):
    out = {"/": f}

    def add(name, obj):
        out["/" + name] = obj  # visititems stops at a callback's first non-None

    f.visititems(add)
    return out


def same_array(a, b):
    a, b = np.asarray(a), np.asarray(b)
    if a.shape != b.shape or a.dtype != b.dtype:
        return False
    return a.tobytes() == b.tobytes()


def stored(d):
    """A dataset's chunks as stored: offset, filter mask, bytes."""
    if not d.chunks or d.is_virtual:
        return None
    out = []
    for k in range(d.id.get_num_chunks()):
        offset = d.id.get_chunk_info(k).chunk_offset
        mask, data = d.id.read_direct_chunk(offset)
        out.append((offset, mask, bytes(data)))
    return out


def main(pa, pb, chunks=False):
    diffs = []
    with h5py.File(pa, "r") as fa, h5py.File(pb, "r") as fb:
        ia, ib = items(fa), items(fb)
        for name in sorted(set(ia) | set(ib)):
            if name not in ia or name not in ib:
                diffs.append("%s: only in %s" % (name, pa if name in ia else pb))
                continue
            a, b = ia[name], ib[name]
            for k in sorted(set(a.attrs) | set(b.attrs)):
                if k in SKIP_ATTRS:
                    continue
                if k not in a.attrs or k not in b.attrs or not same_array(a.attrs[k], b.attrs[k]):
                    diffs.append("%s: attribute %s differs" % (name, k))
            if isinstance(a, h5py.Dataset) and name not in SKIP_DATA:
                if not same_array(a[()], b[()]):
                    diffs.append("%s: data differ" % name)
                elif (chunks and name.startswith(("/bonds/", "/snapshots/"))
                      and stored(a) != stored(b)):
                    diffs.append("%s: stored chunks differ" % name)
    for d in diffs[:20]:
        print(d)
    print("%s and %s: %s (%d objects compared)" % (
        pa, pb, "the same" if not diffs else "%d differences" % len(diffs), len(ia)))
    return 1 if diffs else 0


if __name__ == "__main__":
    args = [a for a in sys.argv[1:] if a != "--chunks"]
    sys.exit(main(args[0], args[1], chunks="--chunks" in sys.argv[1:]))
