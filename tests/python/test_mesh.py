"""thaw.mesh: one step's surface as `thaw mesh` writes it (the OBJ's vertices and triangles)."""
import numpy as np
import pytest

import thaw
from conftest import run_cli


def _read_obj(path):
    v, f = [], []
    for line in path.read_text().splitlines():
        if line.startswith("v "):
            v.append([float(x) for x in line.split()[1:4]])
        elif line.startswith("f "):
            f.append([int(c.split("/")[0]) - 1 for c in line.split()[1:4]])
    return np.array(v), np.array(f)


@pytest.mark.parametrize("surface", ["outer", "inner"])
def test_1d_step_matches_thaw_mesh(short_scenario_file, scratch, surface):
    out = scratch / "sim"
    run_cli("simulate", short_scenario_file, "--out", out, "-q")
    run_cli("mesh", out, "--quiet")
    r = thaw.simulate(short_scenario_file)
    step = 7
    v, f = thaw.mesh(r, step, surface=surface)
    cv, cf = _read_obj(out / "mesh" / f"step_{step:06d}_{surface}.obj")
    assert v.shape == cv.shape and f.shape == cf.shape and f.dtype == np.int64
    assert np.array_equal(v, cv) and np.array_equal(f, cf)


def test_grid_step_matches_thaw_mesh(grid_scenario_file, scratch):
    out = scratch / "sim"
    run_cli("simulate", grid_scenario_file, "--out", out, "-q")
    run_cli("mesh", out, "--quiet")
    r = thaw.simulate(grid_scenario_file)
    v, f = thaw.mesh(r, 2)
    cv, cf = _read_obj(out / "mesh" / "step_000002_outer.obj")
    assert np.array_equal(v, cv) and np.array_equal(f, cf)


def test_a_bad_surface_name_is_a_user_error(short_scenario_file):
    r = thaw.simulate(short_scenario_file)
    with pytest.raises(thaw.UserError) as e:
        thaw.mesh(r, 0, surface="middle")
    assert e.value.key == "surface"
