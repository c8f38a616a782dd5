#!/usr/bin/env python3
"""Prints the README's cost-per-cycle tables from the last `cargo bench -p profilegen-benches --bench cycle_cost` run.

    cargo bench -p profilegen-benches --bench cycle_cost -- --warm-up-time 1 --measurement-time 3
    python3 tools/bench_table.py            # reads target/criterion

Each figure is criterion's median for one window divided by the window's cycles (or steps): the
windows hold only cycles of one phase (benches/cycle_cost.rs). Ratios are to the peers' per-step
medians in the same phase, from the same run. Nothing here asserts a time.
"""
import json
import os
import sys

ROOT = sys.argv[1] if len(sys.argv) > 1 else "target/criterion"
PHASES = ("accelerate", "cruise", "decelerate")


def results() -> dict[str, float]:
    """Median nanoseconds per element (or per iteration, without a throughput), by full id."""
    found = {}
    for directory, _, files in os.walk(ROOT):
        if os.path.basename(directory) != "new" or "benchmark.json" not in files:
            continue
        with open(os.path.join(directory, "benchmark.json")) as f:
            benchmark = json.load(f)
        with open(os.path.join(directory, "estimates.json")) as f:
            median = json.load(f)["median"]["point_estimate"]
        elements = (benchmark.get("throughput") or {}).get("Elements", 1)
        found[benchmark["full_id"]] = median / elements
    return found


def main() -> int:
    r = results()

    def get(key: str) -> float | None:
        return r.get(key)

    def fmt(x: float | None) -> str:
        return "–" if x is None else (f"{x:.2f}" if x < 10 else f"{x:.1f}" if x < 100 else f"{x:,.0f}")

    peer = {name: [get(f"peers: per step/{name}/{p}") for p in PHASES] for name in ("stepgen", "ramp-maker")}

    def ratio(x: float | None, y: float | None) -> str:
        return "–" if x is None or y is None else f"{x / y:.2f}"

    print("| per cycle (per step for the peers): accelerate / cruise / decelerate | ns | × stepgen | × ramp-maker |")
    print("|---|---:|---:|---:|")
    rows = [
        ("profilegen `VelocityContouring::step`", "cost per cycle/velocity"),
        ("profilegen `Trapezoidal::step`", "cost per cycle/trapezoidal"),
        ("profilegen `SCurve::step`", "cost per cycle/scurve"),
        ("profilegen `Mcx514Trapezoidal::step` (reference 003's line)", "cost per cycle/mcx514"),
        ("profilegen `Mcx514SCurve::step` (the same, JK = DJ = 650,000 pps/s²)", "cost per cycle/mcx514_scurve"),
        ("profilegen `ElectronicGear::follow` (engaged at 1.5)", "cost per cycle/gearing"),
        ("stepgen `Stepgen::next` (per step, the peers' move)", "peers: per step/stepgen"),
        ("ramp-maker `Trapezoidal::next_delay` (per step, U32F32)", "peers: per step/ramp-maker"),
    ]
    for label, prefix in rows:
        values = [get(f"{prefix}/{p}") for p in PHASES]
        if all(v is None for v in values):
            continue
        cells = [" / ".join(fmt(v) for v in values)]
        for name in ("stepgen", "ramp-maker"):
            cells.append(" / ".join(ratio(v, w) for v, w in zip(values, peer[name])))
        print(f"| {label} | " + " | ".join(cells) + " |")
    for label, key in (
        ("profilegen `MicrostepTable::outputs` (3-phase, scaled)", "microstep lookup/3-phase, N=256, scaled"),
        ("rsruckig `Ruckig::update` (online, per cycle)", "peers: per cycle/rsruckig/update"),
        ("s_curve evaluate (closed-form position at t, f64)", "peers: per cycle/s_curve/evaluate"),
    ):
        v = get(key)
        if v is not None:
            print(f"| {label} | {fmt(v)} | – | – |")
    print()
    print("| set up the bench move | ns |")
    print("|---|---:|")
    for label, key in (
        ("profilegen `SCurve::new` (plan, exact)", "set up a move/scurve/plan"),
        ("profilegen `Trapezoidal::new` (plan)", "set up a move/trapezoidal/plan"),
        ("rsruckig `Ruckig::calculate`", "peers: plan/rsruckig/calculate"),
        ("s_curve `s_curve_generator`", "peers: plan/s_curve/plan"),
    ):
        v = get(key)
        if v is not None:
            print(f"| {label} | {fmt(v)} |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
