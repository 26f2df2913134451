"""usage: pvbatch paraview_state.py [solution.{pvd,pvtu,vtu}] [--png out.png] [--size W H] [--subdivision N] [--flux glyphs|streams|none] [--cavity-edge] [--sector DEG] [--last]

ParaView picture of a sealfe field file: pressure (with volume_flux arrows), film thickness and
liquid fraction side by side, the annulus seen from +z, Lagrange cells subdivided (level 2).
With --png it saves a screenshot (pvbatch, no window). Without it it only sets up the three views:
pvpython then opens an interactive window per view (the pressure one takes the mouse); in the
ParaView GUI run it with `paraview --script=scripts/paraview_state.py` or Python Shell > Run
Script (it fills the layout on screen), or File > Load State; there the file comes from the
environment variable SEALFE_SOLUTION, else sealfe-output/solve/solution.pvd.

Written against paraview.simple of ParaView 5.11 (Debian 12); not part of CI. Fields as sealfe
writes them (README, "Looking at the result in ParaView"): pressure [Pa], film_thickness [m],
volume_flux [m^2/s], liquid_fraction [-] (1 in the full film), cavitated [-].
"""
import argparse
import math
import os
import sys

from paraview.simple import (Calculator, ColorBy, Contour, CreateLayout, CreateView, Delete,
                             Disk, GetActiveView, GetColorTransferFunction, GetLayout,
                             GetOpacityTransferFunction, GetScalarBar, GetViewsInLayout, Glyph,
                             LoadPalette, OpenDataFile, Render, ResampleWithDataset,
                             SaveScreenshot, SetActiveView, Show, StreamTracer, Text)
from paraview import servermanager

DEFAULT_FILE = os.path.join("sealfe-output", "solve", "solution.pvd")

# Liquid fraction: the cavity (s < 1) on a grey ramp from dark (little liquid) to light, the
# full film (s = 1) in one distinct blue, on the fixed range 0..1.
FULL_FILM_RGB = [0.16, 0.40, 0.78]
CAVITY_RGB_POINTS = [0.0, 0.20, 0.20, 0.20,
                     0.985, 0.88, 0.88, 0.88,
                     1.0] + FULL_FILM_RGB


# ParaView's "Arial" in the Debian package draws [ ] like ( ); DejaVu Sans, where installed,
# keeps the "name [unit]" titles of sealfe's tables.
FONT_DIR = "/usr/share/fonts/truetype/dejavu"
FONT = os.path.join(FONT_DIR, "DejaVuSans.ttf")
FONT_BOLD = os.path.join(FONT_DIR, "DejaVuSans-Bold.ttf")


def set_font(proxy, prefix="", bold=False):
    """Give a text property group (prefix "", "Title" or "Label") the DejaVu font if present."""
    path = FONT_BOLD if bold else FONT
    if os.path.exists(path):
        setattr(proxy, prefix + "FontFamily", "File")
        setattr(proxy, prefix + "FontFile", path)


def parse(argv):
    parser = argparse.ArgumentParser(prog="paraview_state.py",
                                     description="Pressure, film thickness and liquid "
                                     "fraction of a sealfe solution side by side.")
    parser.add_argument("file", nargs="?", default=os.environ.get("SEALFE_SOLUTION",
                                                                  DEFAULT_FILE),
                        help="solution.pvd, .pvtu or .vtu (default: $SEALFE_SOLUTION or "
                        + DEFAULT_FILE + ")")
    parser.add_argument("--png", help="save a screenshot of the three views and exit")
    parser.add_argument("--size", nargs=2, type=int, default=[2100, 620], metavar=("W", "H"),
                        help="screenshot size in pixels (default 2100 620)")
    parser.add_argument("--subdivision", type=int, default=2,
                        help="nonlinear subdivision level of the Lagrange cells (default 2)")
    parser.add_argument("--flux", choices=["glyphs", "streams", "none"], default="glyphs",
                        help="volume_flux on the pressure view (default glyphs)")
    parser.add_argument("--cavity-edge", action="store_true",
                        help="outline the cavity (cavitated = 0.5) on the liquid fraction view")
    parser.add_argument("--sector", type=float, default=360.0, metavar="DEG",
                        help="show a sector of DEG degrees at the top of the annulus (theta = "
                        "90 deg) instead of the whole face: textures are too small to see "
                        "on the whole annulus (default 360)")
    parser.add_argument("--last", action="store_true",
                        help="show the last time of a .pvd (default: the first)")
    args = parser.parse_args(argv)
    if not 0.0 < args.sector <= 360.0:
        parser.error("--sector must be in (0, 360] degrees (got %g)" % args.sector)
    return args


def pressure_unit(p_max):
    """Pa, kPa or MPa so that the colour bar shows numbers of a sensible size."""
    for unit, scale in (("MPa", 1e-6), ("kPa", 1e-3)):
        if p_max >= 1 / scale:
            return unit, scale
    return "Pa", 1.0


def nice_ticks(lo, hi, count=6):
    """Round tick values inside [lo, hi], away from the range labels at both ends, and the
    printf format that shows them (as many decimals as the step needs)."""
    if not hi > lo:
        return [], "%-.3g"
    raw = (hi - lo) / count
    magnitude = 10.0 ** math.floor(math.log10(raw))
    mantissa = next(m for m in (1, 2, 2.5, 5, 10) if m * magnitude >= raw)
    step = mantissa * magnitude
    decimals = max(0, -int(math.floor(math.log10(step) + 1e-9)) + (mantissa == 2.5))
    ticks, value = [], math.ceil(lo / step) * step
    while value <= hi:
        if lo + 0.06 * (hi - lo) < value < hi - 0.06 * (hi - lo):
            ticks.append(round(value, 12))
        value += step
    return ticks, "%%-.%df" % decimals


def style_bar(lut, view, title, lo, hi, horizontal=False):
    """Colour bar on the right of the view, or along its bottom (sector views)."""
    bar = GetScalarBar(lut, view)
    bar.Title = title
    bar.ComponentTitle = ""
    bar.TitleBold = 1
    bar.ScalarBarLength = 0.7
    bar.WindowLocation = "Any Location"
    bar.Orientation = "Horizontal" if horizontal else "Vertical"
    bar.Position = [0.15, 0.05] if horizontal else [0.77, 0.13]
    ticks, label_format = nice_ticks(lo, hi)
    bar.AddRangeLabels = 1
    bar.RangeLabelFormat = label_format
    bar.AutomaticLabelFormat = 0
    bar.LabelFormat = label_format
    bar.UseCustomLabels = 1
    bar.CustomLabels = ticks
    set_font(bar, "Title", bold=True)
    set_font(bar, "Label")
    bar.Visibility = 1
    return bar


def fit_text(view, width):
    """Font sizes and colour bar thickness in proportion to the view's width in pixels
    (the sizes below are for 700 pixels)."""
    factor = width / 700.0
    for representation in view.Representations:
        kind = representation.GetXMLName()
        if kind == "ScalarBarWidgetRepresentation":
            representation.TitleFontSize = max(8, round(24 * factor))
            representation.LabelFontSize = max(7, round(22 * factor))
            representation.ScalarBarThickness = max(8, round(22 * factor))
        elif kind == "TextSourceRepresentation":
            representation.FontSize = max(8, round(26 * factor))


def top_view(view, bounds, aspect, sector=360.0, radii=None):
    """Camera on +z looking down at the annulus, x to the right, y up, parallel projection;
    the annulus on the left of a view of width/height = aspect, the colour bar on the right.
    With a sector of less than 360 degrees: that sector at the top of the annulus, between
    the radii, filling the width of the view above a horizontal colour bar."""
    view.InteractionMode = "2D"
    view.OrientationAxesVisibility = 0
    view.CameraViewUp = [0.0, 1.0, 0.0]
    view.CameraParallelProjection = 1
    if sector < 360.0 and radii is not None:
        r_in, r_out = radii
        half = math.radians(0.5 * min(sector, 180.0))
        half_height = max(1.02 * r_out * math.sin(half) / aspect,
                          (r_out - r_in * math.cos(half)) / (2.0 * 0.62))
        # The sector's top 12 % below the top of the view (the title above it).
        cy = r_out + 0.24 * half_height - half_height
        view.CameraFocalPoint = [0.0, cy, 0.0]
        view.CameraPosition = [0.0, cy, 4.0 * r_out]
        view.CameraParallelScale = half_height
        return
    cx, cy = 0.5 * (bounds[0] + bounds[1]), 0.5 * (bounds[2] + bounds[3])
    radius = 0.5 * max(bounds[1] - bounds[0], bounds[3] - bounds[2])
    half_height = max(1.1 * radius, 1.45 * radius / aspect)
    shift = half_height * aspect - 1.04 * radius
    view.CameraFocalPoint = [cx + shift, cy, 0.0]
    view.CameraPosition = [cx + shift, cy, 4.0 * radius]
    view.CameraParallelScale = half_height


def title(view, text):
    label = Text(Text=text)
    display = Show(label, view)
    display.WindowLocation = "Upper Center"
    display.Bold = 1
    set_font(display, bold=True)
    return label


def coloured(source, view, array, subdivision):
    display = Show(source, view)
    display.Representation = "Surface"
    display.NonlinearSubdivisionLevel = subdivision
    ColorBy(display, ("POINTS", array))
    return display


def flux_overlay(source, view, kind, sector=360.0):
    """volume_flux on the pressure view: arrows on rings through the annulus, their length
    proportional to the flux, or stream lines seeded on a radius."""
    flux_max = source.PointData["volume_flux"].GetRange(-1)[1]
    if flux_max <= 0.0:
        return
    r_in, r_out = annulus_radii(source)
    band = r_out - r_in
    if kind == "glyphs":
        # About 40 arrows across the view along a ring, whatever the sector shown.
        rings, per_ring = (3, 40) if sector >= 360.0 else (5, int(round(40 * 360.0 / sector)))
        seeds = Disk(InnerRadius=r_in + 0.18 * band, OuterRadius=r_out - 0.18 * band,
                     RadialResolution=rings - 1, CircumferentialResolution=per_ring)
        probe = ResampleWithDataset(SourceDataArrays=source, DestinationMesh=seeds)
        probe.PassPointArrays = 0
        glyphs = Glyph(Input=probe, GlyphType="Arrow")
        glyphs.OrientationArray = ["POINTS", "volume_flux"]
        glyphs.ScaleArray = ["POINTS", "volume_flux"]
        # The longest arrow is 0.95 of the spacing along the middle ring.
        glyphs.ScaleFactor = 0.95 * math.pi * (r_in + r_out) / per_ring / flux_max
        glyphs.GlyphMode = "All Points"
        glyphs.GlyphType.TipLength = 0.35
        glyphs.GlyphType.TipRadius = 0.26
        glyphs.GlyphType.ShaftRadius = 0.1
        overlay = glyphs
    else:
        # Seeds on a radius of the annulus; one turn along the flux both ways.
        tracer = StreamTracer(Input=source, SeedType="Line")
        tracer.Vectors = ["POINTS", "volume_flux"]
        tracer.SeedType.Point1 = [r_in + 0.1 * band, 0.0, 0.0]
        tracer.SeedType.Point2 = [r_out - 0.1 * band, 0.0, 0.0]
        tracer.SeedType.Resolution = 4
        tracer.IntegrationDirection = "BOTH"
        tracer.MaximumStreamlineLength = 1.05 * math.pi * r_out
        tracer.MaximumSteps = 20000
        overlay = tracer
    display = Show(overlay, view)
    # Lift the overlay off the film's plane so the surface does not hide it.
    display.Position = [0.0, 0.0, 0.02 * r_out]
    display.ColorArrayName = [None, ""]
    display.AmbientColor = display.DiffuseColor = [0.0, 0.85, 1.0]
    display.Ambient = 1.0
    display.Diffuse = 0.0
    display.LineWidth = 2.0


def annulus_radii(source):
    """Inner and outer radius from the points (the mesh is the annulus ri <= r <= ro)."""
    radius = Calculator(Input=source, ResultArrayName="r_tmp",
                        Function="sqrt(coordsX^2+coordsY^2)")
    radius.UpdatePipeline()
    r_in, r_out = radius.PointData["r_tmp"].GetRange()
    Delete(radius)
    return r_in, r_out


def three_views(name):
    """Three render views side by side in one layout. In the GUI the layout on screen is used
    when it holds just its first view (ParaView 5.11 hung here assigning views to a new,
    hidden layout tab); pvbatch and pvpython get a new layout."""
    active = GetActiveView()
    layout = GetLayout(active) if active else None
    if layout is not None and len(GetViewsInLayout(layout)) == 1 \
            and active.GetXMLName() == "RenderView":
        first = active
    else:
        layout, first = CreateLayout(name), None
    if first is None:
        first = CreateView("RenderView")
        layout.AssignView(0, first)
    # The first view moves to the left cell (1); the right cell (2) splits into 5 and 6.
    layout.SplitHorizontal(0, 1.0 / 3.0)
    layout.SplitHorizontal(2, 0.5)
    views = [first]
    for index in (5, 6):
        view = CreateView("RenderView")
        layout.AssignView(index, view)
        views.append(view)
    return layout, views


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

    layout, views = three_views("sealfe " + os.path.basename(path))
    for view in views:
        view.ViewTime = time
    p_view, h_view, s_view = views

    # Pressure, sequential over the range of the data, volume_flux on top.
    display = coloured(pressure, p_view, "pressure_" + unit, args.subdivision)
    lut = GetColorTransferFunction("pressure_" + unit)
    lut.ApplyPreset("Inferno (matplotlib)", True)
    lut.RescaleTransferFunction(p_lo * scale, p_hi * scale)
    lut.AutomaticRescaleRangeMode = "Never"
    style_bar(lut, p_view, "pressure [%s]" % unit, p_lo * scale, p_hi * scale, args.sector < 360.0)
    if args.flux != "none" and "volume_flux" in names:
        flux_overlay(reader, p_view, args.flux, args.sector)
    title(p_view, "pressure" + (" and volume flux" if args.flux != "none" else ""))

    # Film thickness in micrometres, sequential over the range of the data.
    display = coloured(film, h_view, "film_thickness_um", args.subdivision)
    lut = GetColorTransferFunction("film_thickness_um")
    lut.ApplyPreset("Viridis (matplotlib)", True)
    h_lo, h_hi = film.PointData["film_thickness_um"].GetRange()
    lut.RescaleTransferFunction(h_lo, h_hi)
    lut.AutomaticRescaleRangeMode = "Never"
    style_bar(lut, h_view, "film thickness [\u00b5m]", h_lo, h_hi, args.sector < 360.0)
    title(h_view, "film thickness")

    # Liquid fraction on 0..1: cavity grey, full film blue (optionally the cavity's edge).
    if "liquid_fraction" in names:
        display = coloured(reader, s_view, "liquid_fraction", args.subdivision)
        lut = GetColorTransferFunction("liquid_fraction")
        lut.ColorSpace = "RGB"
        lut.RGBPoints = CAVITY_RGB_POINTS
        lut.AutomaticRescaleRangeMode = "Never"
        GetOpacityTransferFunction("liquid_fraction").RescaleTransferFunction(0.0, 1.0)
        style_bar(lut, s_view, "liquid fraction [-]", 0.0, 1.0, args.sector < 360.0)
        if args.cavity_edge and "cavitated" in names:
            edge = Contour(Input=reader, ContourBy=["POINTS", "cavitated"], Isosurfaces=[0.5])
            edge_display = Show(edge, s_view)
            edge_display.Position = [0.0, 0.0, 0.005 * (bounds[1] - bounds[0])]
            edge_display.ColorArrayName = [None, '']
            edge_display.AmbientColor = edge_display.DiffuseColor = [0.85, 0.1, 0.1]
            edge_display.LineWidth = 2.0
        full = reader.PointData["liquid_fraction"].GetRange()[0] >= 1.0
        title(s_view, "liquid fraction" + (": full film everywhere" if full
                                           else " (blue: full film)"))
    else:
        title(s_view, "no liquid_fraction in the file")
        display = Show(reader, s_view)
        display.NonlinearSubdivisionLevel = args.subdivision
        display.ColorArrayName = [None, '']

    radii = annulus_radii(reader) if args.sector < 360.0 else None
    for view in views:
        Render(view)
        width, height = view.ViewSize
        if args.png or not (width > 0 and height > 0):
            width, height = args.size[0] / 3.0, args.size[1]
        top_view(view, bounds, width / height, args.sector, radii)
        fit_text(view, width)
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


# "__vtkconsole__": loaded in the GUI with File > Load State.
if __name__ in ("__main__", "__vtkconsole__"):
    main(sys.argv[1:])
