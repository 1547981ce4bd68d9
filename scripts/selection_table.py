#!/usr/bin/env python3
"""Markdown table of a study's model selection for docs/results/: per model the mean (sd) and
relative error of every test with an experimental value, the mean |relative error| with its
standard error, the CPU seconds of one run of every test, and the rule's choice and comparison.

    python3 scripts/selection_table.py OUT
"""
import json
import sys


def fmt(v, digits=4):
    return "n/a" if v is None else f"{v:.{digits}g}"


def main(out):
    s = json.load(open(out + "/summary.json"))
    sel = s["model_selection"]
    models = sel["models"]
    tests = [t["label"] for t in models[0]["tests"] if t.get("experimental_mean") is not None]
    print("| model | " + " | ".join(f"{t}: mean (sd), error" for t in tests) +
          " | mean abs error (se) | CPU s a test set | Pareto |")
    print("|---|" + "---|" * len(tests) + "---|---|---|")
    for m in models:
        by = {t["label"]: t for t in m["tests"]}
        cells = []
        for name in tests:
            t = by.get(name)
            if t is None or t.get("mean") is None:
                cells.append("no result")
                continue
            cells.append(f"{fmt(t['mean'])} ({fmt(t.get('sd'), 3)}), {100 * t['rel_error']:+.1f} %")
        err = m.get("mean_abs_rel_error")
        se = m.get("mean_abs_rel_error_se")
        name = f"**{m['model']}**" if m["model"] == sel.get("chosen") else m["model"]
        print(f"| {name} | " + " | ".join(cells) +
              f" | {100 * err:.2f} % ({100 * se:.2f}) | {m['cpu_seconds']:.0f} | {'yes' if m.get('pareto') else 'no'} |"
              if err is not None else f"| {name} | " + " | ".join(cells) + " | n/a | n/a | no |")
    print()
    print(f"Chosen: {sel.get('chosen')} (most accurate: {sel.get('most_accurate')}); tied: "
          f"{', '.join(sel.get('tied', []))}. {sel.get('comparison', '')}.")
    if sel.get("replicates_note"):
        print(f"Replicates to separate the leaders: {sel.get('replicates_to_separate')} ({sel['replicates_note']}).")
    print(f"Verified at: {json.dumps(sel.get('verified_at'))}.")


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    main(sys.argv[1])
