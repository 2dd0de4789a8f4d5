"""Bad input raises thaw.UserError with the command line's text (the cases of
tests/sim/cli_simulate.sh and tests/render/check_render_bad_input.sh), and nothing else."""
import pytest

import thaw
from conftest import SOURCE_DIR, cli_error_text, run_cli

BASE = thaw.Scenario.default().text
GRID = """[simulation]
geometry = "3d"
duration_s = 60.0
output_interval_s = 30.0
[shape]
outer = { kind = "box", size_m = [0.04, 0.04, 0.04] }
cavity = { kind = "box", size_m = [0.024, 0.024, 0.024] }
[water]
initial_temperature_c = 10.0
[ice]
initial_temperature_c = -5.0
[outer_boundary]
kind = "convective"
temperature_c = 25.0
heat_transfer_coefficient_w_m2k = 50.0
"""
BOX = 'kind = "box", size_m = [0.04, 0.04, 0.04]'
CAVITY = 'cavity = { kind = "box", size_m = [0.024, 0.024, 0.024] }'


def _hot():
    hot = BASE.replace('kind = "convective"', 'kind = "temperature"', 1)
    return hot.replace("heat_transfer_coefficient_w_m2k = 50.0", "", 1)


# name -> scenario text (None: a file that does not exist), as in cli_simulate.sh
SIMULATE_CASES = {
    "missing_file": None,
    "malformed": "[simulation\n",
    "unknown_key": BASE.replace("inner_radius_m", "inner_radus_m", 1),
    "negative": BASE.replace("inner_radius_m = 0.02", "inner_radius_m = -0.02", 1),
    "nan": BASE.replace("outer_radius_m = 0.03", "outer_radius_m = nan", 1),
    "inf": BASE.replace("duration_s = 3600.0", "duration_s = inf", 1),
    "inner_gt_outer": BASE.replace("inner_radius_m = 0.02", "inner_radius_m = 0.04", 1),
    "zero_duration": BASE.replace("duration_s = 3600.0", "duration_s = 0.0", 1),
    "long_interval": BASE.replace("output_interval_s = 60.0", "output_interval_s = 7200.0", 1),
    "hot_surface": _hot(),
    "grid_cube_axisymmetric": GRID.replace('"3d"', '"axisymmetric"'),
    "grid_cavity_touching": GRID.replace("[0.024, 0.024, 0.024]", "[0.04, 0.024, 0.024]"),
    "grid_too_coarse": GRID.replace("output_interval_s = 30.0", "output_interval_s = 30.0\ncell_size_m = 0.004"),
    "grid_unknown_kind": GRID.replace(BOX, 'kind = "cube"'),
    "grid_negative_size": GRID.replace("[0.04, 0.04, 0.04]", "[0.04, -0.04, 0.04]"),
    "grid_cavity_outside": GRID.replace(CAVITY, 'cavity = { kind = "sphere", radius_m = 0.005, center_m = [0.1, 0.0, 0.0] }'),
    "grid_zero_size": GRID.replace(CAVITY, 'cavity = { kind = "sphere", radius_m = 0.0 }'),
}


@pytest.mark.parametrize("name", sorted(SIMULATE_CASES))
def test_simulate_bad_input_has_the_cli_text(name, scratch):
    text = SIMULATE_CASES[name]
    path = scratch / f"{name}.toml"
    if text is not None:
        assert text != BASE, "the fixture did not change the scenario"
        path.write_text(text)
    cli = run_cli("simulate", path, "--out", scratch / "out", "-q", check=False)
    assert cli.returncode == 2, cli.stderr
    with pytest.raises(thaw.UserError) as e:
        thaw.simulate(thaw.Scenario.load(path))
    assert str(e.value) == cli_error_text(cli.stderr)
    assert e.value.problem and e.value.problem in str(e.value)
    assert not (scratch / "out").exists()


def test_an_open_obj_shape_has_the_cli_text(scratch):
    obj = scratch / "open.obj"
    obj.write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\n")
    path = scratch / "open.toml"
    path.write_text(GRID.replace(BOX, f'kind = "obj", file = "{obj}", scale = 0.05'))
    cli = run_cli("simulate", path, "--out", scratch / "out", "-q", check=False)
    with pytest.raises(thaw.UserError) as e:
        thaw.simulate(thaw.Scenario.load(path))
    assert str(e.value) == cli_error_text(cli.stderr) and "open.obj" in e.value.file + str(e.value)


SCENE = SOURCE_DIR / "data" / "scenes" / "s1_ice_shell.toml"
# name -> sed-like (old, new) edit of s1_ice_shell.toml, as in check_render_bad_input.sh
RENDER_CASES = {
    "unknown_key": ("max_depth = 10", "max_dpth = 10"),
    "unknown_medium": ('inside = "water"', 'inside = "watr"'),
    "unknown_material": ('material = "floor"', 'material = "flor"'),
    "zero_width": ("width = 640", "width = 0"),
    "huge_size": ("height = 640", "height = 1000000"),
    "missing_obj": ("meshes/floor_200.obj", "meshes/nothing.obj"),
    "unknown_filter": ("max_depth = 10", 'max_depth = 10\nfilter = "lanczos"'),
}


@pytest.mark.parametrize("name", sorted(RENDER_CASES))
def test_render_bad_input_has_the_cli_text(name, scratch):
    old, new = RENDER_CASES[name]
    text = SCENE.read_text()
    assert old in text
    (scratch / "meshes").symlink_to(SCENE.parent / "meshes")  # its relative mesh files
    path = scratch / f"{name}.toml"
    path.write_text(text.replace(old, new, 1))
    cli = run_cli("render", path, "-o", scratch / "out.png", "--quiet", check=False)
    assert cli.returncode == 2, cli.stderr
    with pytest.raises(thaw.UserError) as e:
        thaw.render(path)
    assert str(e.value) == cli_error_text(cli.stderr)


def test_render_overrides_are_checked_by_the_keys_rules():
    with pytest.raises(thaw.UserError) as e:
        thaw.render(SCENE, width=0)
    assert e.value.key == "width" and "must be between" in e.value.problem
    with pytest.raises(thaw.UserError) as e:
        thaw.render(SCENE, widht=10)
    assert "unknown override" in e.value.problem
    with pytest.raises(thaw.UserError) as e:
        thaw.render(SCENE, spp="many")
    assert "must be an integer" in e.value.problem


def test_errors_of_the_two_kinds_are_distinct():
    assert not issubclass(thaw.UserError, thaw.InternalError)
    assert not issubclass(thaw.InternalError, thaw.UserError)
    with pytest.raises(IndexError):
        thaw.mesh(thaw.simulate(thaw.Scenario.default().with_(**{"simulation.duration_s": 120.0})), 99)
