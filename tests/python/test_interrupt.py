"""Ctrl-C during a long thaw.simulate raises KeyboardInterrupt within 1 s, and the next call
works. The simulation runs in a child Python, which is sent SIGINT as a terminal would send it."""
import os
import signal
import subprocess
import sys
import time

CHILD = r"""
import sys, time
import thaw
sc = thaw.Scenario.load(sys.argv[1])
small = thaw.Scenario.default().with_(**{"simulation.duration_s": 120.0})
print("ready", flush=True)
sys.stdin.readline()
start = time.monotonic()
try:
    print("started", flush=True)
    thaw.simulate(sc)
    print("finished without interrupt", flush=True)
except KeyboardInterrupt:
    print("interrupted at %.3f" % time.monotonic(), flush=True)
r = thaw.simulate(small)
print("next call: %d steps" % r.steps, flush=True)
"""


def _long_scenario(tmp_path):
    # A 3D grid run of ten hours in gentle air with a single output interval: thousands of time
    # steps (at most 10 s each) and no output time to stop at, so the solver's own check between
    # steps is what answers Ctrl-C.
    from conftest import SOURCE_DIR
    text = (SOURCE_DIR / "data" / "scenarios" / "hollow_cube.toml").read_text()
    import thaw
    sc = thaw.Scenario.from_toml(text, "hollow_cube.toml").with_(**{
        "simulation.duration_s": 36000.0, "simulation.output_interval_s": 36000.0,
        "simulation.cell_size_m": 0.002, "simulation.flow": "none",
        "outer_boundary.heat_transfer_coefficient_w_m2k": 5.0})
    path = tmp_path / "long.toml"
    path.write_text(sc.text)
    return path


def test_ctrl_c_interrupts_within_a_second_and_the_next_call_works(tmp_path):
    child = subprocess.Popen([sys.executable, "-c", CHILD, str(_long_scenario(tmp_path))],
                             stdin=subprocess.PIPE, stdout=subprocess.PIPE, text=True)
    try:
        assert child.stdout.readline().strip() == "ready"
        child.stdin.write("go\n")
        child.stdin.flush()
        assert child.stdout.readline().strip() == "started"
        time.sleep(2.0)  # well inside the solver's work
        sent = time.monotonic()
        child.send_signal(signal.SIGINT)
        line = child.stdout.readline().strip()
        assert line.startswith("interrupted at "), line
        latency = float(line.split()[-1]) - sent
        print(f"KeyboardInterrupt {latency * 1000:.0f} ms after SIGINT")
        assert latency < 1.0
        assert child.stdout.readline().strip() == "next call: 3 steps"
        assert child.wait(timeout=60) == 0
    finally:
        if child.poll() is None:
            child.kill()
