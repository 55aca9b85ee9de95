#!/usr/bin/python3
"""The demo's preload sweep (paper Fig. 20: E(N0) with the regime map) from Python.

Runs the blade scene of examples/blade_damper at log-spaced preloads on a thread pool (the
module releases the GIL while it integrates), writes OUT/sweep_python.csv and draws
OUT/sweep_python.png as examples/blade_damper/plot.py draws the demo's sweep.png.

    PYTHONPATH=build/python /usr/bin/python3 examples/python/sweep.py --count 32 --duration 20
"""
import argparse
import concurrent.futures
import csv
import math
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import blade_scene as blade  # noqa: E402

REGIMES = {"gross slip": "tab:red", "stick-slip": "tab:orange", "stick": "tab:blue"}
STOPPED = ("lift-off", "left platform", "run stopped")


def sweep_point(preload, duration):
    scene = blade.make_blade_scene(blade.BladeParameters(preload=preload))
    run, summary = blade.run(scene, duration, record_states=False)
    return {"preload_N": preload, "energy_density_m2": summary["energy_density"], "regime": summary["regime"],
            "stick_fraction_1": summary["stick_fraction"][0], "stick_fraction_2": summary["stick_fraction"][1],
            "tip_max_m": summary["tip_max"], "status": str(run.status).split(".")[-1],
            "rhs_evaluations": run.stats.rhs_evaluations, "events": len(scene.system.events())}


def plot(rows, png):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    p = [r["preload_N"] for r in rows]
    e = [r["energy_density_m2"] for r in rows]
    fig, ax = plt.subplots(figsize=(7, 4.5))
    ax.plot(p, e, "-", color="0.6", lw=1)
    stopped = [r["preload_N"] for r in rows if r["regime"] in STOPPED]
    for x in stopped:
        ax.axvline(x, color="tab:gray", alpha=0.3, lw=6)
    if stopped:
        ax.plot([], [], color="tab:gray", alpha=0.3, lw=6, label="run stopped (lift-off / left platform)")
    for regime, colour in REGIMES.items():
        pts = [(r["preload_N"], r["energy_density_m2"]) for r in rows if r["regime"] == regime]
        if pts:
            ax.plot(*zip(*pts), "o", color=colour, label=regime)
    mixed = [(r["preload_N"], r["energy_density_m2"]) for r in rows
             if r["regime"] not in REGIMES and r["regime"] not in STOPPED]
    if mixed:
        ax.plot(*zip(*mixed), "x", color="k", label="mixed regimes")
    finite = [(x, y) for x, y in zip(p, e) if math.isfinite(y)]
    if finite:
        best = min(finite, key=lambda xy: xy[1])
        ax.plot([best[0]], [best[1]], "*", ms=14, color="k", label=f"optimum N0 = {best[0]:.2f} N")
    if any(y > 0 for y in e):
        ax.set_yscale("log")
    ax.set_xlabel("preload N0 [N]")
    ax.set_ylabel("normalised energy density E [m^2]")
    ax.set_title("Preload sweep (paper Fig. 20) with regime map - Python module")
    ax.legend()
    fig.tight_layout()
    fig.savefig(png, dpi=110)
    plt.close(fig)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--lo", type=float, default=0.5, help="lowest preload [N] (default 0.5)")
    ap.add_argument("--hi", type=float, default=40.0, help="highest preload [N] (default 40)")
    ap.add_argument("--count", type=int, default=32, help="preloads, log-spaced (default 32)")
    ap.add_argument("--duration", type=float, default=20.0, help="simulated time per run [s] (default 20)")
    ap.add_argument("--threads", type=int, default=os.cpu_count(), help="worker threads (default: all cores)")
    ap.add_argument("--out", default="out", help="output folder (default out)")
    args = ap.parse_args()
    preloads = list(args.lo * (args.hi / args.lo) ** np.linspace(0.0, 1.0, args.count))
    os.makedirs(args.out, exist_ok=True)
    rows = [None] * len(preloads)
    with concurrent.futures.ThreadPoolExecutor(max_workers=args.threads) as pool:
        futures = {pool.submit(sweep_point, p, args.duration): k for k, p in enumerate(preloads)}
        for done, future in enumerate(concurrent.futures.as_completed(futures), 1):
            k = futures[future]
            rows[k] = future.result()
            print(f"\rsweep: {done}/{len(preloads)} preloads done (last N0 = {preloads[k]:.2f} N: "
                  f"{rows[k]['regime']})        ", end="", flush=True)
    print()
    path = os.path.join(args.out, "sweep_python.csv")
    with open(path, "w", newline="") as fh:
        w = csv.DictWriter(fh, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)
    finite = [r for r in rows if math.isfinite(r["energy_density_m2"])]
    if finite:
        best = min(finite, key=lambda r: r["energy_density_m2"])
        print(f"sweep optimum: N0 = {best['preload_N']:.2f} N, E = {best['energy_density_m2']:.4e} m^2 "
              f"({best['regime']})")
    png = os.path.join(args.out, "sweep_python.png")
    plot(rows, png)
    print(f"rows in {path}, plot in {png}")


if __name__ == "__main__":
    main()
