"""1,000 simulate calls of a small scenario in one process: resident memory grows by <= 5 MB
(Mitsuba 3 issue 1890 is the failure this guards against: memory growing in a sweep loop)."""
import gc

import thaw


def _rss_bytes():
    with open("/proc/self/status") as f:
        for line in f:
            if line.startswith("VmRSS:"):
                return int(line.split()[1]) * 1024
    raise AssertionError("no VmRSS in /proc/self/status")


def test_a_thousand_simulate_calls_keep_memory_flat():
    small = thaw.Scenario.default().with_(**{"simulation.duration_s": 120.0})
    for _ in range(50):  # warm-up: allocator pools, NumPy's caches, the first imports
        r = thaw.simulate(small)
        r.fields(1)
        r.summary
    gc.collect()
    before = _rss_bytes()
    for k in range(1000):
        r = thaw.simulate(small)
        f = r.fields(k % r.steps)["temperature_c"]
        assert r.interfaces["time_s"][-1] == 120.0 and f.base is r
    del r, f
    gc.collect()
    grown = _rss_bytes() - before
    print(f"RSS grew by {grown / 2**20:.2f} MiB over 1000 calls")
    assert grown <= 5 * 2**20
