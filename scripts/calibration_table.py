#!/usr/bin/env python3
"""Markdown rows of calibration studies for docs/results/calibration.md: per study directory the
calibrated frictions with their 95 % intervals (and the shear target's alone), the runs that picked
the point (summary.json's `curve`), convergence, time and the chosen model.

    python3 scripts/calibration_table.py OUT/seed1 OUT/seed2 OUT/seed3
"""
import json
import sys

MU_S, MU_R = "seed_seed.static_friction", "seed_seed.rolling_friction"


def interval(d, p):
    v = d.get(p)
    return f"{v[0]:.3g} .. {v[1]:.3g}" if v else "n/a"


def main(dirs):
    print("| seed | mu_s (95 %) | mu_r (95 %) | identified mu_s, mu_r | shear alone: mu_s; mu_r | curve mode: test values at its points | slope (se), r2 | converged (calibration runs) | wall / CPU s |")
    print("|---|---|---|---|---|---|---|---|---|")
    notes = []
    for d in dirs:
        s = json.load(open(d + "/summary.json"))
        c = s.get("curve", {})
        alone = s.get("posterior", {}).get("target_alone", {}).get("calibrated_interval", {})
        cal, ci, ok = s["calibrated"], s["calibrated_interval"], s["identified"]
        m = c.get("response_model", {})
        slope_name = "s" if c.get("mode") == "curve" else "u2"
        vals = ", ".join(f"{p['value']:.1f}" if p.get("value") is not None else "failed" for p in c.get("points", []))
        slope = m.get("coefficients", {}).get(slope_name, float("nan"))
        se = m.get("standard_errors", {}).get(slope_name, float("nan"))
        print(f"| {s['provenance']['seed']} | {cal[MU_S]:.3f} ({interval(ci, MU_S)}) | {cal[MU_R]:.4f} ({interval(ci, MU_R)}) | "
              f"{ok.get(MU_S)}, {ok.get(MU_R)} | {interval(alone, MU_S)}; {interval(alone, MU_R)} | "
              f"{c.get('mode', c.get('skipped', 'n/a'))}: {vals} | {slope_name} {slope:.2f} ({se:.2f}), {m.get('r2', float('nan')):.2f} | "
              f"{s['converged']} ({s['evaluations']}) | {s['wall_seconds']:.0f} / {s['cpu_seconds']:.0f} |")
        sel = s.get("model_selection", {})
        rows = []
        for row in sel.get("models", []):
            tests = ", ".join(f"{t['test']} {t['mean']:.4g} ({100 * t['rel_error']:+.1f} %)" for t in row["tests"] if t.get("mean") is not None)
            rows.append(f"{row['model']}: {tests}; error {100 * row['mean_abs_rel_error']:.1f} %, {row['cpu_seconds']:.0f} CPU s")
        extra = "; ".join(x for x in (c.get("at_end"), c.get("note")) if x)
        notes.append(f"- seed {s['provenance']['seed']}: chosen {sel.get('chosen')}. " + " | ".join(rows) + (f". Curve: {extra}" if extra else ""))
    print()
    print("\n".join(notes))


if __name__ == "__main__":
    main(sys.argv[1:])
