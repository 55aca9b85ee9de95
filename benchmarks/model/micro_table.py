#!/usr/bin/env python3
"""Markdown tables of model_benchmark's Google Benchmark JSON (one run; the medians when it was
run with --benchmark_repetitions): the right-hand side of FrictionDampedSystem against the bare
modal right-hand side (the paired benchmark's ratios, and those of the separate benchmarks of the
same run), and the step / event / 20 s rows with their
counters.

Usage: /usr/bin/python3 benchmarks/model/micro_table.py model_benchmark.json
"""
import json
import re
import sys

SCALE = {"ns": 1.0, "us": 1e3, "ms": 1e6, "s": 1e9}


def main(path):
    data = json.load(open(path))
    # With --benchmark_repetitions the medians (aggregate rows) are used, else the single runs.
    medians = {b["run_name"]: b for b in data["benchmarks"]
               if b.get("run_type") == "aggregate" and b.get("aggregate_name") == "median"}
    rows = medians or {b["name"]: b for b in data["benchmarks"] if b.get("run_type", "iteration") == "iteration"}
    # (benchmarks with a fixed iteration count carry it in their name: BM_RhsPaired/6/2/0/iterations:401)
    rows = {re.sub(r"/iterations:\d+$", "", name): b for name, b in rows.items()}

    def ns(b):
        return b["cpu_time"] * SCALE[b.get("time_unit", "ns")]

    ctx = data.get("context", {})
    reps = f"medians of {next(iter(medians.values())).get('repetitions', '?')} repetitions" if medians else "single runs"
    print(f"Host: {ctx.get('host_name', '?')}, {ctx.get('num_cpus', '?')} CPUs at "
          f"{ctx.get('mhz_per_cpu', '?')} MHz, build {ctx.get('library_build_type', '?')} benchmark library; "
          f"run {ctx.get('date', '?')}; {reps}\n")
    header = ("| n modes | D dampers | bare RHS [ns] | composed, slipping [ns] | ratio | "
              "composed, stuck [ns] | ratio |\n|---|---|---|---|---|---|---|")

    def paired(name):
        """(bare, composed, ratio) of a BM_RhsPaired row: medians over its pairs of blocks."""
        b = rows.get(name)
        return (b["bare_ns"], b["composed_ns"], b["ratio"]) if b and "ratio" in b else None

    def separate(bare_name, slip_name, stick_name):
        """Bare, slipping, stuck rows of separate benchmarks: ((bare, slip, ratio), (bare, stick, ratio))."""
        bare, slip, stick = rows.get(bare_name), rows.get(slip_name), rows.get(stick_name)
        if not (bare and slip and stick):
            return None
        b = ns(bare)
        return (b, ns(slip), ns(slip) / b), (b, ns(stick), ns(stick) / b)

    def table(title, cases):
        lines = []
        for n, d, slip, stick in cases:
            if slip and stick:
                # (each of the two columns has its own bare time; the slipping pair's is shown)
                lines.append(f"| {n} | {d} | {slip[0]:.0f} | {slip[1]:.0f} | {slip[2]:.2f} | "
                             f"{stick[1]:.0f} | {stick[2]:.2f} |")
        if lines:
            print(f"{title}\n\n{header}")
            print("\n".join(lines))
            print()

    table("Paired (BM_RhsPaired: bare and composed timed in alternating blocks; medians of the "
          "per-pair times and ratios):",
          [(n, d, paired(f"BM_RhsPaired/{n}/{d}/0"), paired(f"BM_RhsPaired/{n}/{d}/1"))
           for n in (6, 24, 96) for d in (2, 8, 32)])
    table("Paired, with the number of modes fixed at compile time (Modes = 6) in both:",
          [("6 (fixed)", d, paired(f"BM_RhsPairedFixed6/{d}/0"), paired(f"BM_RhsPairedFixed6/{d}/1"))
           for d in (2, 8, 32)])
    sep = [(n, d) + (separate(f"BM_RhsBare/{n}/{d}", f"BM_RhsComposed/{n}/{d}/0", f"BM_RhsComposed/{n}/{d}/1") or (None, None))
           for n in (6, 24, 96) for d in (2, 8, 32)]
    table("Separate benchmarks (BM_RhsBare, BM_RhsComposed: each its own median, one bare time per row):", sep)
    sepf = [("6 (fixed)", d) + (separate(f"BM_RhsBareFixed6/{d}", f"BM_RhsComposedFixed6/{d}/0", f"BM_RhsComposedFixed6/{d}/1") or (None, None))
            for d in (2, 8, 32)]
    table("Separate benchmarks, Modes = 6 fixed in both:", sepf)
    print("| benchmark | CPU time | counters |\n|---|---|---|")
    for name, b in rows.items():
        if name.startswith("BM_Rhs"):
            continue
        counters = ", ".join(f"{k} {v:.6g}" for k, v in b.items()
                             if k in ("rhs_per_step", "rhs", "guards", "events", "steps", "t_end"))
        label = f" ({b['label']})" if b.get("label") else ""
        print(f"| {name}{label} | {b['cpu_time']:.4g} {b.get('time_unit', 'ns')} | {counters} |")


if __name__ == "__main__":
    main(sys.argv[1])
