#!/usr/bin/python3
"""Sweep the water's temperature across 4 C (water's density maximum) and compare the shells.

    /usr/bin/python3 examples/sweep.py [--out DIR] [--quick]

For each water temperature the bored ice cylinder (data/scenarios/bored_cylinder.toml: a 4 cm
ice cylinder with a water-filled 1.6 cm bore, axisymmetric grid solver) melts in 25 C air until
the shell breaks through. Plots (DIR/sweep.png): the break-through time against the water's
temperature, and the shell's cross-section (the ice fraction's 1/2 contour in the r-y plane) at
break-through, one line per temperature. The same as examples/sweep.ipynb, as a plain script.
The water flows (natural convection, the grid solver's default), so the 4 C maximum of its
density turns the melt over. --quick: three temperatures on a coarser grid without the flow (what
CTest runs: a 1 mm cell cannot resolve the flow's boundary layer, which thaw refuses).
"""
import argparse
import os
import pathlib

import matplotlib

matplotlib.use("Agg")  # headless: no display needed
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import thaw  # noqa: E402

HERE = pathlib.Path(__file__).resolve().parent
SCENARIO = HERE.parent / "data" / "scenarios" / "bored_cylinder.toml"


def sweep(temperatures_c, cell_size_m=0.0, output_interval_s=20.0, flow="natural_convection"):
    """One simulation per water temperature; returns a list of dicts (temperature, break-through
    time, the result, the output step at break-through)."""
    base = thaw.Scenario.load(SCENARIO).with_(**{
        "simulation.output_interval_s": output_interval_s,
        "simulation.cell_size_m": cell_size_m,
        "simulation.flow": flow})
    runs = []
    for t in temperatures_c:
        result = thaw.simulate(base.with_(**{"water.initial_temperature_c": float(t)}))
        through = [e["time_s"] for e in result.events if e["kind"] == "break_through"]
        time_s = through[0] if through else float("nan")
        times = result.interfaces["time_s"]
        # the first output at or after the break-through: the shell as it opens
        step = int(np.searchsorted(times, time_s)) if through else result.steps - 1
        runs.append({"temperature_c": t, "break_through_s": time_s, "result": result,
                     "step": min(step, result.steps - 1)})
    return runs


def plot(runs, path):
    fig, (ax_t, ax_s) = plt.subplots(1, 2, figsize=(11, 4.6))
    temps = [r["temperature_c"] for r in runs]
    ax_t.plot(temps, [r["break_through_s"] / 60 for r in runs], "o-")
    ax_t.axvline(4.0, color="0.6", ls="--", lw=1)
    ax_t.text(4.05, 0.97, "4 C: densest water", color="0.4", va="top",
              transform=ax_t.get_xaxis_transform())
    ax_t.set_xlabel("water temperature at t = 0 [C]")
    ax_t.set_ylabel("break-through time [min]")
    ax_t.set_title("When the shell opens")
    colors = plt.cm.viridis(np.linspace(0, 0.9, len(runs)))
    for run, c in zip(runs, colors):
        result, step = run["result"], run["step"]
        g = result.grid
        ice = result.fields(step)["ice_fraction"][:, :, 0]  # (nr, ny) of the axisymmetric grid
        h = g["spacing_m"]
        r = (np.arange(g["cells"][0]) + 0.5) * h
        y = g["origin_m"][1] + (np.arange(g["cells"][1]) + 0.5) * h
        # both halves of the section: the axis is r = 0
        rr = np.concatenate([-r[::-1], r]) * 100
        field = np.concatenate([ice[::-1, :], ice], axis=0)
        ax_s.contour(rr, y * 100, field.T, levels=[0.5], colors=[c])
        ax_s.plot([], [], color=c, label=f"{run['temperature_c']:g} C, "
                                         f"t = {result.interfaces['time_s'][step] / 60:.1f} min")
    ax_s.set_aspect("equal")
    ax_s.set_xlabel("x [cm]")
    ax_s.set_ylabel("y [cm]")
    ax_s.set_title("Ice at break-through (ice fraction = 1/2)")
    ax_s.legend(fontsize=8, loc="upper right")
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", default="sweep-out", help="folder for sweep.png")
    ap.add_argument("--quick", action="store_true", help="3 temperatures, coarse grid (CTest)")
    args = ap.parse_args()
    quick = args.quick or os.environ.get("THAW_SWEEP_QUICK") == "1"
    temps = [2.0, 4.0, 6.0] if quick else [0.5, 2.0, 4.0, 6.0, 8.0]
    runs = sweep(temps, cell_size_m=1e-3 if quick else 0.0,
                 flow="none" if quick else "natural_convection")
    out = pathlib.Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    plot(runs, out / "sweep.png")
    for r in runs:
        print(f"water {r['temperature_c']:4.1f} C: break-through at {r['break_through_s'] / 60:6.2f} min")
    print(f"plot: {out / 'sweep.png'}")
    assert all(np.isfinite(r["break_through_s"]) for r in runs), "a shell did not break through"


if __name__ == "__main__":
    main()
