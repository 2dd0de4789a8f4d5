"""thaw.run: `thaw run` as a call, the same files (a frame's PNG byte for byte), with progress."""
import pytest

import thaw
from conftest import run_cli


def test_one_frame_matches_the_cli_byte_for_byte(short_scenario_file, scratch):
    run_cli("run", short_scenario_file, "--out", scratch / "cli", "--frames", "2",
            "--size", "64x48", "--spp", "1", "-q")
    seen = []
    report = thaw.run(thaw.Scenario.load(short_scenario_file), scratch / "py", frames=2,
                      size=(64, 48), spp=1, progress=lambda *a: seen.append(a))
    for name in ("frames/frame_000002.png", "sim/interfaces.csv", "scenario.toml"):
        assert (scratch / "py" / name).read_bytes() == (scratch / "cli" / name).read_bytes(), name
    stages = [s["stage"] for s in report["stages"]]
    assert "simulate" in stages and "render" in stages
    titles = {t for t, _, _ in seen}
    assert any("simulate" in t for t in titles) and any("render" in t for t in titles)
    # a rerun is incremental: nothing to do
    again = thaw.run(thaw.Scenario.load(short_scenario_file), scratch / "py", frames=2,
                     size=(64, 48), spp=1)
    assert all(s["skipped"] for s in again["stages"] if s["stage"] in ("simulate", "render"))


def test_run_checks_thaw_runs_own_sections(short_scenario_file, scratch):
    sc = thaw.Scenario.load(short_scenario_file).with_(**{"render.image.widht": 10})
    cli_file = scratch / "bad.toml"
    cli_file.write_text(sc.text)
    cli = run_cli("run", cli_file, "--out", scratch / "cli", "-q", check=False)
    assert cli.returncode == 2
    with pytest.raises(thaw.UserError) as e:
        thaw.run(thaw.Scenario.load(cli_file), scratch / "py")
    assert "unknown key" in e.value.problem and "render.image.widht" in str(e.value)
    assert cli.stderr.strip() == "thaw: error: " + str(e.value)
    with pytest.raises(thaw.UserError) as e:
        thaw.run(sc, scratch / "py", frames="5-2")
    assert e.value.key == "--frames"
