"""Shared set-up of the thaw module's tests: this build's CLI and data, a scratch folder, and
the small scenarios the tests run (a few seconds of solver time at most)."""
import os
import pathlib
import subprocess
import sys

import pytest

import thaw

SOURCE_DIR = pathlib.Path(os.environ.get("THAW_SOURCE_DIR", pathlib.Path(__file__).parents[2]))
THAW_EXE = os.environ.get("THAW_EXE", str(SOURCE_DIR / "build" / "thaw"))


def run_cli(*args, check=True):
    """Runs this build's `thaw` with args; returns the CompletedProcess (text)."""
    p = subprocess.run([THAW_EXE, *map(str, args)], capture_output=True, text=True)
    if check and p.returncode != 0:
        raise AssertionError(f"thaw {' '.join(map(str, args))}: exit {p.returncode}: {p.stderr}")
    return p


def cli_error_text(stderr):
    """The problem of the CLI's one-line error, as str(thaw.UserError) holds it."""
    lines = stderr.splitlines()
    assert len(lines) == 1, stderr
    prefix = "thaw: error: "
    assert lines[0].startswith(prefix), stderr
    return lines[0][len(prefix):]


SHORT_1D = {"simulation.duration_s": 600.0, "simulation.output_interval_s": 60.0}


@pytest.fixture
def scratch(tmp_path):
    return tmp_path


@pytest.fixture(scope="session")
def short_scenario_file(tmp_path_factory):
    """The default scenario shortened to 10 minutes, as a file the CLI and Python both read."""
    path = tmp_path_factory.mktemp("scenarios") / "short.toml"
    text = thaw.Scenario.default().with_(**SHORT_1D).text
    path.write_text(text)
    return path


@pytest.fixture(scope="session")
def grid_scenario_file(tmp_path_factory):
    """The hollow cube cut to one minute (two output steps after t = 0): a 3D grid run, conduction
    only (its water's flow costs ~45 s of CPU)."""
    src = (SOURCE_DIR / "data" / "scenarios" / "hollow_cube.toml").read_text()
    text = src.replace("duration_s = 3600.0", "duration_s = 60.0").replace(
        "output_interval_s = 60.0", "output_interval_s = 30.0").replace(
        "max_step_s = 10.0", 'max_step_s = 10.0\nflow = "none"')
    assert 'flow = "none"' in text
    assert "duration_s = 60.0" in text
    path = tmp_path_factory.mktemp("scenarios") / "cube.toml"
    path.write_text(text)
    return path


@pytest.fixture(scope="session")
def flow_scenario_file(tmp_path_factory):
    """data/scenarios/hollow_sphere_flow.toml (natural convection) cut to 20 s on 0.6 mm cells
    (2.2 across the water's thermal boundary layer, sim/grid/grid_rules.h)."""
    src = (SOURCE_DIR / "data" / "scenarios" / "hollow_sphere_flow.toml").read_text()
    text = src.replace("duration_s = 3600.0", "duration_s = 20.0").replace(
        "output_interval_s = 60.0", "output_interval_s = 10.0").replace(
        "max_step_s = 10.0", "max_step_s = 10.0\ncell_size_m = 0.0006")
    assert "duration_s = 20.0" in text and "cell_size_m" in text
    path = tmp_path_factory.mktemp("scenarios") / "flow.toml"
    path.write_text(text)
    return path
