# Opens a `thaw run` output folder in ParaView as a time series: the shell's surfaces
# (meshes.pvd) and, for grid runs, the solver's fields (fields.pvd) as a slice through the middle.
# Grid runs' surfaces carry the material temperature at each vertex (point data temperature_c):
# they are coloured by it, on the same Cool to Warm scale as the field slice (same colour = same
# temperature), its range the surfaces' own over the whole run. 1D runs' surfaces carry only
# normals: a solid pale ice blue, see-through so the inner (water|ice) surface shows.
# Run with pvpython (Debian: apt-get install paraview):
#   pvpython data/paraview/open_run.py RUN_DIR [--screenshot out.png]   # batch: checks, picture
#   paraview --script=data/paraview/open_run.py                         # GUI: set THAW_RUN=RUN_DIR
# Prints one line per opened series: "meshes: N time steps, point arrays [...]".
# Checked without ParaView by tests/data/paraview/check_open_run.py (VTK's own readers).
import os
import sys

from paraview.simple import (ColorBy, GetActiveViewOrCreate, GetAnimationScene, GetColorTransferFunction, GetScalarBar,
                             OpenDataFile, ResetCamera, SaveScreenshot, Show, Slice, UpdatePipeline)

TEMPERATURE = "temperature_c"  # [C], written by src/inspect (field_probe: surfaces; field_export: fields)
ICE_BLUE = [0.75, 0.88, 1.0]


def time_steps(source):
    values = source.TimestepValues
    if values is None:
        return []
    return list(values) if hasattr(values, "__len__") else [values]


def array_names(data):
    return [data.GetArray(i).Name for i in range(data.GetNumberOfArrays())]


def temperature_range(source, times):
    """The surfaces' temperature range over every time step (the colour scale's ends)."""
    low, high = None, None
    for t in times or [None]:
        UpdatePipeline(time=t, proxy=source)
        if TEMPERATURE not in array_names(source.PointData):
            continue  # a step without surfaces (the ice is gone)
        a, b = source.PointData[TEMPERATURE].GetRange()
        low = a if low is None else min(low, a)
        high = b if high is None else max(high, b)
    if low is None:
        return None
    if high - low < 0.1:  # an all-but-uniform surface: a 0.1 C wide scale, not a degenerate one
        low, high = low - 0.05, high + 0.05
    return low, high


def colour_by_temperature(display, view, association, value_range):
    ColorBy(display, (association, TEMPERATURE))
    lut = GetColorTransferFunction(TEMPERATURE)
    lut.ApplyPreset("Cool to Warm", True)
    if value_range:
        lut.RescaleTransferFunction(value_range[0], value_range[1])
    display.SetScalarBarVisibility(view, True)
    bar = GetScalarBar(lut, view)
    bar.Title = "temperature [C]"  # ParaView's default reads "temperature_c Magnitude"
    bar.ComponentTitle = ""


def open_run(run_dir, screenshot=None):
    view = GetActiveViewOrCreate("RenderView")
    meshes = OpenDataFile(os.path.join(run_dir, "meshes.pvd"))
    UpdatePipeline(proxy=meshes)
    times = time_steps(meshes)
    arrays = array_names(meshes.PointData)
    print("meshes: %d time steps, point arrays %s" % (len(times), arrays))
    display = Show(meshes, view)
    scale = None
    if TEMPERATURE in arrays:
        scale = temperature_range(meshes, times)
        colour_by_temperature(display, view, "POINTS", scale)
        print("meshes coloured by %s, %.3g to %.3g C" % (TEMPERATURE, scale[0], scale[1]))
    else:
        # Solid colour: no colour array. (ColorBy(display, None) fails in ParaView 5.11 when the
        # display has no array yet: "invalid association string 'NONE'".)
        display.ColorArrayName = ["POINTS", ""]
        display.DiffuseColor = ICE_BLUE
        display.Opacity = 0.6
        print("meshes in solid ice blue (no %s: a 1D run)" % TEMPERATURE)
    fields_pvd = os.path.join(run_dir, "fields.pvd")
    if os.path.exists(fields_pvd):
        fields = OpenDataFile(fields_pvd)
        UpdatePipeline(proxy=fields)
        names = array_names(fields.CellData)
        print("fields: %d time steps, cell arrays %s" % (len(time_steps(fields)), names))
        # The middle of the z extent: a 3D run's mid-plane, or the (r, y) half-plane of an
        # axisymmetric run (one cell thick in z).
        bounds = fields.GetDataInformation().GetBounds()
        cut = Slice(Input=fields)
        cut.SliceType.Origin = [0.5 * (bounds[0] + bounds[1]), 0.5 * (bounds[2] + bounds[3]),
                                0.5 * (bounds[4] + bounds[5])]
        cut.SliceType.Normal = [0.0, 0.0, 1.0]
        shown = Show(cut, view)
        colour_by_temperature(shown, view, "CELLS", scale)
    scene = GetAnimationScene()
    scene.UpdateAnimationUsingDataTimeSteps()
    ResetCamera(view)
    if screenshot:
        if times:
            scene.AnimationTime = times[len(times) // 2]
        SaveScreenshot(screenshot, view, ImageResolution=[640, 480])
    return times


if __name__ == "__main__":
    args = [a for a in sys.argv[1:]]
    shot = None
    if "--screenshot" in args:
        i = args.index("--screenshot")
        shot = args[i + 1]
        del args[i:i + 2]
    run = args[0] if args else os.environ.get("THAW_RUN", "thaw-out")
    open_run(run, shot)
