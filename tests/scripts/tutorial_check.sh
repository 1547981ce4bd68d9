#!/usr/bin/env bash
# Runs docs/tutorial.md as a user would: every ```sh block, in order, in one shell, in an empty
# directory, with `seedcal` and `python3` on the path; then checks what the tutorial says the
# user gets (a calibrated study with its report and both exports).
# Usage: tutorial_check.sh TUTORIAL.md SEEDCAL_BINARY PYTHON3 WORK_DIR
set -euo pipefail
tutorial=$1 seedcal=$2 python=$3 work=$4

rm -rf "$work"
mkdir -p "$work/bin" "$work/run"
ln -s "$(readlink -f "$seedcal")" "$work/bin/seedcal"
ln -s "$(command -v "$python")" "$work/bin/python3"

# The sh blocks: the lines between a line "```sh" and the next line "```".
awk '/^```sh$/ {on = 1; next} /^```$/ {on = 0; next} on {print}' "$tutorial" > "$work/tutorial.sh"
blocks=$(grep -c '^```sh$' "$tutorial")
echo "tutorial_check: $blocks sh blocks, $(wc -l < "$work/tutorial.sh") lines"
[ "$blocks" -ge 8 ] || { echo "tutorial_check: expected the tutorial's steps (8 or more sh blocks)"; exit 1; }

cd "$work/run"
PATH="$work/bin:$PATH" bash -euo pipefail "$work/tutorial.sh"

fail=0
need() { [ -s "$1" ] || { echo "tutorial_check: missing or empty: $1"; fail=1; }; }
for f in myseed-manual-5.toml myseed-manual-7.toml out/shear/metrics.json out/study/summary.json \
         out/study/report.html out/study/study.h5 out/liggghts/in.seedcal_model out/liggghts/in.settle \
         out/csv/spheres.csv out/csv/parameters.csv; do
  need "$f"
done
# The study calibrated both frictions inside their limits, verified both models, and chose one.
"$python" - <<'PY' || fail=1
import json, sys
s = json.load(open("out/study/summary.json"))
c = s["calibrated"]
ok = 0.05 <= c["seed_seed.static_friction"] <= 1.5 and 0.0 <= c["seed_seed.rolling_friction"] <= 0.4
models = {m["model"] for m in s["model_selection"]["models"]}
ok = ok and models == {"manual-5", "manual-7"} and s["model_selection"]["chosen"] in models
# The run's config holds the variety's values: the seed's density of myseed.toml.
m = json.load(open("out/shear/metrics.json"))
ok = ok and "density_kg_m3 = 1230.0" in m["provenance"]["config"] and m["variety"].endswith("myseed.toml")
print("tutorial_check: summary", "as described" if ok else "NOT as described", c, sorted(models))
sys.exit(0 if ok else 1)
PY
exit $fail
