#!/usr/bin/env python3
"""The direct shear box's index at the paper's Table 6 values, and its answer to the inter-seed
static and rolling friction, for each rig and fidelity: docs/results/direct_shear.md.

For every (geometry, fidelity): seeds 1-N at Table 6 (mean, sd, per-run cv with its 90 % interval,
the curve shapes), and the static friction 0.3 -> 0.9 and rolling friction 0.02 -> 0.12 at M seeds
a level, each effect in pooled sd. One thread a run, J runs at a time.

Usage: scripts/shear_rig_table.py OUT_DIR [--seeds 10] [--level-seeds 6] [--jobs 2]
       [--geometry zj shells] [--fidelity quick paper] [--set KEY=VALUE ...]
"""
import argparse
import concurrent.futures as cf
import json
import math
import os
import statistics as st
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SCENE = os.path.join(ROOT, "data/scenes/jinong1/direct_shear.toml")


def chi2_quantile(p, k):
    """Wilson-Hilferty approximation of the chi-square quantile (0.5 % for k >= 5)."""
    z = {0.05: -1.6448536, 0.95: 1.6448536}[p]
    return k * (1.0 - 2.0 / (9.0 * k) + z * math.sqrt(2.0 / (9.0 * k))) ** 3


def run(args):
    out, fidelity, geometry, seed, sets = args
    if not os.path.exists(os.path.join(out, "metrics.json")):
        cmd = [os.path.join(ROOT, "build/seedcal"), "run", SCENE, "--set", "fidelity=" + fidelity,
               "--set", "direct_shear.%s.geometry=%s" % (fidelity, geometry), "--seed", str(seed),
               "--threads", "1", "--out", out]
        for s in sets:
            cmd += ["--set", s]
        subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    with open(os.path.join(out, "metrics.json")) as f:
        return json.load(f)


def main():
    p = argparse.ArgumentParser()
    p.add_argument("out")
    p.add_argument("--seeds", type=int, default=10)
    p.add_argument("--level-seeds", type=int, default=6)
    p.add_argument("--jobs", type=int, default=2)
    p.add_argument("--geometry", nargs="+", default=["zj", "shells"])
    p.add_argument("--fidelity", nargs="+", default=["quick", "paper"])
    p.add_argument("--set", nargs="*", default=[], dest="sets")
    a = p.parse_args()
    levels = [("base", []), ("mu_s 0.3", ["seed_seed.static_friction=0.3"]), ("mu_s 0.9", ["seed_seed.static_friction=0.9"]),
              ("mu_r 0.02", ["seed_seed.rolling_friction=0.02"]), ("mu_r 0.12", ["seed_seed.rolling_friction=0.12"])]
    tasks = []
    for g in a.geometry:
        for fid in a.fidelity:
            for name, sets in levels:
                n = a.seeds if name == "base" else a.level_seeds
                for s in range(1, n + 1):
                    d = os.path.join(a.out, g, fid, name.replace(" ", "_"), str(s))
                    os.makedirs(d, exist_ok=True)
                    tasks.append(((g, fid, name, s), (d, fid, g, s, sets + a.sets)))
    with cf.ThreadPoolExecutor(a.jobs) as ex:
        results = dict(zip([t[0] for t in tasks], ex.map(run, [t[1] for t in tasks])))
    print("| rig | fidelity | Table 6, seeds 1-%d: mean kPa (sd) | cv, 90 %% interval | curves: peak / plateau / rising |"
          " CPU s a run | mu_s 0.3 -> 0.9, kPa | effect, pooled sd | mu_r 0.02 -> 0.12, kPa | effect, pooled sd |" % a.seeds)
    print("|---|---|---|---|---|---|---|---|---|---|")
    for g in a.geometry:
        for fid in a.fidelity:
            def vals(name, n):
                return [results[(g, fid, name, s)] for s in range(1, n + 1)]
            base = vals("base", a.seeds)
            bad = [m for m in base if m["status"] != "ok"]
            x = [m["shear_strength_pa"] / 1e3 for m in base]
            mean, sd = st.mean(x), st.stdev(x)
            k = len(x) - 1
            cv_lo = sd / mean * math.sqrt(k / chi2_quantile(0.95, k))
            cv_hi = sd / mean * math.sqrt(k / chi2_quantile(0.05, k))
            shapes = [m.get("curve_shape", "?") for m in base]
            cpu = st.mean(m["cpu_seconds"] for m in base)

            def effect(lo, hi):
                a_, b_ = ([m["shear_strength_pa"] / 1e3 for m in vals(n, a.level_seeds)] for n in (lo, hi))
                pooled = math.sqrt((st.variance(a_) + st.variance(b_)) / 2)
                return st.mean(a_), st.mean(b_), (st.mean(b_) - st.mean(a_)) / pooled
            s0, s1, se = effect("mu_s 0.3", "mu_s 0.9")
            r0, r1, re = effect("mu_r 0.02", "mu_r 0.12")
            print("| %s | %s | %.1f (%.1f)%s | %.1f %% (%.1f-%.1f %%) | %d / %d / %d | %.1f | %.1f -> %.1f | %.2f | %.1f -> %.1f | %.2f |" % (
                g, fid, mean, sd, " (%d failed)" % len(bad) if bad else "", 100 * sd / mean, 100 * cv_lo, 100 * cv_hi,
                shapes.count("peak"), shapes.count("plateau"), shapes.count("rising"), cpu, s0, s1, se, r0, r1, re))
    sys.stdout.flush()


if __name__ == "__main__":
    main()
