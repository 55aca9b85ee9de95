#!/usr/bin/env python3
"""Log-log work-precision plots of work_precision.csv (error against the reference vs CPU time).

Usage: /usr/bin/python3 benchmarks/work_precision/plot_work_precision.py OUT_DIR
Writes OUT_DIR/work_precision_tip.png (tip error, one panel per scene) and
OUT_DIR/work_precision_switch_force.png (switch-time and contact-force errors).
"""
import csv
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

STYLE = {
    "rk4+bisection": ("tab:red", "o", "-"),
    "rk4+root": ("tab:orange", "s", "--"),
    "dopri5+root": ("tab:blue", "o", "-"),
    "dopri5+bisection": ("tab:cyan", "s", "--"),
    "rosenbrock23+root": ("tab:green", "^", "-"),
    "regularised dopri5 1e-8": ("tab:purple", "v", ":"),
    "regularised rosenbrock23 1e-5": ("tab:pink", "v", ":"),
    "dopri5+root 3 modes": ("tab:olive", "D", "-."),
    "dopri5+root 4 modes": ("tab:brown", "D", "-."),
    "rk4+root 2 modes": ("gold", "P", ":"),
    "rk4+root 3 modes": ("tab:gray", "P", ":"),
    "rk4+root 4 modes": ("black", "P", ":"),
}


def value(row, key):
    try:
        v = float(row[key])
    except ValueError:
        return math.nan
    return v


def load(path):
    with open(path) as f:
        return list(csv.DictReader(f))


def panel(ax, rows, key, title, floor):
    families = {}
    for r in rows:
        if r["family"] == "reference" or r["model_variant"] == "1":
            continue
        families.setdefault(r["family"], []).append(r)
    for fam, rs in families.items():
        pts = sorted((value(r, "cpu_s"), value(r, key)) for r in rs)
        pts = [(c, max(e, floor)) for c, e in pts if math.isfinite(c) and math.isfinite(e)]
        if not pts:
            continue
        color, marker, ls = STYLE.get(fam, ("gray", "x", "-"))
        ax.plot([p[0] for p in pts], [p[1] for p in pts], ls, color=color, marker=marker, ms=4, lw=1, label=fam)
    for r in rows:
        if r["family"] == "rk4+bisection" and abs(value(r, "value") - 1e-4) < 1e-12:
            c, e = value(r, "cpu_s"), value(r, key)
            if math.isfinite(c) and math.isfinite(e):
                ax.plot([c], [max(e, floor)], "*", color="k", ms=12, zorder=5, label="paper: RK4 dt=1e-4 + bisection")
    for r in rows:
        if r["model_variant"] != "1":
            continue
        c, e = value(r, "cpu_s"), value(r, key)
        if math.isfinite(c) and math.isfinite(e):
            ax.plot([c], [max(e, floor)], "x", color="0.4", ms=5)
            ax.annotate(r["setting"].replace("blade=", "b").replace(",platform=", "/p"), (c, max(e, floor)),
                        fontsize=5, color="0.35")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_title(title, fontsize=9)
    ax.grid(True, which="both", lw=0.3)


def main(out):
    rows = load(os.path.join(out, "work_precision.csv"))
    scenes = []
    for r in rows:
        if r["scene"] not in scenes:
            scenes.append(r["scene"])
    regime = {r["scene"]: r["regime"] for r in rows}

    fig, axes = plt.subplots(2, 2, figsize=(12, 9))
    for ax, sc in zip(axes.flat, scenes):
        panel(ax, [r for r in rows if r["scene"] == sc], "tip_max_rel", f"{sc} ({regime[sc]})", 1e-12)
        ax.set_xlabel("CPU time [s]")
        ax.set_ylabel("max tip error / tip amplitude")
        for lvl in (1e-2, 1e-3, 1e-4):
            ax.axhline(lvl, color="0.7", lw=0.6, ls=":")
    handles, labels = [], []
    for ax in axes.flat:
        for h, lab in zip(*ax.get_legend_handles_labels()):
            if lab not in labels:
                handles.append(h)
                labels.append(lab)
    fig.legend(handles, labels, loc="lower center", ncol=4, fontsize=8)
    fig.suptitle("Work-precision: tip displacement error vs CPU time (grey x: model variants at rtol 1e-10)")
    fig.tight_layout(rect=(0, 0.08, 1, 0.97))
    fig.savefig(os.path.join(out, "work_precision_tip.png"), dpi=110)

    fig, axes = plt.subplots(2, len(scenes), figsize=(4 * len(scenes), 7.5))
    for k, sc in enumerate(scenes):
        rs = [r for r in rows if r["scene"] == sc]
        panel(axes[0][k], rs, "switch_max_s", f"{sc}: switch-time error [s]", 1e-14)
        panel(axes[1][k], rs, "force_max_rel", f"{sc}: contact-force error / max N", 1e-12)
        axes[1][k].set_xlabel("CPU time [s]")
    fig.legend(handles, labels, loc="lower center", ncol=4, fontsize=8)
    fig.tight_layout(rect=(0, 0.08, 1, 1))
    fig.savefig(os.path.join(out, "work_precision_switch_force.png"), dpi=100)
    write_speedups(rows, scenes, os.path.join(out, "speedup.md"))
    print(f"plot_work_precision.py: wrote PNGs and speedup.md in {out}")


def write_speedups(rows, scenes, path):
    """Speed-up over RK4 + bisection at equal tip accuracy, down to 1e-8 (same run's CSV)."""
    lines = ["| scene | target | fastest setting | CPU [s] | cheapest RK4+bisection | CPU [s] | speed-up |",
             "|---|---|---|---|---|---|---|"]
    for sc in scenes:
        rs = [r for r in rows if r["scene"] == sc and r["family"] != "reference" and r["model_variant"] == "0"
              and math.isfinite(value(r, "tip_max_rel")) and math.isfinite(value(r, "cpu_s"))]
        for target in (1e-2, 1e-3, 1e-4, 1e-6, 1e-8):
            ok = [r for r in rs if value(r, "tip_max_rel") <= target]
            rk = [r for r in ok if r["family"] == "rk4+bisection"]
            if not ok:
                lines.append(f"| {sc} | {target:g} | none | | | | |")
                continue
            best = min(ok, key=lambda r: value(r, "cpu_s"))
            cell = f"| {sc} | {target:g} | {best['family']}, {best['setting']} | {value(best, 'cpu_s'):.3g} | "
            if rk:
                ref = min(rk, key=lambda r: value(r, "cpu_s"))
                cell += (f"{ref['setting']} | {value(ref, 'cpu_s'):.3g} | "
                         f"{value(ref, 'cpu_s') / value(best, 'cpu_s'):.3g}x |")
            else:
                finest = max((r for r in rs if r["family"] == "rk4+bisection"), key=lambda r: value(r, "cpu_s"))
                cell += (f"not reached (finest {finest['setting']}) | > {value(finest, 'cpu_s'):.3g} | "
                         f"> {value(finest, 'cpu_s') / value(best, 'cpu_s'):.3g}x |")
            lines.append(cell)
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n")


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else ".")
