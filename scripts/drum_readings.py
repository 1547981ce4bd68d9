#!/usr/bin/env python3
"""Reads the dynamic angle of repose of finished drum runs in several ways, from the surface
points the runs wrote, without running them again.

Usage: python3 scripts/drum_readings.py RUN_DIR... (each written by `seedcal run drum.toml --out
RUN_DIR`: drum_surface.csv and metrics.json)

The scene (docs/scenes/drum.md) fits one line to the central `fit_width_fraction` (0.6) of the
bed's chord in every frame. The laboratory's reading of a binarised image is not stated, so this
also reads:
  fit F      a least-squares line over the central fraction F of the chord (F = 0.6: the scene);
  hi-lo      the line from the surface's highest to its lowest point (an S-shaped surface at a
             higher speed shows in it first);
  steepest   the steepest least-squares line over 7 consecutive columns (about 3.5 seeds).
Each run's reading is the mean over its frames. Runs are grouped by `speed_rpm`; for the lowest
and highest speed the change is also given in pooled sample sd (when each has two runs or more).
"""
import csv
import json
import math
import statistics
import sys
from collections import defaultdict


def slope(points):
    mx = statistics.fmean(p[0] for p in points)
    mz = statistics.fmean(p[1] for p in points)
    sxx = sum((x - mx) ** 2 for x, _ in points)
    return sum((x - mx) * (z - mz) for x, z in points) / sxx


def angle(s):
    return math.degrees(math.atan(abs(s)))


def readings(points):
    points = sorted(points)
    x0, x1 = points[0][0], points[-1][0]
    centre, width = 0.5 * (x0 + x1), x1 - x0
    out = {}
    for fraction in (0.4, 0.6, 0.8, 1.0):
        window = [p for p in points if abs(p[0] - centre) <= 0.5 * fraction * width + 1e-12]
        out[f"fit {fraction:.1f}"] = angle(slope(window))
    hi = max(points, key=lambda p: p[1])
    lo = min(points, key=lambda p: p[1])
    out["hi-lo"] = angle((hi[1] - lo[1]) / (hi[0] - lo[0]))
    w = 7
    out["steepest"] = max(angle(slope(points[i:i + w])) for i in range(len(points) - w + 1))
    return out


def run_readings(run_dir):
    frames = defaultdict(list)
    try:
        with open(f"{run_dir}/metrics.json") as f:
            rpm = float(json.load(f)["speed_rpm"])
        with open(f"{run_dir}/drum_surface.csv") as f:
            for row in csv.DictReader(f):
                frames[row["time_s"]].append((float(row["x_m"]), float(row["z_m"])))
    except (OSError, KeyError, ValueError) as e:
        sys.exit(f"{run_dir}: not a finished drum run written with --out "
                 f"(metrics.json with speed_rpm, drum_surface.csv): {e!r}")
    per_frame = [readings(p) for p in frames.values() if len(p) >= 7]
    if not per_frame:
        sys.exit(f"{run_dir}/drum_surface.csv: no frame with 7 surface columns or more")
    return rpm, {k: statistics.fmean(r[k] for r in per_frame) for k in per_frame[0]}


def main(dirs):
    if not dirs:
        sys.exit(__doc__)
    by_speed = defaultdict(list)
    for d in dirs:
        rpm, r = run_readings(d)
        by_speed[rpm].append(r)
    speeds = sorted(by_speed)
    keys = list(by_speed[speeds[0]][0])
    print(f"{'reading':9s}" + "".join(f"{f'{s:g} rpm: deg (sd, runs)':>24s}" for s in speeds) +
          "   last - first (pooled sd)")
    for k in keys:
        line = f"{k:9s} "
        for s in speeds:
            v = [r[k] for r in by_speed[s]]
            sd = f"{statistics.stdev(v):.2f}" if len(v) > 1 else "-"
            line += f"{f'{statistics.fmean(v):.2f} ({sd}, {len(v)})':>24s}"
        a = [r[k] for r in by_speed[speeds[0]]]
        b = [r[k] for r in by_speed[speeds[-1]]]
        change = statistics.fmean(b) - statistics.fmean(a)
        line += f"   {change:+.2f} deg"
        if len(a) > 1 and len(b) > 1:
            pooled = math.sqrt(0.5 * (statistics.variance(a) + statistics.variance(b)))
            line += f" ({change / pooled:+.2f})"
        print(line)


if __name__ == "__main__":
    main(sys.argv[1:])
