"""Show a run written by `post vtk` in ParaView, and save a picture.

    pvbatch share/paraview/show_run.py VTK_DIR [OUT.png] [--time T] [--size W H]
    paraview --script=share/paraview/show_run.py    (then VTK_DIR from $DEM_VTK_DIR)

VTK_DIR is the directory `post vtk` wrote (particles.pvd, cracks.pvd,
platens.pvd, geometry.vtp). Two views side by side, at the last snapshot
(or the one at time T, s):
  left   the spheres as sphere glyphs of their true radius, coloured by
         displacement magnitude, with the front half cut away along a plane
         through the loading axis so the inside shows;
  right  every crack so far as a disc (tension red, shear blue) inside the
         translucent specimen, between the platens.
The loading axis is found from the platens. With OUT.png the layout is
saved (pvbatch needs an X display: run it under `xvfb-run -a` on a headless
machine).
"""
import math
import os
import sys

from paraview import servermanager
from paraview.simple import (
    AssignViewToLayout, Clip, ColorBy, CreateLayout, CreateView, GetAnimationScene,
    GetColorTransferFunction, GetScalarBar, Glyph, PVDReader, Render, SaveScreenshot, Show,
    Text, XMLPolyDataReader)

TENSION = [0.839, 0.153, 0.157]  # share/gnuplot/style.gp colours
SHEAR = [0.122, 0.306, 0.620]


def parse(argv):
    args = {"dir": os.environ.get("DEM_VTK_DIR"), "out": None, "time": None,
            "size": (1800, 900)}
    rest = list(argv)
    while rest:
        a = rest.pop(0)
        if a == "--time":
            args["time"] = float(rest.pop(0))
        elif a == "--size":
            args["size"] = (int(rest.pop(0)), int(rest.pop(0)))
        elif args["dir"] is None or (args["dir"] == os.environ.get("DEM_VTK_DIR") and
                                     not a.endswith(".png")):
            args["dir"] = a
        else:
            args["out"] = a
    if not args["dir"]:
        sys.exit("usage: pvbatch show_run.py VTK_DIR [OUT.png] [--time T] [--size W H]")
    return args


def platen_axis(platens):
    """Centre, unit axis and length between the two platens."""
    data = servermanager.Fetch(platens)
    centres = []
    for c in range(data.GetNumberOfCells()):
        ids = data.GetCell(c).GetPointIds()
        pts = [data.GetPoint(ids.GetId(k)) for k in range(ids.GetNumberOfIds())]
        centres.append([sum(p[i] for p in pts) / len(pts) for i in range(3)])
    lo, hi = centres[0], centres[1]
    d = [hi[i] - lo[i] for i in range(3)]
    length = math.sqrt(sum(x * x for x in d))
    return [(lo[i] + hi[i]) / 2 for i in range(3)], [x / length for x in d], length


def across(axis):
    """A unit vector normal to the axis (towards the viewer)."""
    k = min(range(3), key=lambda i: abs(axis[i]))
    u = [1.0 if i == k else 0.0 for i in range(3)]
    dot = sum(u[i] * axis[i] for i in range(3))
    v = [u[i] - dot * axis[i] for i in range(3)]
    n = math.sqrt(sum(x * x for x in v))
    return [x / n for x in v]


def camera(view, centre, axis, towards, length):
    view.CameraViewAngle = 30
    view.CameraFocalPoint = centre
    view.CameraPosition = [centre[i] + 2.8 * length * towards[i] for i in range(3)]
    view.CameraViewUp = axis
    view.CameraParallelProjection = 0
    view.OrientationAxesVisibility = 0
    view.Background = [1, 1, 1]
    try:
        view.UseColorPaletteForBackground = 0
    except AttributeError:
        pass


def style_bar(bar, title):
    bar.Title = title
    bar.ComponentTitle = ""
    bar.TitleColor = [0, 0, 0]
    bar.LabelColor = [0, 0, 0]
    bar.TitleFontSize = 9
    bar.LabelFontSize = 8
    bar.ScalarBarLength = 0.4


def label(view, text):
    t = Text(Text=text)
    d = Show(t, view)
    d.FontSize = 9
    d.Color = [0, 0, 0]
    d.WindowLocation = "Upper Center"


def main(argv):
    args = parse(argv)
    path = lambda name: os.path.join(args["dir"], name)
    particles = PVDReader(FileName=path("particles.pvd"))
    cracks = PVDReader(FileName=path("cracks.pvd"))
    platens = PVDReader(FileName=path("platens.pvd"))
    scene = GetAnimationScene()
    scene.UpdateAnimationUsingDataTimeSteps()
    times = particles.TimestepValues
    times = list(times) if hasattr(times, "__len__") else [times]
    t = args["time"] if args["time"] is not None else times[-1]
    scene.AnimationTime = t
    for src in (particles, cracks, platens):
        src.UpdatePipeline(t)
    centre, axis, length = platen_axis(platens)
    towards = across(axis)

    left = CreateView("RenderView")
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
    ColorBy(shown, ("POINTS", "displacement", "Magnitude"))
    lut = GetColorTransferFunction("displacement")
    lut.ApplyPreset("Viridis (matplotlib)", True)
    shown.RescaleTransferFunctionToDataRange(True, False)
    shown.SetScalarBarVisibility(left, True)
    style_bar(GetScalarBar(lut, left), "displacement (m)")
    plates = Show(platens, left)
    plates.DiffuseColor = [0.55, 0.55, 0.55]
    plates.Opacity = 0.5
    camera(left, centre, axis, towards, length)
    label(left, "spheres by displacement at t = %.4g s (front half cut away)" % t)

    right = CreateView("RenderView")
    right.ViewTime = t
    discs = Show(cracks, right)
    ColorBy(discs, ("CELLS", "mode"))
    modes = GetColorTransferFunction("mode")
    modes.InterpretValuesAsCategories = 1
    modes.Annotations = ["1", "tension", "2", "shear"]
    modes.IndexedColors = TENSION + SHEAR
    discs.SetScalarBarVisibility(right, True)
    style_bar(GetScalarBar(modes, right), "crack mode")
    if os.path.exists(path("geometry.vtp")):
        outline = Show(XMLPolyDataReader(FileName=[path("geometry.vtp")]), right)
        outline.DiffuseColor = [0.7, 0.7, 0.7]
        outline.Opacity = 0.12
    plates2 = Show(platens, right)
    plates2.DiffuseColor = [0.55, 0.55, 0.55]
    plates2.Opacity = 0.5
    camera(right, centre, axis, towards, length)
    label(right, "cracks so far: tension red, shear blue")

    layout = CreateLayout("run")
    AssignViewToLayout(view=left, layout=layout, hint=0)
    layout.SplitHorizontal(0, 0.5)
    AssignViewToLayout(view=right, layout=layout, hint=2)
    for view in (left, right):
        Render(view)
        camera(view, centre, axis, towards, length)
    if args["out"]:
        SaveScreenshot(args["out"], layout, ImageResolution=list(args["size"]))
        print("wrote %s" % args["out"])


main(sys.argv[1:])
