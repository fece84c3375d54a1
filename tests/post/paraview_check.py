"""Check the picture share/paraview/show_run.py saved of a run: its size,
that it is not blank, and that the colours are where the data put them.

    python3 paraview_check.py SHOW.png VTK_DIR W H [--bonds]

Reads the PNG and the VTK files with Debian's python3-vtk9 (what
libvtk9-dev brings), not with ParaView. The picture is two views side by
side, each W/2 x H. Right view: each crack disc's centre is projected with
the camera of show_run.py's camera() and the pixel there (or next to it)
must have the colour of inverted Viridis at the axial strain at which the
crack formed, over the 2nd to 98th percentile of those strains; most of
them must, and clearly more than with another crack's strain. Left view:
likewise each sphere behind the cut in sight at its centre, with inverted
Inferno at its damage (0 to the 99th percentile). With --bonds (a picture
of show_run.py --bonds: three views, each W/3 x H), the third view too:
each broken bond's midpoint in the colour of its mode. Also that each
view's title fits in it. Prints what it measured; exits 1 with the reason
on the first check that fails.
"""
import math
import os
import sys
import xml.etree.ElementTree as ET

from vtkmodules.vtkIOImage import vtkPNGReader
from vtkmodules.vtkIOXML import vtkXMLPolyDataReader, vtkXMLUnstructuredGridReader
from vtkmodules.vtkRenderingCore import vtkCamera

# matplotlib's Viridis and Inferno at 0, 1/4, 1/2, 3/4, 1.
VIRIDIS = [(68, 1, 84), (59, 82, 139), (33, 145, 140), (94, 201, 98), (253, 231, 37)]
INFERNO = [(0, 0, 4), (87, 16, 110), (188, 55, 84), (249, 142, 9), (252, 255, 164)]
TENSION = (214, 39, 40)  # share/gnuplot/style.gp colours
SHEAR = (31, 78, 158)
BACKGROUND = (255, 255, 255)


def fail(msg):
    print("FAIL: " + msg)
    sys.exit(1)


def last_file(vtk_dir, pvd):
    root = ET.parse(os.path.join(vtk_dir, pvd)).getroot()
    sets = root.iter("DataSet")
    return os.path.join(vtk_dir, list(sets)[-1].get("file"))


def first_file(vtk_dir, pvd):
    root = ET.parse(os.path.join(vtk_dir, pvd)).getroot()
    return os.path.join(vtk_dir, next(root.iter("DataSet")).get("file"))


def read(reader, name):
    r = reader()
    r.SetFileName(name)
    r.Update()
    return r.GetOutput()


def array(data, name):
    a = data.GetCellData().GetArray(name) or data.GetPointData().GetArray(name)
    return [a.GetTuple(k) for k in range(a.GetNumberOfTuples())] if a is not None else []


def percentile(xs, p):
    s = sorted(xs)
    r = (len(s) - 1) * p / 100.0
    k = int(math.floor(r))
    f = r - k
    return s[k] if k + 1 >= len(s) else s[k] * (1 - f) + s[k + 1] * f


def colour(table, s):
    """The map's colour at s in [0, 1], linear between the control points."""
    s = min(1.0, max(0.0, s)) * (len(table) - 1)
    k = min(int(s), len(table) - 2)
    f = s - k
    return tuple(table[k][i] * (1 - f) + table[k + 1][i] * f for i in range(3))


def near(pixel, target, tol):
    """Within tol of the target colour, allowing the shading of a lit
    surface (a common factor) and the pale translucent specimen in front."""
    best = 1e9
    for shade in (0.55, 0.65, 0.75, 0.85, 1.0):
        for veil in (0.0, 0.1, 0.2):
            c = [(1 - veil) * shade * target[i] + veil * 230 for i in range(3)]
            best = min(best, math.sqrt(sum((pixel[i] - c[i]) ** 2 for i in range(3))))
    return best <= tol


def main(argv):
    png, vtk_dir, w, h = argv[0], argv[1], int(argv[2]), int(argv[3])
    bonds = argv[4:] == ["--bonds"]
    vw, vh = w // (3 if bonds else 2), h  # each view
    image = read(vtkPNGReader, png)
    dims = image.GetDimensions()
    if (dims[0], dims[1]) != (w, h):
        fail("%s is %d x %d, not %d x %d" % (png, dims[0], dims[1], w, h))
    scalars = image.GetPointData().GetScalars()
    nc = scalars.GetNumberOfComponents()

    def pixel(x, y):  # y up from the bottom row, as VTK stores images
        return scalars.GetTuple(y * w + x)[:3]

    # Not blank: each view has drawn pixels and many colours.
    for name, x0 in (("left", 0), ("right", vw), ("bonds", 2 * vw))[:3 if bonds else 2]:
        drawn, colours = 0, set()
        for y in range(0, h, 2):
            for x in range(x0, x0 + vw, 2):
                p = pixel(x, y)
                colours.add(tuple(int(v) // 8 for v in p))
                drawn += p != BACKGROUND
        frac = drawn / float((h // 2) * (vw // 2))
        print("%s view: %.1f %% of pixels drawn, %d colours" % (name, 100 * frac, len(colours)))
        if frac < 0.05 or len(colours) < 50:
            fail("the %s view is (nearly) blank" % name)
    if nc not in (3, 4):
        fail("%s has %d components" % (png, nc))

    # Each view's title inside it: nothing drawn in the top eighth of the
    # picture within 3 to 13 pixels of a view's sides (a title too wide for
    # its view runs into them).
    for name, x0 in (("left", 0), ("right", vw), ("bonds", 2 * vw))[:3 if bonds else 2]:
        inked = 0
        for y in range(h - h // 8, h):
            for x in list(range(x0 + 3, x0 + 13)) + list(range(x0 + vw - 13, x0 + vw - 3)):
                inked += max(abs(v - b) for v, b in zip(pixel(x, y), BACKGROUND)) > 60
        if inked:
            fail("the %s view's title runs into its sides (%d pixels)" % (name, inked))

    # The camera of show_run.py's camera(), from the platens.
    def platens(name):
        data = read(vtkXMLPolyDataReader, name)
        centres = []
        for c in range(data.GetNumberOfCells()):
            ids = data.GetCell(c).GetPointIds()
            pts = [data.GetPoint(ids.GetId(k)) for k in range(ids.GetNumberOfIds())]
            centres.append([sum(p[i] for p in pts) / len(pts) for i in range(3)])
        lo, hi = centres[0], centres[1]
        d = [hi[i] - lo[i] for i in range(3)]
        length = math.sqrt(sum(x * x for x in d))
        return [(lo[i] + hi[i]) / 2 for i in range(3)], [x / length for x in d], length

    centre, axis, length = platens(last_file(vtk_dir, "platens.pvd"))
    k = min(range(3), key=lambda i: abs(axis[i]))
    u = [1.0 if i == k else 0.0 for i in range(3)]
    dot = sum(u[i] * axis[i] for i in range(3))
    towards = [u[i] - dot * axis[i] for i in range(3)]
    n = math.sqrt(sum(x * x for x in towards))
    towards = [x / n for x in towards]
    focus = [centre[i] - 0.1 * length * axis[i] for i in range(3)]
    cam = vtkCamera()
    cam.SetFocalPoint(focus)
    cam.SetPosition([focus[i] + 3.2 * length * towards[i] for i in range(3)])
    cam.SetViewUp(axis)
    cam.SetViewAngle(30)
    cam.SetClippingRange(0.1 * length, 10 * length)
    m = cam.GetCompositeProjectionTransformMatrix(vw / float(vh), -1, 1)

    def project(p, x0):
        q = [sum(m.GetElement(r, c) * (list(p) + [1.0])[c] for c in range(4)) for r in range(4)]
        return int(round(x0 + (q[0] / q[3] + 1) / 2 * vw)), int(round((q[1] / q[3] + 1) / 2 * vh))

    # Right view: each crack's colour at its centre.
    cracks = read(vtkXMLPolyDataReader, last_file(vtk_dir, "cracks.pvd"))
    strain = [100 * e[0] for e in array(cracks, "strain_axial")]
    if len(strain) < 10:
        fail("too few cracks (%d) in %s to check their colours" % (len(strain), vtk_dir))
    lo, hi = percentile(strain, 2), percentile(strain, 98)
    ids = [c[0] for c in array(cracks, "crack")]
    centres = {}
    for c in range(cracks.GetNumberOfCells()):
        cell = cracks.GetCell(c).GetPointIds()
        pts = [cracks.GetPoint(cell.GetId(j)) for j in range(cell.GetNumberOfIds())]
        centres[c] = [sum(p[i] for p in pts) / len(pts) for i in range(3)]
    good = looked = 0
    for c, e in enumerate(strain):
        x, y = project(centres[c], vw)
        if not (vw + 2 <= x < 2 * vw - 2 and 2 <= y < h - 2):
            continue
        looked += 1
        want = colour(VIRIDIS, 1 - (e - lo) / (hi - lo))  # inverted
        if any(near(pixel(x + dx, y + dy), want, 40) for dx in (-1, 0, 1) for dy in (-1, 0, 1)):
            good += 1
    print("right view: %d of %d crack centres (%d cracks, ids %d-%d) have the colour of the "
          "strain at which they formed (%.3g-%.3g %%)" %
          (good, looked, len(strain), min(ids), max(ids), lo, hi))
    if looked < 0.9 * len(strain):
        fail("only %d of %d crack centres fall inside the right view" % (looked, len(strain)))
    if good < 0.6 * looked:
        fail("the cracks do not have the colours of the strains at which they formed")
    # ... and not just because every colour of the map is about: where the
    # map puts another crack's strain well apart, the pixel has this
    # crack's colour and not that one.
    def matches(c, e):
        x, y = project(centres[c], vw)
        want = colour(VIRIDIS, 1 - (e - lo) / (hi - lo))
        return any(near(pixel(x + dx, y + dy), want, 40) for dx in (-1, 0, 1) for dy in (-1, 0, 1))

    pairs = own = other = 0
    for c, e in enumerate(strain):
        x, y = project(centres[c], vw)
        f = strain[(c + len(strain) // 2) % len(strain)]
        if not (vw + 2 <= x < 2 * vw - 2 and 2 <= y < h - 2) or abs(e - f) < 0.3 * (hi - lo):
            continue
        pairs += 1
        own += matches(c, e)
        other += matches(c, f)
    print("right view: of %d cracks paired with one of a strain well apart, %d have their own "
          "colour, %d the other's" % (pairs, own, other))
    if pairs >= 10 and own - other < 0.3 * pairs:
        fail("the crack colours do not follow the strain at which each crack formed")

    # Left view: each sphere behind the cut that nothing hides at its centre
    # has there the colour of inverted Inferno at its damage, over 0 to the
    # 99th percentile (at least 0.05).
    particles = read(vtkXMLUnstructuredGridReader, last_file(vtk_dir, "particles.pvd"))
    damage = [d[0] for d in array(particles, "damage")]
    radius = [r[0] for r in array(particles, "radius")]
    dhi = min(1.0, max(0.05, percentile(damage, 99)))
    eye = cam.GetPosition()
    kept = [i for i in range(particles.GetNumberOfPoints())
            if sum((particles.GetPoint(i)[k] - centre[k]) * towards[k] for k in range(3)) <= 0]
    pos = {i: particles.GetPoint(i) for i in kept}

    def hidden(i):
        d = [pos[i][k] - eye[k] for k in range(3)]
        far = math.sqrt(sum(x * x for x in d))
        d = [x / far for x in d]
        for j in kept:
            if j == i:
                continue
            v = [pos[j][k] - eye[k] for k in range(3)]
            t = sum(v[k] * d[k] for k in range(3))
            off2 = sum(x * x for x in v) - t * t
            if off2 < radius[j] ** 2 and t - math.sqrt(radius[j] ** 2 - off2) < far - radius[i]:
                return True
        return False

    seen = [i for i in kept if not hidden(i)]

    def sphere_matches(i, d):
        x, y = project(pos[i], 0)
        want = colour(INFERNO, 1 - d / dhi)
        return any(near(pixel(x + dx, y + dy), want, 40) for dx in (-1, 0, 1) for dy in (-1, 0, 1))

    good = sum(sphere_matches(i, damage[i]) for i in seen)
    print("left view: %d of %d spheres behind the cut (%d in sight) have the colour of their "
          "damage (0-%.2f)" % (good, len(kept), len(seen), dhi))
    if len(seen) < 20:
        fail("only %d spheres in sight behind the cut" % len(seen))
    if good < 0.6 * len(seen):
        fail("the spheres do not have the colours of their damage")
    pairs = own = other = 0
    for n, i in enumerate(seen):
        e = damage[seen[(n + len(seen) // 2) % len(seen)]]
        if abs(min(e, dhi) - min(damage[i], dhi)) < 0.3 * dhi:
            continue
        pairs += 1
        own += sphere_matches(i, damage[i])
        other += sphere_matches(i, e)
    print("left view: of %d spheres paired with one of a damage well apart, %d have their own "
          "colour, %d the other's" % (pairs, own, other))
    if pairs >= 10 and own - other < 0.3 * pairs:
        fail("the sphere colours do not follow their damage")
    if bonds:
        check_bonds(vtk_dir, pixel, project, 2 * vw, vw, h)
    print("ok")


def check_bonds(vtk_dir, pixel, project, x0, vw, h):
    """Third view: each broken bond's midpoint in the colour of its mode,
    and clearly more often than in the other mode's colour."""
    data = read(vtkXMLPolyDataReader, last_file(vtk_dir, "bonds.pvd"))
    state = [s[0] for s in array(data, "state")]
    good = other = looked = 0
    for c, st in enumerate(state):
        if st < 2:
            continue
        ids = data.GetCell(c).GetPointIds()
        a, b = data.GetPoint(ids.GetId(0)), data.GetPoint(ids.GetId(1))
        x, y = project([(a[i] + b[i]) / 2 for i in range(3)], x0)
        if not (x0 + 2 <= x < x0 + vw - 2 and 2 <= y < h - 2):
            continue
        looked += 1
        own, alt = (TENSION, SHEAR) if st == 2 else (SHEAR, TENSION)
        around = [pixel(x + dx, y + dy) for dx in (-1, 0, 1) for dy in (-1, 0, 1)]
        good += any(near(p, own, 40) for p in around)
        other += any(near(p, alt, 40) for p in around)
    print("bonds view: %d of %d broken bonds in sight have the colour of their mode at their "
          "midpoint, %d the other mode's" % (good, looked, other))
    if looked < 10:
        fail("too few broken bonds (%d) in sight to check their colours" % looked)
    if good < 0.6 * looked or good - other < 0.3 * looked:
        fail("the broken bonds do not have the colours of their modes")


main(sys.argv[1:])
