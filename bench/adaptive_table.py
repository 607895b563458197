"""The table of bench/run-adaptive.sh from the CSVs `raytracer converge` wrote.

Per target RMSE (0.01, the issue's, which whole images reach in a few samples;
0.003, where the noise is left in a few places), scene and series: CPU seconds
to the target (log-log interpolation
between the measured points around the crossing, '>' when the series never
got there), the ratio to uniform jittered, and the RMSE each series had at the
CPU time adaptive needed (interpolated the same way); for adaptive also the
ratio to uniform Sobol, the sampler it draws its samples from. Standard
library only. --clock wall reads the wall-clock seconds instead: on a GPU the
CPU time is the host's alone, not the renderer's work.

Usage: adaptive_table.py [--clock cpu|wall] OUT_DIR SCENE.json...
"""
import csv
import math
import os
import sys

TARGETS = [0.01, 0.003]
SERIES = ["random", "jittered", "sobol", "adaptive"]


def read_points(path, column):
    points = {}
    with open(path, newline="") as f:
        for row in csv.DictReader(f):
            points.setdefault(row["sampler"], []).append(
                (float(row[column]), float(row["rmse"])))
    return points


def seconds_to(points, target):
    """Log-log interpolated time of the first crossing below target, or None."""
    if points and points[0][1] <= target:
        return None
    for (t0, e0), (t1, e1) in zip(points, points[1:]):
        if e0 > target >= e1:
            f = (math.log(e0) - math.log(target)) / (math.log(e0) - math.log(e1))
            return math.exp(math.log(t0) + f * (math.log(t1) - math.log(t0)))
    return None


def rmse_at(points, seconds):
    """Log-log interpolated RMSE at a time inside the measured span, or None."""
    for (t0, e0), (t1, e1) in zip(points, points[1:]):
        if t0 <= seconds <= t1:
            f = (math.log(seconds) - math.log(t0)) / (math.log(t1) - math.log(t0))
            return math.exp(math.log(e0) + f * (math.log(e1) - math.log(e0)))
    return None


def print_table(out, scenes, target, clock):
    column = "cpu_seconds" if clock == "cpu" else "seconds"
    print(f"\ntime to RMSE {target} ({clock} s, whole image) and RMSE at adaptive's time")
    print(f"{'scene':<16} {'series':<9} {clock + '_s':>9} {'vs jittered':>12} {'vs sobol':>9} "
          f"{'rmse@t_adaptive':>16}")
    for scene in scenes:
        name = os.path.splitext(os.path.basename(scene))[0]
        points = read_points(os.path.join(out, name + ".csv"), column)
        times = {s: seconds_to(points[s], target) for s in SERIES if s in points}
        pivot = times.get("adaptive")
        for series in SERIES:
            if series not in points:
                continue
            t = times[series]
            last = points[series][-1][0]
            first, first_error = points[series][0]
            if t:
                shown = f"{t:.3f}"
            elif first_error <= target:
                shown = f"<{first:.3f}"  # below the target at its first point already
            else:
                shown = f">{last:.3f}"
            ratio = f"{t / times['jittered']:.2f}x" if t and times.get("jittered") else "-"
            to_sobol = "-"
            if series == "adaptive" and t and times.get("sobol"):
                to_sobol = f"{t / times['sobol']:.2f}x"
            at = rmse_at(points[series], pivot) if pivot else None
            print(f"{name:<16} {series:<9} {shown:>9} {ratio:>12} {to_sobol:>9} "
                  f"{(f'{at:.5f}' if at else '-'):>16}")


def main():
    args = sys.argv[1:]
    clock = "cpu"
    if args[:1] == ["--clock"]:
        clock, args = args[1], args[2:]
    if clock not in ("cpu", "wall") or not args:
        sys.exit("usage: adaptive_table.py [--clock cpu|wall] OUT_DIR SCENE.json...")
    out, scenes = args[0], args[1:]
    for target in TARGETS:
        print_table(out, scenes, target, clock)


if __name__ == "__main__":
    main()
