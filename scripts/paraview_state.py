"""usage: pvbatch paraview_state.py [solution.{pvd,pvtu,vtu}] [--png out.png] [--size W H] [--subdivision N] [--flux glyphs|streams|none] [--last]

ParaView picture of a sealfe field file: pressure, film thickness and liquid fraction side by
side, the annulus seen from +z. With --png it saves a screenshot (pvbatch, no window); without it
it only sets up the three views (pvpython opens an interactive window; in the ParaView GUI load it
with File > Load State or Python Shell > Run Script: the file then comes from the environment
variable SEALFE_SOLUTION, else sealfe-output/solve/solution.pvd).

Written against paraview.simple of ParaView 5.11 (Debian 12); not part of CI. Fields as sealfe
writes them (README, "Looking at the result in ParaView"): pressure [Pa], film_thickness [m],
volume_flux [m^2/s], liquid_fraction [-] (JFO; absent for other models), cavitated [-].
"""
import argparse
import os
import sys

from paraview.simple import (AssignViewToLayout, Calculator, ColorBy, Contour, CreateLayout,
                             CreateView, GetActiveViewOrCreate, GetColorTransferFunction,
                             GetLayout, GetOpacityTransferFunction, GetScalarBar, Glyph, Hide,
                             LoadPalette, OpenDataFile, Render, SaveScreenshot, SetActiveView,
                             Show, StreamTracer, Text, UpdatePipeline)
from paraview import servermanager

DEFAULT_FILE = os.path.join("sealfe-output", "solve", "solution.pvd")

# Liquid fraction: the cavity (s < 1) on a grey ramp from dark (little liquid) to light, the
# full film (s = 1) in one distinct blue, on the fixed range 0..1.
FULL_FILM_RGB = [0.16, 0.40, 0.78]
CAVITY_RGB_POINTS = [0.0, 0.20, 0.20, 0.20,
                     0.985, 0.88, 0.88, 0.88,
                     1.0] + FULL_FILM_RGB


def parse(argv):
    parser = argparse.ArgumentParser(prog="paraview_state.py",
                                     description=__doc__.splitlines()[0])
    parser.add_argument("file", nargs="?", default=os.environ.get("SEALFE_SOLUTION",
                                                                  DEFAULT_FILE),
                        help="solution.pvd, .pvtu or .vtu (default: $SEALFE_SOLUTION or "
                        + DEFAULT_FILE + ")")
    parser.add_argument("--png", help="save a screenshot of the three views and exit")
    parser.add_argument("--size", nargs=2, type=int, default=[2400, 760], metavar=("W", "H"),
                        help="screenshot size in pixels (default 2400 760)")
    parser.add_argument("--subdivision", type=int, default=2,
                        help="nonlinear subdivision level of the Lagrange cells (default 2)")
    parser.add_argument("--flux", choices=["glyphs", "streams", "none"], default="glyphs",
                        help="volume_flux on the pressure view (default glyphs)")
    parser.add_argument("--last", action="store_true",
                        help="show the last time of a .pvd (default: the first)")
    return parser.parse_args(argv)


def pressure_unit(p_max):
    """Pa, kPa or MPa so that the colour bar shows numbers of a sensible size."""
    for unit, scale in (("MPa", 1e-6), ("kPa", 1e-3)):
        if p_max >= 1 / scale:
            return unit, scale
    return "Pa", 1.0


def style_bar(lut, view, title):
    bar = GetScalarBar(lut, view)
    bar.Title = title
    bar.ComponentTitle = ""
    bar.TitleFontSize = 20
    bar.LabelFontSize = 17
    bar.TitleBold = 1
    bar.ScalarBarThickness = 20
    bar.ScalarBarLength = 0.6
    bar.WindowLocation = "Any Location"
    bar.Orientation = "Vertical"
    bar.Position = [0.84, 0.2]
    bar.AddRangeLabels = 1
    bar.RangeLabelFormat = "%-#.3g"
    bar.AutomaticLabelFormat = 0
    bar.LabelFormat = "%-#.3g"
    bar.Visibility = 1
    return bar


def top_view(view, bounds):
    """Camera on +z looking down at the annulus, x to the right, y up, parallel projection."""
    view.InteractionMode = "2D"
    view.OrientationAxesVisibility = 0
    cx, cy = 0.5 * (bounds[0] + bounds[1]), 0.5 * (bounds[2] + bounds[3])
    extent = max(bounds[1] - bounds[0], bounds[3] - bounds[2])
    # Leave room on the right for the colour bar.
    view.CameraFocalPoint = [cx + 0.17 * extent, cy, 0.0]
    view.CameraPosition = [cx + 0.17 * extent, cy, 2.0 * extent]
    view.CameraViewUp = [0.0, 1.0, 0.0]
    view.CameraParallelProjection = 1
    view.CameraParallelScale = 0.56 * extent


def title(view, text):
    label = Text(Text=text)
    display = Show(label, view)
    display.WindowLocation = "Upper Center"
    display.FontSize = 22
    display.Bold = 1
    return label


def coloured(source, view, array, subdivision):
    display = Show(source, view)
    display.Representation = "Surface"
    display.NonlinearSubdivisionLevel = subdivision
    ColorBy(display, ("POINTS", array))
    return display


def flux_overlay(source, view, bounds, kind):
    """volume_flux on the pressure view: arrows scaled by its magnitude, or stream lines."""
    flux_max = source.PointData["volume_flux"].GetRange(-1)[1]
    if flux_max <= 0.0:
        return
    width = 0.5 * (bounds[1] - bounds[0])
    if kind == "glyphs":
        glyphs = Glyph(Input=source, GlyphType="Arrow")
        glyphs.OrientationArray = ["POINTS", "volume_flux"]
        glyphs.ScaleArray = ["POINTS", "volume_flux"]
        glyphs.ScaleFactor = 0.09 * width / flux_max
        glyphs.GlyphMode = "Uniform Spatial Distribution (Surface Sampling)"
        glyphs.MaximumNumberOfSamplePoints = 400
        glyphs.Seed = 1
        display = Show(glyphs, view)
        # Lift the arrows off the film's plane so the surface does not hide them.
        display.Position = [0.0, 0.0, 0.01 * width]
        display.ColorArrayName = [None, '']
        display.AmbientColor = display.DiffuseColor = [0.0, 0.85, 1.0]
        display.Ambient = 1.0
        display.Diffuse = 0.0
    else:
        # Seeds on a radial line through the annulus; integrate both ways along the flux.
        r_in, r_out = annulus_radii(source)
        tracer = StreamTracer(Input=source, SeedType="Line")
        tracer.Vectors = ["POINTS", "volume_flux"]
        tracer.SeedType.Point1 = [r_in * 1.001, 0.0, 0.0]
        tracer.SeedType.Point2 = [r_out * 0.999, 0.0, 0.0]
        tracer.SeedType.Resolution = 12
        tracer.IntegrationDirection = "BOTH"
        tracer.MaximumStreamlineLength = 20.0 * width
        tracer.MaximumSteps = 20000
        display = Show(tracer, view)
        display.Position = [0.0, 0.0, 0.01 * width]
        display.ColorArrayName = [None, '']
        display.AmbientColor = display.DiffuseColor = [0.0, 0.85, 1.0]
        display.LineWidth = 1.5


def annulus_radii(source):
    """Inner and outer radius from the points (the mesh is the annulus ri <= r <= ro)."""
    radius = Calculator(Input=source, ResultArrayName="r_tmp",
                        Function="sqrt(coordsX^2+coordsY^2)")
    radius.UpdatePipeline()
    r_in, r_out = radius.PointData["r_tmp"].GetRange()
    Hide(radius)
    return r_in, r_out


def build(args):
    path = os.path.abspath(args.file)
    if not os.path.exists(path):
        sys.exit("paraview_state.py: no such file: " + path)
    reader = OpenDataFile(path)
    if reader is None:
        sys.exit("paraview_state.py: ParaView cannot read " + path)
    times = list(getattr(reader, "TimestepValues", None) or [])
    time = times[-1] if (args.last and times) else (times[0] if times else 0.0)
    reader.UpdatePipeline(time)
    names = reader.PointData.keys()
    for needed in ("pressure", "film_thickness"):
        if needed not in names:
            sys.exit("paraview_state.py: %s has no point field %s" % (path, needed))
    bounds = reader.GetDataInformation().GetBounds()

    p_lo, p_hi = reader.PointData["pressure"].GetRange()
    unit, scale = pressure_unit(max(abs(p_lo), abs(p_hi)))
    pressure = Calculator(Input=reader, ResultArrayName="pressure_" + unit,
                          Function="pressure*%.17g" % scale)
    film = Calculator(Input=reader, ResultArrayName="film_thickness_um",
                      Function="film_thickness*1e6")
    for source in (pressure, film):
        source.UpdatePipeline(time)

    layout = CreateLayout("sealfe " + os.path.basename(path))
    views = []
    for _ in range(3):
        view = CreateView("RenderView")
        view.ViewTime = time
        views.append(view)
    # Three equal cells side by side.
    layout.SplitHorizontal(0, 1.0 / 3.0)
    layout.SplitHorizontal(2, 0.5)
    for index, view in zip((1, 5, 6), views):
        AssignViewToLayout(view=view, layout=layout, hint=index)
    p_view, h_view, s_view = views

    # Pressure, sequential over the range of the data, volume_flux on top.
    display = coloured(pressure, p_view, "pressure_" + unit, args.subdivision)
    lut = GetColorTransferFunction("pressure_" + unit)
    lut.ApplyPreset("Inferno (matplotlib)", True)
    lut.RescaleTransferFunction(p_lo * scale, p_hi * scale)
    lut.AutomaticRescaleRangeMode = "Never"
    style_bar(lut, p_view, "pressure [%s]" % unit)
    if args.flux != "none" and "volume_flux" in names:
        flux_overlay(reader, p_view, bounds, args.flux)
    title(p_view, "pressure" + ("  + volume flux" if args.flux != "none" else ""))

    # Film thickness in micrometres, sequential over the range of the data.
    display = coloured(film, h_view, "film_thickness_um", args.subdivision)
    lut = GetColorTransferFunction("film_thickness_um")
    lut.ApplyPreset("Viridis (matplotlib)", True)
    h_lo, h_hi = film.PointData["film_thickness_um"].GetRange()
    lut.RescaleTransferFunction(h_lo, h_hi)
    lut.AutomaticRescaleRangeMode = "Never"
    style_bar(lut, h_view, "film thickness [\u00b5m]")
    title(h_view, "film thickness")

    # Liquid fraction on 0..1: cavity grey, full film blue; the cavity's edge outlined.
    if "liquid_fraction" in names:
        display = coloured(reader, s_view, "liquid_fraction", args.subdivision)
        lut = GetColorTransferFunction("liquid_fraction")
        lut.ColorSpace = "RGB"
        lut.RGBPoints = CAVITY_RGB_POINTS
        lut.AutomaticRescaleRangeMode = "Never"
        lut.Annotations = ["1", "full film"]
        GetOpacityTransferFunction("liquid_fraction").RescaleTransferFunction(0.0, 1.0)
        bar = style_bar(lut, s_view, "liquid fraction [-]")
        bar.DrawAnnotations = 1
        if "cavitated" in names and reader.PointData["cavitated"].GetRange()[1] > 0.5:
            edge = Contour(Input=reader, ContourBy=["POINTS", "cavitated"], Isosurfaces=[0.5])
            edge_display = Show(edge, s_view)
            edge_display.Position = [0.0, 0.0, 0.005 * (bounds[1] - bounds[0])]
            edge_display.ColorArrayName = [None, '']
            edge_display.AmbientColor = edge_display.DiffuseColor = [0.85, 0.1, 0.1]
            edge_display.LineWidth = 2.0
        title(s_view, "liquid fraction (JFO)")
    else:
        title(s_view, "no liquid_fraction (not a JFO run)")
        display = Show(reader, s_view)
        display.NonlinearSubdivisionLevel = args.subdivision
        display.ColorArrayName = [None, '']

    for view in views:
        Render(view)
        top_view(view, bounds)
    SetActiveView(p_view)
    return layout, views


def main(argv):
    args = parse(argv)
    if args.png:
        # White background and black text for documents.
        LoadPalette("WhiteBackground")
    layout, views = build(args)
    if args.png:
        layout.SetSize(*args.size)
        for view in views:
            Render(view)
        SaveScreenshot(args.png, layout, SaveAllViews=1, ImageResolution=list(args.size),
                       FontScaling="Do not scale fonts")
        print("paraview_state.py: wrote " + args.png)
        return
    for view in views:
        Render(view)
    # pvpython (not pvbatch, not the GUI): open an interactive window.
    process = servermanager.vtkProcessModule.GetProcessType()
    in_gui = "paraview" in os.path.basename(sys.executable or "") or not sys.argv[0]
    if process == servermanager.vtkProcessModule.PROCESS_CLIENT and not in_gui:
        from paraview.simple import Interact
        Interact(views[0])


if __name__ == "__main__":
    main(sys.argv[1:])
