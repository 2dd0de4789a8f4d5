"""thaw.render: the pixels `thaw render -o image.pfm` writes, bit for bit."""
import numpy as np

import thaw
from conftest import SOURCE_DIR, run_cli

SCENE = SOURCE_DIR / "data" / "scenes" / "s1_ice_shell.toml"


def _read_pfm(path):
    data = path.read_bytes()
    header, rest = data.split(b"\n", 1)
    size, rest = rest.split(b"\n", 1)
    scale, pixels = rest.split(b"\n", 1)
    assert header == b"PF" and float(scale) < 0  # colour, little endian
    w, h = map(int, size.split())
    return np.frombuffer(pixels, dtype="<f4").reshape(h, w, 3)[::-1]  # PFM: bottom row first


def test_render_matches_the_cli_bit_for_bit(scratch):
    run_cli("render", SCENE, "-o", scratch / "cli.pfm", "--width", 48, "--height", 40, "--quiet")
    cli = _read_pfm(scratch / "cli.pfm")
    img = thaw.render(SCENE, width=48, height=40)
    assert img.shape == (40, 48, 3) and img.dtype == np.float32
    assert img.tobytes() == np.ascontiguousarray(cli).tobytes()
    assert img.max() > 0


def test_render_a_scene_dict_and_thread_counts_agree(scratch, monkeypatch):
    import tomllib
    scene = tomllib.loads(SCENE.read_text())
    monkeypatch.chdir(SCENE.parent)  # the dict's relative mesh files
    a = thaw.render(scene, width=32, height=32, threads=1)
    b = thaw.render(SCENE, width=32, height=32, threads=2)
    assert np.array_equal(a, b)
