#!/usr/bin/env python3
"""The variant table of docs/convergence.md from the converge CSVs and the timing rounds.

Usage: python3 docs/convergence/table.py docs/convergence docs/convergence/timing.txt

timing.txt holds one line per timing run of 64 spp: "variant render_seconds
cpu_seconds load" (cpu_seconds "-" when not measured). The machine is shared, so
the render cost per spp is the fastest of the interleaved runs (the least
disturbed); the median CPU time per spp is printed beside it as a cross-check.
Each variant's error is fitted as  error(N) = a / N + c  over its checkpoints with
N >= 64 (least squares, weights 1/error^2): a / N is the variance of the N-sample
mean, c the reference's own error, which every measurement against it contains.
The efficiency and the time to a target relMSE then use a and the render cost per
sample per pixel.
"""
import csv
import statistics
import sys
from pathlib import Path

VARIANTS = ["cosine-nee-area", "cosine-nee-solid-angle", "report-nee-area",
            "report-nee-solid-angle", "cosine-no-nee", "report-no-nee"]
TARGET = 0.05


def fit(points):
    """Weighted least squares of y = a x + c (x = 1/N), weights 1/y^2."""
    sw = swx = swy = swxx = swxy = 0.0
    for x, y in points:
        w = 1.0 / (y * y)
        sw += w; swx += w * x; swy += w * y; swxx += w * x * x; swxy += w * x * y
    det = sw * swxx - swx * swx
    a = (sw * swxy - swx * swy) / det
    c = (swxx * swy - swx * swxy) / det
    return a, c


def measured_time_to(rows, target):
    prev = None
    for r in rows:
        if r["rel_mse"] <= target:
            if prev is None:
                return r["seconds"]
            import math
            f = (math.log(target) - math.log(prev["rel_mse"])) / (
                math.log(r["rel_mse"]) - math.log(prev["rel_mse"]))
            return math.exp(math.log(prev["seconds"]) +
                            f * (math.log(r["seconds"]) - math.log(prev["seconds"])))
        prev = r
    return None


def main():
    folder = Path(sys.argv[1])
    timing, cpu = {}, {}
    for line in Path(sys.argv[2]).read_text().split("\n"):
        if line.strip() and not line.startswith("#"):
            name, seconds, cpu_seconds, _ = line.split()
            timing.setdefault(name, []).append(float(seconds) / 64.0)
            if cpu_seconds != "-":  # the whole process: 64 spp plus the 1-spp warm-up
                cpu.setdefault(name, []).append(float(cpu_seconds) / 65.0)
    print("| variant | s per spp | CPU s per spp | RMSE | relMSE | relMSE x spp (a) "
          "| efficiency 1/(MSE t) | rel. efficiency 1/(relMSE t) | time to relMSE 0.05 "
          "| in the run |")
    print("| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |")
    floors = []
    for name in VARIANTS:
        rows = []
        with open(folder / f"{name}.csv") as f:
            for r in csv.DictReader(f):
                rows.append({k: (float(v) if k not in ("estimator", "error_source") else v)
                             for k, v in r.items()})
        last = rows[-1]
        high = [r for r in rows if r["spp"] >= 64]
        a_rel, c_rel = fit([(1.0 / r["spp"], r["rel_mse"]) for r in high])
        a_mse, c_mse = fit([(1.0 / r["spp"], r["mse"]) for r in high])
        floors.append((name, c_rel, c_mse))
        cost = min(timing[name])
        cpu_cost = statistics.median(cpu[name])
        efficiency = 1.0 / (a_mse * cost)
        rel_efficiency = 1.0 / (a_rel * cost)
        seconds_to_target = a_rel / TARGET * cost
        run = measured_time_to(rows, TARGET)
        run_text = (f"{run:.0f} s" if run is not None
                    else f"not reached ({last['rel_mse']:.3f} at {last['spp']:.0f} spp)")
        print(f"| {last['estimator']} | {cost:.4f} | {cpu_cost:.3f} "
              f"| {last['rmse']:.3f} at {last['spp']:.0f} spp "
              f"| {last['rel_mse']:.4f} | {a_rel:.1f} | {efficiency:.2f} | {rel_efficiency:.2f} "
              f"| {seconds_to_target:.0f} s ({a_rel / TARGET:.0f} spp) | {run_text} |")
    print()
    for name, c_rel, c_mse in floors:
        print(f"reference floor from {name}: relMSE {c_rel:.4f}, MSE {c_mse:.4f}")
    for name in VARIANTS:
        print(f"timing {name}: " + " ".join(f"{x:.3f}" for x in timing[name]))


if __name__ == "__main__":
    main()
