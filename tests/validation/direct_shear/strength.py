#!/usr/bin/env python3
"""Shear strength of a LIGGGHTS curve (in.direct_shear's output) by seedcal's rule
(solver/scenes/direct_shear.cpp): the curve smoothed by a centred moving average over 0.5 mm of
displacement, its maximum up to the failure displacement of 4 mm (GB/T 50123).

Usage: strength.py CURVE [CURVE ...]   prints one strength in Pa per curve
"""
import sys

WINDOW_M, FAILURE_M = 0.0005, 0.004


def strength(path):
    rows = []
    with open(path) as f:
        for line in f:
            parts = line.split()
            if len(parts) < 2 or parts[0].startswith("#") or not parts[0][0].isdigit():
                continue
            rows.append((float(parts[0]), float(parts[1])))
    best = 0.0
    lo = 0
    for k, (d, _) in enumerate(rows):
        if d > FAILURE_M:
            break
        while rows[lo][0] < d - 0.5 * WINDOW_M:
            lo += 1
        window = [t for (x, t) in rows[lo:] if abs(x - d) <= 0.5 * WINDOW_M]
        best = max(best, sum(window) / len(window))
    return best


if __name__ == "__main__":
    for p in sys.argv[1:]:
        print("%.1f" % strength(p))
