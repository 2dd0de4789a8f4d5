# Checks data/paraview/open_run.py on a thaw run folder without ParaView: the script runs against
# the stand-in paraview.simple of fake_paraview/ (VTK's own readers), then this checks what it
# did against the files:
# - every .pvd it opened lists only files VTK reads (the stand-in's OpenDataFile);
# - meshes.pvd is opened; where the surfaces carry point data temperature_c (grid runs) they are
#   coloured by it, on a colour scale that holds every surface temperature of the run; where they
#   do not (1D runs) they are a solid colour;
# - fields.pvd, where the run has one, is opened, cut through the middle with cells at every time
#   step and coloured by its cell data temperature_c on the same scale;
# - both are time series with one time step per .pvd time.
# Usage: /usr/bin/python3 check_open_run.py SCRIPT RUN_DIR [--expect grid|1d]
# Prints "open_run.py checked: ..." and exits 0, or a traceback and exits 1.
import importlib.util
import os
import sys
import xml.etree.ElementTree as ElementTree

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "fake_paraview"))
from paraview import simple  # noqa: E402  (the stand-in, found first)


def pvd_times(path):
    return sorted({float(ds.get("timestep", "0")) for ds in ElementTree.parse(path).getroot().iter("DataSet")})


def surface_temperatures(source):
    values = []
    for _, blocks in source.all_steps():
        for b in blocks:
            a = b.GetPointData().GetArray("temperature_c")
            if a is not None:
                values += [a.GetValue(i) for i in range(a.GetNumberOfTuples())]
    return values


def main():
    script, run_dir = sys.argv[1], sys.argv[2]
    expect = sys.argv[sys.argv.index("--expect") + 1] if "--expect" in sys.argv else None
    spec = importlib.util.spec_from_file_location("open_run", script)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    times = module.open_run(run_dir, screenshot=os.path.join(run_dir, "paraview_check.png"))
    record = simple.RECORD
    by_name = {s.name: s for s in record["sources"]}
    meshes = by_name["meshes.pvd"]
    assert times == pvd_times(os.path.join(run_dir, "meshes.pvd")), "meshes' time steps"
    mesh_display = next(d for d in record["displays"] if d._source is meshes)
    temperatures = surface_temperatures(meshes)
    grid = bool(temperatures)
    assert expect is None or expect == ("grid" if grid else "1d"), "expected a %s run" % expect
    lut = record["luts"].get("temperature_c")
    if grid:
        assert mesh_display._colour == ("POINTS", "temperature_c"), mesh_display._colour
        assert lut and lut._preset and lut._range, "a temperature colour scale with a range"
        assert lut._range[0] <= min(temperatures) and max(temperatures) <= lut._range[1], \
            "scale %r holds the surfaces' %g..%g C" % (lut._range, min(temperatures), max(temperatures))
        assert mesh_display._scalar_bar, "a colour legend"
    else:
        assert mesh_display._colour is None, "1D surfaces: a solid colour, got %r" % (mesh_display._colour,)
        assert len(getattr(mesh_display, "DiffuseColor", [])) == 3
    fields_pvd = os.path.join(run_dir, "fields.pvd")
    checked = ["meshes: %d steps, %s" % (len(times), "temperature_c" if grid else "solid colour")]
    if os.path.exists(fields_pvd):
        fields = by_name["fields.pvd"]
        assert fields.TimestepValues == pvd_times(fields_pvd), "fields' time steps"
        cut = next(s for s in record["sources"] if isinstance(s, simple.SliceFilter) and s._input is fields)
        cut_display = next(d for d in record["displays"] if d._source is cut)
        assert cut_display._colour == ("CELLS", "temperature_c"), cut_display._colour
        for t, blocks in cut.all_steps():
            assert sum(b.GetNumberOfCells() for b in blocks) > 0, "empty slice at t = %g" % t
        checked.append("fields: %d steps, slice coloured by temperature_c" % len(fields.TimestepValues))
    else:
        assert not grid, "a grid run's folder has fields.pvd"
    assert record["screenshots"], "the screenshot was asked for"
    print("open_run.py checked: " + "; ".join(checked))


if __name__ == "__main__":
    main()
