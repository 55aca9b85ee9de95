"""optimal.png from blade_damper --optimise-preload's files (imported by plot.py): the resonant
tip amplitude A(N0) = max over frequency of the largest stable response's tip amplitude at every
preload the search evaluated (the coarse grid and the golden sections), the optimum N0* marked and
the preloads whose peak is a subharmonic response ringed; below, the peak frequency at each N0."""
import csv
import json
import os

import matplotlib.pyplot as plt


def plot_optimal(out):
    path = os.path.join(out, "optimal_peaks.csv")
    if not os.path.exists(path):
        return []
    with open(path, newline="") as fh:
        rows = sorted((float(r["preload_N"]), float(r["peak_frequency_hz"]), float(r["resonant_tip_amplitude_m"]),
                       int(r.get("peak_period_T", "1") or 1)) for r in csv.DictReader(fh))
    with open(os.path.join(out, "optimal.json")) as fh:
        best = json.load(fh)
    fig, (ax, bx) = plt.subplots(2, 1, figsize=(7, 6.5), sharex=True, gridspec_kw={"height_ratios": [2, 1]})
    n0 = [r[0] for r in rows]
    ax.loglog(n0, [r[2] for r in rows], "o-", ms=4, lw=1)
    bx.semilogx(n0, [r[1] for r in rows], "o-", ms=4, lw=1)
    # preloads whose peak is not a period-1 response (a subharmonic, or no period <= 8 T): ringed
    sub = [r for r in rows if r[3] != 1]
    if sub:
        ax.scatter([r[0] for r in sub], [r[2] for r in sub], s=60, facecolors="none", edgecolors="C3", zorder=3,
                   label="peak set by a subharmonic / aperiodic response")
        for r in sub:
            ax.annotate(f"{r[3]}T" if r[3] > 0 else "aper.", (r[0], r[2]), fontsize=7, xytext=(4, 4),
                        textcoords="offset points")
    if best.get("ok"):
        ax.plot([best["optimal_preload_N"]], [best["resonant_tip_amplitude_m"]], "r*", ms=14,
                label=f"N0* = {best['optimal_preload_N']:.3g} N, {best['resonant_tip_amplitude_m']:.3e} m "
                      f"at {best['peak_frequency_hz']:.2f} Hz, period {best.get('peak_period_T', 1)} T")
        ax.legend(fontsize=8)
    ax.set_ylabel("resonant tip amplitude [m]\n(max over frequency, half peak-to-peak)")
    ax.set_title("Optimal preload: the largest stable response over frequency")
    bx.set_xlabel("preload N0 [N]")
    bx.set_ylabel("peak frequency [Hz]")
    for a in (ax, bx):
        a.grid(True, which="both", lw=0.3)
    fig.tight_layout()
    png = os.path.join(out, "optimal.png")
    fig.savefig(png, dpi=110)
    plt.close(fig)
    return [png]
