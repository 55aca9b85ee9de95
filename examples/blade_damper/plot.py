#!/usr/bin/env python3
"""PNG figures of the blade_damper results, in the style of the paper's Figs 8-20.

Usage: /usr/bin/python3 examples/blade_damper/plot.py OUT_DIR
Reads history_N0_*.csv, spectra_N0_*.csv, tip_N0_*.csv, sweep.csv and sweep.json written by
blade_damper, and the same records of each regime's representative run in OUT_DIR/regime_*/;
with compare.csv (blade_damper --compare) also the work-precision figure compare.png; with frc.csv
(blade_damper --frc) the frequency-response curves frc.png; with optimal_peaks.csv
(blade_damper --optimise-preload) optimal.png.
Regime names come from sweep.json (the example's one rule, blade_regime.hpp), not from here.
"""
import csv
import glob
import json
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from plot_optimal import plot_optimal  # noqa: E402  (blade_damper --optimise-preload)


def read_csv(path):
    with open(path, newline="") as fh:
        rows = list(csv.DictReader(fh))
    if not rows:
        return {}
    cols = {k: [] for k in rows[0]}
    for r in rows:
        for k, v in r.items():
            try:
                cols[k].append(float(v))
            except ValueError:
                cols[k].append(v)
    return cols


def spectrum_axis(ax, spec, key, label, fmax=400.0):
    f = [x for x in spec["frequency_hz"] if x <= fmax]
    ax.plot(f, spec[key][: len(f)], lw=0.8)
    ax.set_xlabel("frequency [Hz]")
    ax.set_ylabel(label)


def plot_run(out, tag, title=None):
    hist = read_csv(os.path.join(out, f"history_{tag}.csv"))
    if not hist:
        return []
    spec_path = os.path.join(out, f"spectra_{tag}.csv")
    spec = read_csv(spec_path) if os.path.exists(spec_path) else None
    t = hist["t"]
    made = []
    what = title or tag.replace("_", " = ") + " N"

    # Fig 8/12/16: tip response and its spectrum.
    fig, ax = plt.subplots(1, 2, figsize=(10, 3.5))
    ax[0].plot(t, [1e3 * v for v in hist["tip"]], lw=0.8)
    ax[0].set_xlabel("t [s]")
    ax[0].set_ylabel("blade tip x [mm]")
    if spec:
        spectrum_axis(ax[1], spec, "tip", "tip amplitude [m]")
    fig.suptitle(f"Blade tip, {what}")
    fig.tight_layout()
    made.append(os.path.join(out, f"tip_{tag}.png"))
    fig.savefig(made[-1], dpi=110)
    plt.close(fig)

    # Fig 9/13/17: normal and friction forces with spectra.
    fig, ax = plt.subplots(2, 4, figsize=(14, 6))
    for i in (1, 2):
        ax[0, i - 1].plot(t, hist[f"N{i}"], lw=0.8)
        ax[0, i - 1].set_ylabel(f"N{i} [N]")
        ax[1, i - 1].plot(t, hist[f"f{i}"], lw=0.8)
        ax[1, i - 1].set_ylabel(f"f{i} [N]")
        for a in (ax[0, i - 1], ax[1, i - 1]):
            a.set_xlabel("t [s]")
        if spec:
            spectrum_axis(ax[0, i + 1], spec, f"N{i}", f"|N{i}| [N]")
            spectrum_axis(ax[1, i + 1], spec, f"f{i}", f"|f{i}| [N]")
    fig.suptitle(f"Contact forces, {what}")
    fig.tight_layout()
    made.append(os.path.join(out, f"forces_{tag}.png"))
    fig.savefig(made[-1], dpi=110)
    plt.close(fig)

    # Fig 10/14/18: damper motion (x along the platform, y with it) and spectra.
    fig, ax = plt.subplots(2, 4, figsize=(14, 6))
    for i in (1, 2):
        ax[0, i - 1].plot(t, [1e6 * v for v in hist[f"x{i}"]], lw=0.8)
        ax[0, i - 1].set_ylabel(f"x{i} [um]")
        ax[1, i - 1].plot(t, [1e6 * v for v in hist[f"y{i}"]], lw=0.8)
        ax[1, i - 1].set_ylabel(f"y{i} [um]")
        for a in (ax[0, i - 1], ax[1, i - 1]):
            a.set_xlabel("t [s]")
        if spec:
            spectrum_axis(ax[0, i + 1], spec, f"x{i}", f"|x{i}| [m]")
            spectrum_axis(ax[1, i + 1], spec, f"y{i}", f"|y{i}| [m]")
    fig.suptitle(f"Damper motion, {what}")
    fig.tight_layout()
    made.append(os.path.join(out, f"dampers_{tag}.png"))
    fig.savefig(made[-1], dpi=110)
    plt.close(fig)

    # Fig 11/15/19: phase planes, relative velocity vs damper displacement.
    fig, ax = plt.subplots(1, 2, figsize=(10, 4))
    fig.suptitle(f"Phase planes, {what}")
    for i in (1, 2):
        ax[i - 1].plot([1e6 * v for v in hist[f"x{i}"]], [1e3 * v for v in hist[f"V{i}"]], lw=0.6)
        ax[i - 1].set_xlabel(f"x{i} [um]")
        ax[i - 1].set_ylabel(f"sliding velocity V{i} [mm/s]")
        ax[i - 1].set_title("left damper" if i == 1 else "right damper")
    fig.tight_layout()
    made.append(os.path.join(out, f"phase_{tag}.png"))
    fig.savefig(made[-1], dpi=110)
    plt.close(fig)
    return made


def read_sweep_json(out):
    path = os.path.join(out, "sweep.json")
    if not os.path.exists(path):
        return {}
    with open(path) as fh:
        return json.load(fh)


def plot_sweep(out, info):
    path = os.path.join(out, "sweep.csv")
    if not os.path.exists(path):
        return []
    s = read_csv(path)
    names = [r["name"] for r in info.get("regimes", [])]
    colours = dict(zip(names, ["tab:red", "tab:orange", "tab:blue"]))
    colours["intermittent contact"] = "tab:purple"  # dampers leaving the platform (--restitution)
    fig, ax = plt.subplots(figsize=(7, 4.5))
    ax.plot(s["preload_N"], s["energy_density_m2"], "-", color="0.6", lw=1)
    stopped = [p for p, r in zip(s["preload_N"], s["regime"]) if r in ("lift-off", "left platform", "run stopped")]
    for p in stopped:
        ax.axvline(p, color="tab:gray", alpha=0.3, lw=6)
    if stopped:
        ax.plot([], [], color="tab:gray", alpha=0.3, lw=6, label="run stopped (lift-off / left platform)")
    for regime, colour in colours.items():
        xs = [p for p, r in zip(s["preload_N"], s["regime"]) if r == regime]
        ys = [e for e, r in zip(s["energy_density_m2"], s["regime"]) if r == regime]
        if xs:
            ax.plot(xs, ys, "o", color=colour, label=regime)
    others = [(p, e) for p, e, r in zip(s["preload_N"], s["energy_density_m2"], s["regime"])
              if r not in colours and p not in stopped]
    if others:
        ax.plot([p for p, _ in others], [e for _, e in others], "x", color="k", label="mixed regimes")
    reps = info.get("representatives", [])
    energy = dict(zip(s["preload_N"], s["energy_density_m2"]))
    for k, rep in enumerate(reps):
        e = energy.get(rep["preload_N"])
        if e is not None:
            ax.plot([rep["preload_N"]], [e], "s", ms=12, mfc="none", color=colours.get(rep["regime"], "k"),
                    label="representatives (regime_*/ figures)" if k == 0 else None)
    ax.set_xlabel("preload N0 [N]")
    ax.set_ylabel("normalised energy density E [m^2]")
    if any(e > 0 for e in s["energy_density_m2"]):  # NaN (no E: every run stopped) compares False
        ax.set_yscale("log")
    ax.legend()
    ax.set_title("Preload sweep (paper Fig. 20) with regime map")
    fig.tight_layout()
    png = os.path.join(out, "sweep.png")
    fig.savefig(png, dpi=110)
    plt.close(fig)
    return [png]


def plot_compare(out):
    """compare.csv (rows: reference, its validation, then the variants): tip error against CPU."""
    path = os.path.join(out, "compare.csv")
    if not os.path.exists(path):
        return []
    with open(path, newline="") as fh:
        rows = list(csv.DictReader(fh))
    if len(rows) < 2:
        return []
    floor = float(rows[1]["output_error_max"])
    fig, ax = plt.subplots(figsize=(7.5, 5))
    for r in rows[2:]:
        cpu, err = float(r["cpu_seconds"]), float(r["output_error_max"])
        if r["status"] != "success" or not (err > 0) or not (cpu > 0):
            continue
        ax.loglog(cpu, err, "o")
        ax.annotate(r["name"], (cpu, err), textcoords="offset points", xytext=(4, 3), fontsize=7)
    if floor > 0:
        ax.axhline(floor, color="gray", ls="--", lw=0.8, label="reference's own error (validation)")
        ax.legend(fontsize=8)
    ax.set_xlabel("CPU time [s] (median of repeats)")
    ax.set_ylabel("blade tip error, max / max |tip| of the reference")
    ax.set_title(f"Speed/accuracy trade against {rows[0]['name']}")
    ax.grid(True, which="both", lw=0.3)
    fig.tight_layout()
    png = os.path.join(out, "compare.png")
    fig.savefig(png, dpi=110)
    plt.close(fig)
    return [png]


# frc.csv's kind column: which branch a segment is on
KIND_LABEL = {"period_1": "segment", "restart": "restart's segment", "subharmonic": "subharmonic segment",
              "period_doubled": "period-doubled branch"}


def plot_frc(out):
    """frc.csv and frc_linear.csv (blade_damper --frc): tip amplitude against excitation frequency per
    preload, solid where stable and dashed where unstable, markers coloured by regime, every branch
    found (period 1, subharmonic restarts, period-doubled branches: line width by kind), with the
    linear all-stuck and frictionless (mu = 0) curves at each preload (thin, same colour) and, with
    frc_sweep.csv (--frc-sweep), the responses of the transient sweeps up and down."""
    path = os.path.join(out, "frc.csv")
    if not os.path.exists(path):
        return []
    with open(path, newline="") as fh:
        rows = list(csv.DictReader(fh))
    lin = read_csv(os.path.join(out, "frc_linear.csv"))
    fig, ax = plt.subplots(figsize=(8, 5.5))
    regimes = sorted({r["regime"] for r in rows})
    colour = {g: plt.cm.tab10(k) for k, g in enumerate(regimes)}
    for k, n0 in enumerate(sorted({float(r["preload_N"]) for r in rows})):
        pts = [r for r in rows if float(r["preload_N"]) == n0]
        f = [float(r["frequency_hz"]) for r in pts]
        a = [float(r["tip_amplitude_m"]) for r in pts]
        stable = [r["stable"] == "1" for r in pts]
        # segment 0: the branch; k > 0: a part's own branch that the branch never reached
        # (--frc-parts), drawn apart: no line joins two segments
        segment = [int(r.get("segment", "0") or 0) for r in pts]
        line = plt.cm.Set1(k)
        if lin:  # the linear limits at this preload (the damper mass depends on N0)
            idx = [i for i, v in enumerate(lin["preload_N"]) if v == n0]
            fl = [lin["frequency_hz"][i] for i in idx]
            ax.semilogy(fl, [lin["tip_all_stuck_m"][i] for i in idx], color=line, lw=0.7, alpha=0.6,
                        label=f"all stuck, linear (N0 = {n0:g} N)")
            ax.semilogy(fl, [lin["tip_frictionless_m"][i] for i in idx], color=line, lw=0.7, ls=":", alpha=0.6,
                        label=f"frictionless mu = 0, linear (N0 = {n0:g} N)")
        for i in range(len(pts) - 1):  # segment style from its two ends: dashed unless both stable
            if segment[i] != segment[i + 1]:
                continue
            label = None
            kind = pts[i].get("kind", "period_1") or "period_1"
            if i == 0:
                label = f"N0 = {n0:g} N"
            elif segment[i] > 0 and segment[i - 1] != segment[i]:
                what = KIND_LABEL.get(kind, "separate segment")
                label = f"N0 = {n0:g} N, {what} (period {pts[i].get('period_T', '1')} T) from {f[i]:.2f} Hz"
            # period-doubled branches (born at a flip) thicker, restarts' segments thinner
            width = {"period_doubled": 2.2, "subharmonic": 1.8}.get(kind, 1.4 if segment[i] == 0 else 1.0)
            ax.semilogy(f[i:i + 2], a[i:i + 2], color=line, lw=width,
                        ls="-" if stable[i] and stable[i + 1] else "--", label=label)
        ax.scatter(f, a, s=9, zorder=3, c=[colour[r["regime"]] for r in pts])
        # subharmonic orbits (period k T, k > 1, found by a restart): ringed
        sub = [i for i, r in enumerate(pts) if int(r.get("period_T", "1") or 1) > 1]
        if sub:
            ks = sorted({int(pts[i]["period_T"]) for i in sub})
            ax.scatter([f[i] for i in sub], [a[i] for i in sub], s=30, zorder=4, facecolors="none",
                       edgecolors=line, label=f"N0 = {n0:g} N, subharmonic orbits (period "
                                              + ", ".join(f"{k} T" for k in ks) + ")")
    # the restarts' frequencies without a periodic response: tip amplitude in each recorded period
    poinc = os.path.join(out, "frc_poincare.csv")
    if os.path.exists(poinc):
        with open(poinc, newline="") as fh:
            prow = list(csv.DictReader(fh))
        if prow:
            ax.scatter([float(r["frequency_hz"]) for r in prow], [float(r["tip_amplitude_m"]) for r in prow],
                       s=4, color="0.4", zorder=2,
                       label="not periodic (<= 8 T): tip amplitude per period of a transient")
    # the transients swept up and down in frequency (--frc-sweep): what the structure reaches,
    # triangles up / down, the response's period k written next to a subharmonic one, x where
    # no period <= 8 T was found
    sweep = os.path.join(out, "frc_sweep.csv")
    if os.path.exists(sweep):
        with open(sweep, newline="") as fh:
            srow = [r for r in csv.DictReader(fh) if r["tip_amplitude_m"] not in ("", "nan")]
        preloads = sorted({float(r["preload_N"]) for r in rows})
        for r_dir, marker in (("up", "^"), ("down", "v")):
            for n0 in sorted({float(r["preload_N"]) for r in srow}):
                sel = [r for r in srow if r["direction"] == r_dir and float(r["preload_N"]) == n0]
                if not sel:
                    continue
                k = preloads.index(n0) if n0 in preloads else 0
                periodic = [r for r in sel if int(r["period_T"]) > 0]
                ax.scatter([float(r["frequency_hz"]) for r in periodic], [float(r["tip_amplitude_m"]) for r in periodic],
                           s=22, marker=marker, facecolors="none", edgecolors=plt.cm.Set1(k), zorder=5,
                           label=f"N0 = {n0:g} N, transients swept {r_dir}")
                none = [r for r in sel if int(r["period_T"]) == 0]
                if none:
                    ax.scatter([float(r["frequency_hz"]) for r in none], [float(r["tip_amplitude_m"]) for r in none],
                               s=22, marker="x", color=plt.cm.Set1(k), zorder=5)
                for r in sel:
                    if int(r["period_T"]) > 1 or r.get("asymmetric") == "1":
                        text = (r["period_T"] + "T" if int(r["period_T"]) > 1 else "") + \
                               (" asym" if r.get("asymmetric") == "1" else "")
                        ax.annotate(text, (float(r["frequency_hz"]), float(r["tip_amplitude_m"])), fontsize=6,
                                    xytext=(3, 3 if r_dir == "up" else -8), textcoords="offset points",
                                    color=plt.cm.Set1(k))
    for g in regimes:
        ax.scatter([], [], s=12, color=colour[g], label=f"regime: {g}")
    ax.set_xlabel("excitation frequency [Hz]")
    ax.set_ylabel("tip amplitude, half peak-to-peak [m]")
    ax.set_title("Blade tip frequency response (periodic orbits; solid stable, dashed unstable)")
    ax.grid(True, which="both", lw=0.3)
    ax.legend(fontsize=7)
    fig.tight_layout()
    png = os.path.join(out, "frc.png")
    fig.savefig(png, dpi=110)
    plt.close(fig)
    return [png]


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else "out"
    made = []
    for path in sorted(glob.glob(os.path.join(out, "history_N0_*.csv"))):
        tag = os.path.basename(path)[len("history_"):-len(".csv")]
        made += plot_run(out, tag)
    info = read_sweep_json(out)
    for rep in info.get("representatives", []):
        folder = os.path.join(out, rep["folder"])
        for path in sorted(glob.glob(os.path.join(folder, "history_N0_*.csv"))):
            tag = os.path.basename(path)[len("history_"):-len(".csv")]
            made += plot_run(folder, tag, f"{rep['regime']} (N0 = {rep['preload_N']:.3g} N)")
    made += plot_sweep(out, info)
    made += plot_compare(out)
    made += plot_frc(out)
    made += plot_optimal(out)
    print(f"plot.py: wrote {len(made)} PNG figures in {out}/ and its regime_*/ folders")


if __name__ == "__main__":
    main()
