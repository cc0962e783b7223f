#!/usr/bin/env python3
"""Plots the CSVs of the two LJ benchmarks (written with --csv) for docs/benchmarks.md.

    plot_benchmarks.py [--throughput LJ_CSV]... [--accuracy ACCURACY_CSV]... [--output-dir DIR] [--device D]

- From structmd_lj_benchmark CSVs: DIR/benchmark_throughput.png, particle-steps/s against N, log-log,
  one line per backend and precision, with the single-precision targets of issue 5 as markers.
  When several rows share (backend, precision, N), the last one read is drawn.
- From structmd_accuracy_benchmark CSVs: DIR/benchmark_accuracy.png, wall time per unit of simulated
  time against |energy drift| per particle, log-log, one marker per precision, one colour per dt,
  each point labelled with its dt and skin. A zero drift has no place on a log axis: such rows are
  listed on standard error and left out.

DIR defaults to the repository's docs/. Needs matplotlib (pip install matplotlib)."""
import argparse
import csv
import os
import sys

import matplotlib

matplotlib.use("Agg")  # files only, no display
import matplotlib.pyplot as plt

# Issue 5's single-precision throughput targets on one GPU: N -> particle-steps/s.
SINGLE_PRECISION_TARGETS = {10_000: 6e8, 64_000: 1.3e9, 1_000_000: 2.5e9, 16_000_000: 2.5e9}
PRECISION_MARKERS = {"single": "o", "mixed": "s", "double": "^"}


def read_rows(paths):
    rows = []
    for path in paths:
        with open(path, newline="") as f:
            rows.extend(csv.DictReader(f))
    return rows


def with_device(title, device):
    return f"{title}\n{device}" if device else title


def plot_throughput(rows, output, device):
    series = {}  # (backend, precision) -> {n: particle-steps/s}
    for row in rows:
        series.setdefault((row["backend"], row["precision"]), {})[int(row["n"])] = float(row["particle_steps_per_second"])

    figure, axes = plt.subplots(figsize=(7, 5))
    for (backend, precision), points in sorted(series.items()):
        sizes = sorted(points)
        axes.plot(sizes, [points[n] for n in sizes], marker=PRECISION_MARKERS.get(precision, "x"),
                  label=f"{backend}, {precision}")
    target_sizes = sorted(SINGLE_PRECISION_TARGETS)
    axes.plot(target_sizes, [SINGLE_PRECISION_TARGETS[n] for n in target_sizes], linestyle="none", marker="*",
              markersize=14, color="black", label="target (issue 5, single)")
    axes.set_xscale("log")
    axes.set_yscale("log")
    axes.set_xlabel("particles N")
    axes.set_ylabel("particle-steps / s")
    axes.set_title(with_device("LJ liquid throughput (density 0.8442, r_c 2.5, skin 0.3, dt 0.005)", device))
    axes.grid(True, which="both", alpha=0.3)
    axes.legend()
    figure.tight_layout()
    figure.savefig(output, dpi=150)
    plt.close(figure)


def plot_accuracy(rows, output, device):
    drawn = [row for row in rows if float(row["energy_drift"]) != 0.0]
    for row in rows:
        if row not in drawn:
            print(f"left out (zero drift): {row}", file=sys.stderr)
    time_steps = sorted({float(row["dt"]) for row in drawn})
    colours = {dt: plt.cm.viridis(k / max(1, len(time_steps) - 1)) for k, dt in enumerate(time_steps)}

    figure, axes = plt.subplots(figsize=(8, 6))
    for row in drawn:
        dt, skin = float(row["dt"]), float(row["skin"])
        x, y = abs(float(row["energy_drift"])), float(row["seconds_per_tau"])
        axes.scatter(x, y, marker=PRECISION_MARKERS.get(row["precision"], "x"), color=colours[dt])
        axes.annotate(f"{dt:g}/{skin:g}", (x, y), textcoords="offset points", xytext=(4, 3), fontsize=6)
    # Legend entries: marker = precision, colour = dt.
    for precision in sorted({row["precision"] for row in drawn}):
        axes.scatter([], [], marker=PRECISION_MARKERS.get(precision, "x"), color="grey", label=precision)
    for dt in time_steps:
        axes.scatter([], [], marker="o", color=colours[dt], label=f"dt {dt:g}")
    axes.set_xscale("log")
    axes.set_yscale("log")
    axes.set_xlabel("|energy drift| (epsilon / tau per particle)")
    axes.set_ylabel("wall time per tau (s)")
    axes.set_title(with_device("LJ liquid (shifted): cost against energy drift, labels dt/skin", device))
    axes.grid(True, which="both", alpha=0.3)
    axes.legend(fontsize=8)
    figure.tight_layout()
    figure.savefig(output, dpi=150)
    plt.close(figure)


def main():
    repository = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--throughput", action="append", default=[], help="CSV of structmd_lj_benchmark")
    parser.add_argument("--accuracy", action="append", default=[], help="CSV of structmd_accuracy_benchmark")
    parser.add_argument("--output-dir", default=os.path.join(repository, "docs"))
    parser.add_argument("--device", help="a second title line saying where it ran, e.g. 'NVIDIA H100, CUDA 13'")
    arguments = parser.parse_args()
    if not arguments.throughput and not arguments.accuracy:
        parser.error("give at least one --throughput or --accuracy CSV")

    if arguments.throughput:
        output = os.path.join(arguments.output_dir, "benchmark_throughput.png")
        plot_throughput(read_rows(arguments.throughput), output, arguments.device)
        print(output)
    if arguments.accuracy:
        output = os.path.join(arguments.output_dir, "benchmark_accuracy.png")
        plot_accuracy(read_rows(arguments.accuracy), output, arguments.device)
        print(output)


if __name__ == "__main__":
    main()
