#!/usr/bin/env python3
"""PNG figures of the bladed_disk results.

Usage: /usr/bin/python3 examples/bladed_disk/plot.py OUT_DIR
Reads frc.csv, linear.csv and mistuning.csv written by bladed_disk and writes OUT_DIR/frc.png
(the engine-order frequency-response curves at each preload, stable and unstable travelling
waves, with the stuck and damper-free linear curves) and OUT_DIR/mistuning.png (the histogram of
the amplification factor with Whitehead's bound).
"""
import csv
import json
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def read(path):
    with open(path, newline="") as fh:
        return list(csv.DictReader(fh))


def main(out):
    linear = read(os.path.join(out, "linear.csv"))
    frc = read(os.path.join(out, "frc.csv"))
    fig, ax = plt.subplots(figsize=(7, 4.5))
    w = [float(r["omega"]) for r in linear]
    ax.semilogy(w, [float(r["free_tip"]) for r in linear], "k--", lw=1, label="no dampers (linear)")
    ax.semilogy(w, [float(r["stuck_tip"]) for r in linear], "k:", lw=1, label="dampers stuck (linear)")
    for preload in sorted({float(r["preload"]) for r in frc}):
        rows = [r for r in frc if float(r["preload"]) == preload and r["ok"] == "1"]
        line = ax.semilogy([float(r["omega"]) for r in rows], [float(r["tip"]) for r in rows], "-", lw=1.2,
                           label=f"N0 = {preload:g} N")[0]
        unstable = [r for r in rows if r["stable"] != "1"]
        if unstable:
            ax.plot([float(r["omega"]) for r in unstable], [float(r["tip"]) for r in unstable], "x",
                    color=line.get_color(), ms=5)
    ax.set_xlabel("excitation frequency Omega [rad/s]")
    ax.set_ylabel("blade tip amplitude [m]")
    ax.set_title("24 blades, EO 3: travelling waves (x: unstable)")
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "frc.png"), dpi=120)

    rows = [r for r in read(os.path.join(out, "mistuning.csv")) if r["amplification"] not in ("", "nan")]
    amp = [float(r["amplification"]) for r in rows]
    summary = json.load(open(os.path.join(out, "summary.json")))
    fig, ax = plt.subplots(figsize=(6, 4))
    ax.hist(amp, bins=max(5, int(math.sqrt(len(amp)))), color="0.6", edgecolor="k")
    ax.axvline(summary["mistuning"]["whitehead_bound"], color="r", ls="--", label="Whitehead's bound")
    ax.set_xlabel("amplification factor (largest blade peak / tuned peak)")
    ax.set_ylabel("samples")
    ax.set_title(f"mistuning, sigma = {summary['mistuning']['sigma']:g}, dampers stuck")
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "mistuning.png"), dpi=120)
    print("wrote", os.path.join(out, "frc.png"), "and", os.path.join(out, "mistuning.png"))


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "out_disk")
