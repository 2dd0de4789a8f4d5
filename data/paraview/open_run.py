# Opens a `thaw run` output folder in ParaView as a time series: the shell's surfaces
# (meshes.pvd: outer ice|air surface pale blue and see-through, inner water|ice surface blue),
# and for grid runs the solver's fields (fields.pvd) as a slice through the middle, coloured by
# temperature. Run with pvpython (Debian: apt-get install paraview):
#   pvpython data/paraview/open_run.py RUN_DIR [--screenshot out.png]   # batch: checks, picture
#   paraview --script=data/paraview/open_run.py                         # GUI: set THAW_RUN=RUN_DIR
# Prints one line per opened series: "meshes: N time steps, point arrays [...]".
import os
import sys

from paraview.simple import (ColorBy, GetActiveViewOrCreate, GetAnimationScene, GetColorTransferFunction,
                             OpenDataFile, ResetCamera, SaveScreenshot, Show, Slice, UpdatePipeline)


def open_run(run_dir, screenshot=None):
    view = GetActiveViewOrCreate("RenderView")
    meshes = OpenDataFile(os.path.join(run_dir, "meshes.pvd"))
    UpdatePipeline(proxy=meshes)
    times = list(meshes.TimestepValues) if hasattr(meshes.TimestepValues, "__len__") else [meshes.TimestepValues]
    arrays = [meshes.PointData.GetArray(i).Name for i in range(meshes.PointData.GetNumberOfArrays())]
    print("meshes: %d time steps, point arrays %s" % (len(times), arrays))
    display = Show(meshes, view)
    display.DiffuseColor = [0.75, 0.88, 1.0]
    display.Opacity = 0.6
    fields_pvd = os.path.join(run_dir, "fields.pvd")
    if os.path.exists(fields_pvd):
        fields = OpenDataFile(fields_pvd)
        UpdatePipeline(proxy=fields)
        names = [fields.CellData.GetArray(i).Name for i in range(fields.CellData.GetNumberOfArrays())]
        ftimes = fields.TimestepValues
        print("fields: %d time steps, cell arrays %s" % (len(ftimes) if hasattr(ftimes, "__len__") else 1, names))
        cut = Slice(Input=fields)
        cut.SliceType.Normal = [0.0, 0.0, 1.0]
        shown = Show(cut, view)
        ColorBy(shown, ("CELLS", "temperature_c"))
        lut = GetColorTransferFunction("temperature_c")
        lut.ApplyPreset("Cool to Warm", True)
    scene = GetAnimationScene()
    scene.UpdateAnimationUsingDataTimeSteps()
    ResetCamera(view)
    if screenshot:
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
