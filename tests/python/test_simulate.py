"""thaw.simulate and its Result: the command line's results bit for bit; fields without copies."""
import json
import sys

import numpy as np
import pytest

import thaw
from conftest import run_cli


def _cli_result(scenario_file, out):
    run_cli("simulate", scenario_file, "--out", out, "-q")
    return out


def _without_wall_time(summary):
    summary = dict(summary)
    summary.pop("wall_time_s")
    return summary


def test_1d_matches_the_cli_byte_for_byte(short_scenario_file, scratch):
    out = _cli_result(short_scenario_file, scratch / "cli")
    r = thaw.simulate(thaw.Scenario.load(short_scenario_file))
    csv = (out / "interfaces.csv").read_text()
    assert r.interfaces_csv() == csv
    # the arrays hold exactly the doubles the CSV's 17 digits stand for
    table = np.genfromtxt(out / "interfaces.csv", delimiter=",", names=True)
    for name in table.dtype.names:
        assert np.array_equal(r.interfaces[name], table[name]), name
    cli_summary = json.loads((out / "summary.json").read_text())
    assert _without_wall_time(r.summary) == _without_wall_time(cli_summary)
    assert r.events == [{k: e[k] for k in ("kind", "time_s", "radius_m")} for e in cli_summary["events"]]
    # write() is `thaw simulate --out`: the same files (summary.json but for the wall time)
    r.write(scratch / "py")
    assert (scratch / "py" / "interfaces.csv").read_bytes() == (out / "interfaces.csv").read_bytes()
    for name in ("step_000000.csv", "step_000005.csv"):
        assert (scratch / "py" / "profiles" / name).read_bytes() == (out / "profiles" / name).read_bytes()


def test_grid_matches_the_cli_byte_for_byte(grid_scenario_file, scratch):
    out = _cli_result(grid_scenario_file, scratch / "cli")
    r = thaw.simulate(grid_scenario_file)
    assert r.interfaces_csv() == (out / "interfaces.csv").read_text()
    r.write(scratch / "py")
    for step in range(r.steps):
        name = f"fields/step_{step:06d}.grid"
        assert (scratch / "py" / name).read_bytes() == (out / name).read_bytes()


def test_grid_fields_are_read_only_views_owned_by_the_result(grid_scenario_file):
    r = thaw.simulate(grid_scenario_file)
    g = r.grid
    f = r.fields(1)
    for name in ("temperature_c", "liquid_fraction", "ice_fraction"):
        a = f[name]
        assert a.base is r, name  # a view of the Result's memory: no copy
        assert not a.flags.writeable and not a.flags.owndata
        assert a.shape == tuple(g["cells"]) and a.dtype == np.float32
        with pytest.raises(ValueError):
            a[0, 0, 0] = 1.0
    # the same memory on every call (O(1): nothing is made)
    assert f["temperature_c"].__array_interface__["data"][0] == \
        r.fields(1)["temperature_c"].__array_interface__["data"][0]
    assert float(f["ice_fraction"].sum()) > 0
    # the array keeps the result alive after the last reference to it is gone
    t = r.fields(-1)["temperature_c"]
    expected = t.copy()
    del r, f
    assert np.array_equal(t, expected)
    assert sys.getrefcount(t.base) >= 2


def test_grid_velocity_is_a_read_only_view_of_the_flow(flow_scenario_file, scratch):
    r = thaw.simulate(flow_scenario_file)
    g = r.grid
    u = r.fields(-1)["velocity_m_s"]
    assert u.base is r and not u.flags.writeable and not u.flags.owndata
    assert u.shape == (*g["cells"], 3) and u.dtype == np.float32
    with pytest.raises(ValueError):
        u[0, 0, 0, 0] = 1.0
    # the cell-centre velocities whose largest speed summary.json reports (float rounding)
    speed = np.sqrt((u.astype(np.float64) ** 2).sum(axis=-1))
    reported = r.summary["flow"][-1]["max_speed_m_s"]
    assert reported > 0
    assert abs(speed.max() - reported) <= 1e-6 * reported
    assert np.all(u[..., 2] == 0)  # axisymmetric: (u_r, u_y, 0)
    # the CLI's field files hold the same bytes
    out = _cli_result(flow_scenario_file, scratch / "cli")
    r.write(scratch / "py")
    for step in range(r.steps):
        name = f"fields/step_{step:06d}.grid"
        assert (scratch / "py" / name).read_bytes() == (out / name).read_bytes()


def test_grid_velocity_without_flow_is_zero_and_costs_nothing(grid_scenario_file):
    r = thaw.simulate(grid_scenario_file)
    u = r.fields(1)["velocity_m_s"]
    assert u.base is r and not u.flags.writeable
    assert u.shape == (*r.grid["cells"], 3) and not u.any()
    assert u.strides[:3] == (0, 0, 0)  # one (0, 0, 0) seen from every cell: no memory per cell


def test_1d_fields_view_the_profile(short_scenario_file):
    r = thaw.simulate(short_scenario_file)
    f = r.fields(3)
    for name in ("radius_m", "temperature_c", "liquid_fraction"):
        assert f[name].base is r and not f[name].flags.writeable
    assert np.all(np.diff(f["radius_m"]) >= 0)
    water = f["liquid_fraction"] == 1.0
    assert water.any() and (~water).any()
    with pytest.raises(IndexError):
        r.fields(r.steps)


def test_progress_is_called_on_this_thread(short_scenario_file):
    seen = []
    thaw.simulate(short_scenario_file, progress=lambda stage, done, total: seen.append((stage, done, total)))
    assert seen and seen[-1][1] <= seen[-1][2] and all(s == "simulate" for s, _, _ in seen)


def test_a_callback_that_raises_stops_the_run_and_the_next_call_works(short_scenario_file):
    def stop(stage, done, total):
        raise RuntimeError("enough")
    with pytest.raises(RuntimeError, match="enough"):
        thaw.simulate(thaw.Scenario.load(short_scenario_file).with_(**{"simulation.duration_s": 3600.0}), progress=stop)
    assert thaw.simulate(short_scenario_file).steps == 11
