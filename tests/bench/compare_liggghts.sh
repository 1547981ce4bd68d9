#!/usr/bin/env bash
# Runs the peer benchmark back to back on this machine: the LIGGGHTS decks of
# shared/bench/liggghts/ (Debian package `liggghts`) and `seedcal bench` on the same scenes, on one
# and two processes/threads, and prints one table. Needs build/seedcal (scripts/setup.sh).
#   bash tests/bench/compare_liggghts.sh [OUTDIR]
set -euo pipefail
root="$(cd "$(dirname "$0")/../.." && pwd)"
decks="$root/../shared/bench/liggghts"
out="${1:-$root/out/bench}"
mkdir -p "$out"
command -v liggghts >/dev/null || { echo "install the Debian package: apt-get install -y liggghts openmpi-bin"; exit 2; }
cp "$decks"/in.settled_bed "$decks"/in.clump_bed "$decks"/clump9.txt "$root/tests/bench/in.fine_clump_bed" "$out/"
# The fine clump bed's template, as LIGGGHTS's multisphere reads it: x y z r per line (m).
python3 - "$root/data/clumps/jinong1-auto-s2.toml" > "$out/auto_s2.txt" <<'PY'
import re, sys
text = open(sys.argv[1]).read()
for row in re.findall(r"\[([-0-9.e+]+), *([-0-9.e+]+), *([-0-9.e+]+), *([-0-9.e+]+)\]", text):
    print(" ".join(row))
PY
cd "$out"

loop_time() { grep "Loop time" "$1" | tail -1 | awk '{print $4}'; }
# The thermo column of compute cs is headed "cs" (LIGGGHTS 3.8) or "c_cs"; the last row of the
# timed run holds the bed's total contact count.
contacts() { awk '/Step +Atoms +KinEng +(c_)?cs/{f=1;next} f&&/^ +[0-9]/{c=$4} END{print c+0}' "$1"; }

run_liggghts() {  # name deck settle np
  local name=$1 deck=$2 settle=$3 np=$4
  if [ "$np" = 1 ]; then
    liggghts -var settle "$settle" -var steps 20000 -in "$deck" -log "lig-$name-$np.log" > /dev/null
  else
    mpirun --allow-run-as-root -np "$np" liggghts -var settle "$settle" -var steps 20000 -in "$deck" \
      -log "lig-$name-$np.log" > /dev/null
  fi
}

printf "%-12s %-10s %-4s %14s %12s %10s\n" scene code n sphere_steps/s contacts/sph wall_s > table.txt
for scene in settled-bed clump-bed fine-clump-bed; do
  case "$scene" in
    settled-bed) deck=in.settled_bed settle=80000 spheres=10000 clump="" ;;
    clump-bed) deck=in.clump_bed settle=100000 spheres=9000 clump="--clump-file $root/data/bench/clump9.txt" ;;
    fine-clump-bed) deck=in.fine_clump_bed settle=160000 spheres=16400 clump="--clump-file $root/data/clumps/jinong1-auto-s2.toml" ;;
  esac
  for n in 1 2; do
    run_liggghts "$scene" "$deck" "$settle" "$n"
    t=$(loop_time "lig-$scene-$n.log")
    c=$(contacts "lig-$scene-$n.log")
    printf "%-12s %-10s %-4s %14.4e %12.3f %10.2f\n" "$scene" liggghts "$n" \
      "$(echo "$spheres * 20000 / $t" | bc -l)" "$(echo "$c / $spheres" | bc -l)" "$t" >> table.txt
    # shellcheck disable=SC2086
    "$root/build/seedcal" bench "$scene" --threads "$n" $clump \
      | tail -1 > "seedcal-$scene-$n.json"
    python3 - "$scene" "$n" "seedcal-$scene-$n.json" >> table.txt <<'PY'
import json, sys
j = json.load(open(sys.argv[3]))
print("%-12s %-10s %-4s %14.4e %12.3f %10.2f" % (sys.argv[1], "seedcal", sys.argv[2],
      j["sphere_steps_per_second"], j["contacts_per_sphere"], j["wall_seconds"]))
PY
  done
done
cat table.txt
