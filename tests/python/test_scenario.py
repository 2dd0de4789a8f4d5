"""thaw.Scenario: made from a file, the built-in default, a dict; edited with with_()."""
import pytest

import thaw
from conftest import SOURCE_DIR


def test_default_is_the_built_in_file():
    sc = thaw.Scenario.default()
    assert sc.text == (SOURCE_DIR / "data" / "scenarios" / "default.toml").read_text()
    p = sc.parameters
    assert p["shell"]["inner_radius_m"] == 0.02 and p["shell"]["outer_radius_m"] == 0.03
    assert sc.output_times[0] == 0.0 and sc.output_times[-1] == p["simulation"]["duration_s"]


def test_load_reads_the_file_as_given():
    path = SOURCE_DIR / "data" / "scenarios" / "water_drop_freezing.toml"
    sc = thaw.Scenario.load(path)
    assert sc.text == path.read_text() and sc.source == str(path)
    assert sc.parameters == thaw.Scenario.from_toml(path.read_text()).parameters


def test_from_dict_round_trips_every_parameter():
    base = thaw.Scenario.default()
    again = thaw.Scenario.from_dict(base.to_dict())
    assert again.parameters == base.parameters
    assert again.source == "<dict>"


def test_with_changes_one_key_and_nothing_else():
    base = thaw.Scenario.default()
    warm = base.with_(**{"water.initial_temperature_c": 4.0})
    assert warm.parameters["water"]["initial_temperature_c"] == 4.0
    p, q = base.parameters, warm.parameters
    p["water"]["initial_temperature_c"] = 4.0
    assert p == q
    assert base.parameters["water"]["initial_temperature_c"] == 10.0  # immutable
    with pytest.raises(AttributeError):
        base.text = "x"


def test_with_a_misspelt_key_is_an_error_not_a_default():
    with pytest.raises(thaw.UserError) as e:
        thaw.Scenario.default().with_(**{"water.initial_temperatur_c": 4.0})
    assert "unknown key" in e.value.problem and "water.initial_temperatur_c" in str(e.value)


def test_with_a_value_out_of_range_names_the_key():
    with pytest.raises(thaw.UserError) as e:
        thaw.Scenario.default().with_(**{"shell.inner_radius_m": -0.01})
    assert "shell.inner_radius_m" in e.value.key and "must not be negative" in e.value.problem


def test_from_dict_names_a_missing_required_key():
    with pytest.raises(thaw.UserError) as e:
        thaw.Scenario.from_dict({"simulation": {"duration_s": 120.0}}, source="mine")
    assert e.value.file == "mine" and "simulation.geometry" in e.value.key
    assert e.value.problem == "required key is missing"
