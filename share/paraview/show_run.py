"""Show a run written by `post vtk` in ParaView, and save a picture.

    pvbatch share/paraview/show_run.py VTK_DIR [OUT.png] [--time T] [--size W H] [--bonds]
                                       [--ranges-at-end]
    paraview --script=share/paraview/show_run.py    (then VTK_DIR from $DEM_VTK_DIR; the
                                                     left view only, in the window's)

VTK_DIR is the directory `post vtk` wrote (particles.pvd, cracks.pvd,
platens.pvd, geometry.vtp). Two views side by side, at the last snapshot
(or the one at time T, s), under a title with the time, the axial strain
and the axial stress (compression positive) of that frame: its field data
(`post vtk` writes time, strain_axial and stress_axial in every frame);
in files without them, the run's history at that time from the curve.csv
`post curve` wrote beside VTK_DIR, else the change of the platens' distance
and their `stress_axial`:
  left   the spheres behind a cut through the loading axis, as sphere glyphs
         of their true radius, coloured by `damage` (the mean over a sphere's
         bonds of 1 for a broken bond, else its damage): the cut face shows
         where the bonds broke inside the specimen;
  right  every crack so far as a disc inside the translucent specimen,
         coloured by the axial strain at which it formed, so that the order
         in which the fracture grew shows;
  --bonds adds a third view: the broken-bond network, each broken bond
         (bonds.pvd, `state` 2 or 3) as a line between the two sphere
         centres, tension red and shear blue.
Each colour range runs between percentiles of what is shown (damage: 0 to
the 99th, at least 0.05; strain: 2nd to 98th), so that one outlier does not
set it; with --ranges-at-end the ranges are those of the last frame, the
same for every frame of a series (tools/render-series); the legends are horizontal bars inside each view. The loading axis
is found from the platens. With OUT.png the layout is saved, W x H pixels
(default 1280 x 640, which fits xvfb-run's default screen; 1920 x 640 with
--bonds).
"""
import math
import os
import sys

from paraview import servermanager
from paraview.simple import (
    AssignViewToLayout, Calculator, Clip, ColorBy, CreateLayout, CreateView,
    GetActiveView, GetColorTransferFunction, GetLayouts, GetOpacityTransferFunction, GetScalarBar, Glyph, PVDReader,
    Render, SaveScreenshot, Show, Text, Threshold, XMLPolyDataReader)

DAMAGE_MAP = "Inferno (matplotlib)"  # inverted: intact pale, broken dark
STRAIN_MAP = "Viridis (matplotlib)"  # inverted: first cracks yellow, last dark blue
DEFAULT_SIZE = (1280, 640)
# Text sizes at the default size; a narrower view (--size) shrinks them in
# proportion, so that the two-line titles still fit (set in main).
font_scale = 1.0
TENSION = [0.839, 0.153, 0.157]  # share/gnuplot/style.gp colours
SHEAR = [0.122, 0.306, 0.620]


def parse(argv):
    args = {"dir": os.environ.get("DEM_VTK_DIR"), "out": None, "time": None,
            "size": None, "bonds": False, "ranges_at_end": False}
    rest = list(argv)
    while rest:
        a = rest.pop(0)
        if a == "--time":
            args["time"] = float(rest.pop(0))
        elif a == "--bonds":
            args["bonds"] = True
        elif a == "--ranges-at-end":
            args["ranges_at_end"] = True
        elif a == "--size":
            args["size"] = (int(rest.pop(0)), int(rest.pop(0)))
        elif args["dir"] is None or (args["dir"] == os.environ.get("DEM_VTK_DIR") and
                                     not a.endswith(".png")):
            args["dir"] = a
        else:
            args["out"] = a
    if not args["dir"]:
        sys.exit("usage: pvbatch show_run.py VTK_DIR [OUT.png] [--time T] [--size W H] [--bonds] "
                 "[--ranges-at-end]")
    # The run.pvd that post vtk names, or any .pvd of its series: its directory.
    if args["dir"].endswith(".pvd") and os.path.isfile(args["dir"]):
        args["dir"] = os.path.dirname(os.path.abspath(args["dir"]))
    if not os.path.isfile(os.path.join(args["dir"], "particles.pvd")):
        sys.exit("show_run.py: %s: not a run's VTK directory (expected the directory post vtk "
                 "wrote, with particles.pvd and run.pvd)" % args["dir"])
    if args["size"] is None:
        w, h = DEFAULT_SIZE
        args["size"] = (w * 3 // 2, h) if args["bonds"] else (w, h)
    return args


def platen_axis(platens, t):
    """Centre, unit axis, length between the two platens and their mean
    axial stress (Pa) at time t."""
    platens.UpdatePipeline(t)
    data = servermanager.Fetch(platens)
    centres = []
    for c in range(data.GetNumberOfCells()):
        ids = data.GetCell(c).GetPointIds()
        pts = [data.GetPoint(ids.GetId(k)) for k in range(ids.GetNumberOfIds())]
        centres.append([sum(p[i] for p in pts) / len(pts) for i in range(3)])
    lo, hi = centres[0], centres[1]
    d = [hi[i] - lo[i] for i in range(3)]
    length = math.sqrt(sum(x * x for x in d))
    stress = data.GetCellData().GetArray("stress_axial")
    s = None
    if stress is not None and stress.GetNumberOfTuples() > 0:
        s = sum(stress.GetValue(k) for k in range(stress.GetNumberOfTuples()))
        s /= stress.GetNumberOfTuples()
    return [(lo[i] + hi[i]) / 2 for i in range(3)], [x / length for x in d], length, s


def across(axis):
    """A unit vector normal to the axis (towards the viewer)."""
    k = min(range(3), key=lambda i: abs(axis[i]))
    u = [1.0 if i == k else 0.0 for i in range(3)]
    dot = sum(u[i] * axis[i] for i in range(3))
    v = [u[i] - dot * axis[i] for i in range(3)]
    n = math.sqrt(sum(x * x for x in v))
    return [x / n for x in v]


def values(source, t, kind, name):
    """The values of a scalar array of a source at time t, as a list."""
    source.UpdatePipeline(t)
    data = servermanager.Fetch(source)
    if data is None:
        return []
    fields = data.GetPointData() if kind == "POINTS" else data.GetCellData()
    a = fields.GetArray(name)
    if a is None:
        return []
    return [a.GetValue(k) for k in range(a.GetNumberOfTuples())]


def percentile(xs, p):
    """The p-th percentile (0-100) of xs, interpolated between ranks."""
    s = sorted(xs)
    if not s:
        return 0.0
    r = (len(s) - 1) * p / 100.0
    k = int(math.floor(r))
    f = r - k
    return s[k] if k + 1 >= len(s) else s[k] * (1 - f) + s[k + 1] * f


def frame_state(source, t):
    """Time, axial strain and axial stress (Pa) of the frame shown at time t,
    from its field data; None in files without them."""
    source.UpdatePipeline(t)
    data = servermanager.Fetch(source)
    fields = data.GetFieldData() if data is not None else None
    got = []
    for name in ("time", "strain_axial", "stress_axial"):
        a = fields.GetArray(name) if fields is not None else None
        if a is None or a.GetNumberOfTuples() < 1:
            return None
        got.append(a.GetValue(0))
    return tuple(got)


def history_at(vtk_dir, t):
    """Axial strain and stress (Pa) at time t from the run's history, as
    `post curve` wrote it beside the vtk directory (curve.csv), linearly
    interpolated; None where there is no such file."""
    name = os.path.join(os.path.dirname(os.path.abspath(vtk_dir)), "curve.csv")
    try:
        with open(name) as f:
            head = f.readline().strip().split(",")
            it, ie, isg = (head.index(k) for k in ("t", "strain_axial", "stress_axial"))
            rows = []
            for line in f:
                v = line.split(",")
                rows.append((float(v[it]), float(v[ie]), float(v[isg])))
    except (OSError, ValueError, IndexError):
        return None
    if not rows:
        return None
    prev = rows[0]
    for r in rows:
        if r[0] >= t:
            f = 0.0 if r[0] <= prev[0] else (t - prev[0]) / (r[0] - prev[0])
            return tuple(prev[k] + f * (r[k] - prev[k]) for k in (1, 2))
        prev = r
    return rows[-1][1], rows[-1][2]


def camera(view, centre, axis, towards, length):
    view.CameraViewAngle = 30
    # The specimen a little above the middle: room for the title above it
    # and the legend below.
    focus = [centre[i] - 0.1 * length * axis[i] for i in range(3)]
    view.CameraFocalPoint = focus
    view.CameraPosition = [focus[i] + 3.2 * length * towards[i] for i in range(3)]
    view.CameraViewUp = axis
    view.CameraParallelProjection = 0
    view.OrientationAxesVisibility = 0
    view.Background = [1, 1, 1]
    try:
        view.UseColorPaletteForBackground = 0
    except AttributeError:
        pass


def colour_map(name, preset, lo, hi, invert):
    lut = GetColorTransferFunction(name)
    if not lut.ApplyPreset(preset, True):
        lut.ApplyPreset("Cool to Warm", True)
    if invert:
        lut.InvertTransferFunction()
    if hi <= lo:
        hi = lo + (abs(lo) * 1e-3 or 1e-12)
    lut.RescaleTransferFunction(lo, hi)
    GetOpacityTransferFunction(name).RescaleTransferFunction(lo, hi)
    lut.AutomaticRescaleRangeMode = "Never"
    return lut


def font(points):
    """A text size of the default view's, scaled to this one's width."""
    return max(6, int(round(points * font_scale)))


def legend(bar, title, fmt):
    """A horizontal colour legend near the bottom of its view, its ends and a few
    values between them labelled."""
    bar.Title = title
    bar.ComponentTitle = ""
    bar.TitleColor = [0, 0, 0]
    bar.LabelColor = [0, 0, 0]
    bar.TitleFontSize = font(11)
    bar.LabelFontSize = font(10)
    bar.TitleBold = 0
    bar.Orientation = "Horizontal"
    bar.WindowLocation = "Any Location"
    bar.Position = [0.25, 0.06]
    bar.ScalarBarLength = 0.5
    bar.ScalarBarThickness = 10
    bar.AddRangeLabels = 1
    bar.RangeLabelFormat = fmt
    bar.LabelFormat = fmt
    bar.UseCustomLabels = 0
    bar.DrawTickMarks = 1
    bar.DrawTickLabels = 1


def show_platens(platens, view):
    """The platens, grey and half transparent."""
    plates = Show(platens, view)
    plates.DiffuseColor = [0.55, 0.55, 0.55]
    plates.Opacity = 0.5


def label(view, text):
    t = Text(Text=text)
    d = Show(t, view)
    d.FontSize = font(11)
    d.Color = [0, 0, 0]
    d.WindowLocation = "Upper Center"
    d.Justification = "Center"


def bond_view(path, t, platens, centre, axis, towards, length):
    """The broken bonds as lines between the sphere centres, by mode."""
    view = CreateView("RenderView")
    view.ViewTime = t
    bonds = PVDReader(FileName=path("bonds.pvd"))
    bonds.UpdatePipeline(t)
    broken = Threshold(Input=bonds)
    broken.Scalars = ["CELLS", "state"]
    broken.LowerThreshold = 2
    broken.UpperThreshold = 3
    try:
        broken.ThresholdMethod = "Between"
    except AttributeError:
        pass
    lines = Show(broken, view)
    ColorBy(lines, ("CELLS", "state"))
    states = GetColorTransferFunction("state")
    states.InterpretValuesAsCategories = 1
    states.Annotations = ["2", "tension", "3", "shear"]
    states.IndexedColors = TENSION + SHEAR
    lines.LineWidth = 2
    try:
        lines.RenderLinesAsTubes = 1
    except AttributeError:
        pass
    lines.SetScalarBarVisibility(view, True)
    bar = GetScalarBar(states, view)
    legend(bar, "broken bond", "%s")
    bar.ScalarBarLength = 0.3
    show_platens(platens, view)
    camera(view, centre, axis, towards, length)
    state = values(broken, t, "CELLS", "state")
    label(view, "%d broken bonds (%d in tension, %d in shear)\nas lines between the sphere "
          "centres" % (len(state), state.count(2), state.count(3)))
    return view


def main(argv):
    global font_scale
    args = parse(argv)
    views = 3 if args["bonds"] else 2
    font_scale = min(1.0, args["size"][0] / views / (DEFAULT_SIZE[0] / 2))
    path = lambda name: os.path.join(args["dir"], name)
    particles = PVDReader(FileName=path("particles.pvd"))
    cracks = PVDReader(FileName=path("cracks.pvd"))
    platens = PVDReader(FileName=path("platens.pvd"))
    times = particles.TimestepValues
    times = list(times) if hasattr(times, "__len__") else [times]
    t = args["time"] if args["time"] is not None else times[-1]
    _, _, length0, _ = platen_axis(platens, times[0])
    centre, axis, length, stress = platen_axis(platens, t)
    for src in (particles, cracks, platens):
        src.UpdatePipeline(t)
    towards = across(axis)
    strain = (length0 - length) / length0
    shown_t = t
    state = frame_state(particles, t)
    history = history_at(args["dir"], t) if state is None else None
    if state is not None:
        shown_t, strain, stress = state
    elif history is not None:
        strain, stress = history
    title = "t = %.4g ms, axial strain %.3f %%" % (1e3 * shown_t, 100 * strain)
    if stress is not None:
        title += ", axial stress %.3g MPa" % (stress / 1e6)

    # The GUI's window has a layout with a view already: draw the left
    # picture in it (registering a new layout from a start-up script would
    # wait on the GUI, which waits on the script).
    window = list(GetLayouts().values())
    left = GetActiveView() if window else CreateView("RenderView")
    left.ViewTime = t
    half = Clip(Input=particles)
    half.ClipType = "Plane"
    half.ClipType.Origin = centre
    half.ClipType.Normal = towards
    half.Invert = 1
    half.Crinkleclip = 1
    spheres = Glyph(Input=half, GlyphType="Sphere")
    spheres.ScaleArray = ["POINTS", "radius"]
    spheres.ScaleFactor = 2.0  # the sphere glyph has radius 0.5
    spheres.GlyphMode = "All Points"
    spheres.GlyphType.ThetaResolution = 16
    spheres.GlyphType.PhiResolution = 12
    shown = Show(spheres, left)
    ColorBy(shown, ("POINTS", "damage"))
    range_t = times[-1] if args["ranges_at_end"] else t
    damage = values(half, range_t, "POINTS", "damage")
    hi = min(1.0, max(0.05, percentile(damage, 99)))
    lut = colour_map("damage", DAMAGE_MAP, 0.0, hi, True)
    shown.SetScalarBarVisibility(left, True)
    legend(GetScalarBar(lut, left), "damage (0 to the 99th percentile)", "%-#.2f")
    show_platens(platens, left)
    camera(left, centre, axis, towards, length)
    label(left, title + "\nspheres behind a cut through the axis, by damage")

    right = CreateView("RenderView")
    right.ViewTime = t
    formed = [100 * e for e in values(cracks, t, "CELLS", "strain_axial")]
    formed_range = ([100 * e for e in values(cracks, range_t, "CELLS", "strain_axial")]
                    if args["ranges_at_end"] else formed)
    if formed:
        pct = Calculator(Input=cracks, AttributeType="Cell Data",
                         ResultArrayName="formed_at_strain_pct", Function="100*strain_axial")
        discs = Show(pct, right)
        ColorBy(discs, ("CELLS", "formed_at_strain_pct"))
        slut = colour_map("formed_at_strain_pct", STRAIN_MAP, percentile(formed_range, 2),
                          percentile(formed_range, 98), True)
        discs.SetScalarBarVisibility(right, True)
        legend(GetScalarBar(slut, right), "axial strain (%) when the crack formed", "%-#.3g")
    if os.path.exists(path("geometry.vtp")):
        outline = Show(XMLPolyDataReader(FileName=[path("geometry.vtp")]), right)
        outline.DiffuseColor = [0.7, 0.7, 0.7]
        outline.Opacity = 0.12
    show_platens(platens, right)
    camera(right, centre, axis, towards, length)
    modes = values(cracks, t, "CELLS", "mode")
    label(right, "%d cracks so far (%d tension, %d shear)\nas discs, by the axial strain at which "
          "each formed" % (len(modes), modes.count(1), modes.count(2)))

    views = [left, right]
    if args["bonds"]:
        views.append(bond_view(path, t, platens, centre, axis, towards, length))

    layout = None
    if not window:  # in the GUI, the layout cannot change from here either
        layout = CreateLayout("run")
        AssignViewToLayout(view=left, layout=layout, hint=0)
        if len(views) == 2:
            layout.SplitHorizontal(0, 0.5)
            AssignViewToLayout(view=right, layout=layout, hint=2)
        else:
            layout.SplitHorizontal(0, 1.0 / 3)
            AssignViewToLayout(view=right, layout=layout, hint=2)
            layout.SplitHorizontal(2, 0.5)
            AssignViewToLayout(view=views[2], layout=layout, hint=6)
    for view in views:
        Render(view)
        camera(view, centre, axis, towards, length)
    if args["out"]:
        SaveScreenshot(args["out"], layout, ImageResolution=list(args["size"]))
        print("wrote %s" % args["out"])


main(sys.argv[1:])
