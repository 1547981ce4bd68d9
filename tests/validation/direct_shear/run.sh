#!/usr/bin/env bash
# Cross-check of the direct shear box against LIGGGHTS (docs/results/direct_shear.md, "Cross-check"):
# seeds of one size (SHAPE sphere: r 4.35 mm; clump: data/bench/clump9.txt) weighed in to the
# laboratory's bulk density (680.75 kg/m3) in the ZJ rig of seedcal's quick direct shear, upper ring
# held, seed-seed static friction 0.3 and 0.9, rolling friction off and on, N seeds a level in each
# code. Prints each run's shear strength and, per code and rolling setting, the means, sds and the
# friction effect in pooled sd.
#   bash tests/validation/direct_shear/run.sh [SHAPE] [N] [OUT_DIR]   (needs build/seedcal and liggghts)
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
root="$(cd "$here/../../.." && pwd)"
shape="${1:-sphere}"
n="${2:-6}"
out="${3:-$(mktemp -d)}"
mkdir -p "$out"
python3 "$here/make_rig.py" "$out/rig"
if [ "$shape" = clump ]; then
  seedfile="$root/data/bench/clump9.txt"; clumps=1
else
  seedfile="$out/sphere.txt"; clumps=0
  printf '0.0 0.0 0.0 0.00435\n' > "$seedfile"
fi
primes=(10007 10009 10037 10039 10061 10067 10069 10079 10091 10093 10099 10103)
# dt: seedcal's default step for these seeds (0.2 of the Rayleigh step), read from its own run.
jobs=()
for roll in off cdt; do
  for mu in 0.3 0.9; do
    seedcal_roll=$([ "$roll" = off ] && echo none || echo cdt)
    "$root/build/seedcal" run "$root/data/scenes/jinong1/direct_shear.toml" --set fidelity=quick \
      --set particle.clump_file="$seedfile" --set particle.scale_sd=0 \
      --set direct_shear.quick.upper_ring_fixed=true --set direct_shear.quick.sample_density_kg_m3=680.75 --set contact.rolling="$seedcal_roll" \
      --set seed_seed.static_friction="$mu" --set repeats="$n" --jobs 2 --seed 1 \
      --out "$out/seedcal-$roll-$mu" > /dev/null
    # The same step and the same number of seeds (one size: the weighed-in mass over one seed's).
    read -r dt count < <(python3 -c "import json; j = json.load(open('$out/seedcal-$roll-$mu/metrics.json')); print(j['dt_s'], j['seeds'])")
    for k in $(seq 0 $((n - 1))); do
      jobs+=("liggghts -var mu $mu -var roll $roll -var seed ${primes[$k]} -var dt $dt -var rig $out/rig -var out $out/liggghts-$roll-$mu-$k.txt -var clumps $clumps -var clump $seedfile -var count $count -in $here/in.direct_shear -log none -screen /dev/null")
    done
  done
done
printf '%s\n' "${jobs[@]}" | (cd "$out" && xargs -P 2 -I{} sh -c '{}')
python3 - "$out" "$n" "$here" <<'PY'
import json, math, statistics as st, sys
sys.path.insert(0, sys.argv[3])
from strength import strength
out, n = sys.argv[1], int(sys.argv[2])
print("| code | rolling | mu_s | shear strength, kPa, per seed | mean | sd | effect 0.3 -> 0.9, pooled sd |")
print("|---|---|---|---|---|---|---|")
for code in ("seedcal", "liggghts"):
    for roll in ("off", "cdt"):
        vals = {}
        for mu in ("0.3", "0.9"):
            if code == "seedcal":
                v = [x / 1e3 for x in json.load(open(f"{out}/seedcal-{roll}-{mu}/metrics.json"))["shear_strength_pa_samples"]]
            else:
                v = [strength(f"{out}/liggghts-{roll}-{mu}-{k}.txt") / 1e3 for k in range(n)]
            vals[mu] = v
        pooled = math.sqrt((st.variance(vals["0.3"]) + st.variance(vals["0.9"])) / 2)
        effect = (st.mean(vals["0.9"]) - st.mean(vals["0.3"])) / pooled
        for mu in ("0.3", "0.9"):
            v = vals[mu]
            print(f"| {code} | {roll} | {mu} | {' '.join('%.0f' % x for x in v)} | {st.mean(v):.1f} | {st.stdev(v):.1f} | {effect:.2f} |" if mu == "0.9" else
                  f"| {code} | {roll} | {mu} | {' '.join('%.0f' % x for x in v)} | {st.mean(v):.1f} | {st.stdev(v):.1f} | |")
PY
