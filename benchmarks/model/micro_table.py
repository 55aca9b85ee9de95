#!/usr/bin/env python3
"""Markdown tables of model_benchmark's Google Benchmark JSON (one run; the medians when it was
run with --benchmark_repetitions): the right-hand side of FrictionDampedSystem against the bare
modal right-hand side (ratio from the same run), and the step / event / 20 s rows with their
counters.

Usage: /usr/bin/python3 benchmarks/model/micro_table.py model_benchmark.json
"""
import json
import sys

SCALE = {"ns": 1.0, "us": 1e3, "ms": 1e6, "s": 1e9}


def main(path):
    data = json.load(open(path))
    # With --benchmark_repetitions the medians (aggregate rows) are used, else the single runs.
    medians = {b["run_name"]: b for b in data["benchmarks"]
               if b.get("run_type") == "aggregate" and b.get("aggregate_name") == "median"}
    rows = medians or {b["name"]: b for b in data["benchmarks"] if b.get("run_type", "iteration") == "iteration"}

    def ns(b):
        return b["cpu_time"] * SCALE[b.get("time_unit", "ns")]

    ctx = data.get("context", {})
    reps = f"medians of {next(iter(medians.values())).get('repetitions', '?')} repetitions" if medians else "single runs"
    print(f"Host: {ctx.get('host_name', '?')}, {ctx.get('num_cpus', '?')} CPUs at "
          f"{ctx.get('mhz_per_cpu', '?')} MHz, build {ctx.get('library_build_type', '?')} benchmark library; "
          f"run {ctx.get('date', '?')}; {reps}\n")
    print("| n modes | D dampers | bare RHS [ns] | composed, slipping [ns] | ratio | composed, stuck [ns] | ratio |")
    print("|---|---|---|---|---|---|---|")
    for n in (6, 24, 96):
        for d in (2, 8, 32):
            bare = rows.get(f"BM_RhsBare/{n}/{d}")
            slip = rows.get(f"BM_RhsComposed/{n}/{d}/0")
            stick = rows.get(f"BM_RhsComposed/{n}/{d}/1")
            if not (bare and slip and stick):
                continue
            b, s, k = ns(bare), ns(slip), ns(stick)
            print(f"| {n} | {d} | {b:.0f} | {s:.0f} | {s / b:.2f} | {k:.0f} | {k / b:.2f} |")
    fixed = [(d, rows.get(f"BM_RhsBareFixed6/{d}"), rows.get(f"BM_RhsComposedFixed6/{d}/0"),
              rows.get(f"BM_RhsComposedFixed6/{d}/1")) for d in (2, 8, 32)]
    if any(all(r) for _, *r in fixed):
        print("\nWith the number of modes fixed at compile time (Modes = 6) in both:\n")
        print("| n modes | D dampers | bare RHS [ns] | composed, slipping [ns] | ratio | composed, stuck [ns] | ratio |")
        print("|---|---|---|---|---|---|---|")
        for d, bare, slip, stick in fixed:
            if not (bare and slip and stick):
                continue
            b, s, k = ns(bare), ns(slip), ns(stick)
            print(f"| 6 (fixed) | {d} | {b:.0f} | {s:.0f} | {s / b:.2f} | {k:.0f} | {k / b:.2f} |")
    print("\n| benchmark | CPU time | counters |\n|---|---|---|")
    for name, b in rows.items():
        if name.startswith("BM_Rhs"):
            continue
        counters = ", ".join(f"{k} {v:.6g}" for k, v in b.items()
                             if k in ("rhs_per_step", "rhs", "guards", "events", "steps", "t_end"))
        label = f" ({b['label']})" if b.get("label") else ""
        print(f"| {name}{label} | {b['cpu_time']:.4g} {b.get('time_unit', 'ns')} | {counters} |")


if __name__ == "__main__":
    main(sys.argv[1])
