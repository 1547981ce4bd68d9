#!/usr/bin/env bash
# Builds the libFuzzer targets in the clang sanitizer build (build-asan/, preset asan) and runs each for a bounded time on a seed
# corpus taken from data/ (STL files are made here: one binary, one ASCII tetrahedron).
# Usage: scripts/fuzz.sh [SECONDS_PER_TARGET]   (default 60). A finding stops with exit 1 and
# leaves its input as build-asan/crash-* (add it to tests as a regression case).
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/lib/packages.sh
seconds="${1:-60}"
ensure_packages "${sanitizer_packages[@]}"
if [ ! -f build-asan/build.ninja ]; then cmake --preset asan >/dev/null; fi
cmake --build build-asan -j "$(nproc)" --target fuzz_stl fuzz_study fuzz_clump

corpus=build-asan/corpus
rm -rf "$corpus"
mkdir -p "$corpus/stl" "$corpus/study" "$corpus/clump"
cp data/studies/*.toml "$corpus/study/"
cp data/clumps/*.toml "$corpus/clump/"
cat > "$corpus/stl/tetra.stl" <<'STL'
solid tetra
facet normal 0 0 -1
outer loop
vertex 0 0 0
vertex 1 0 0
vertex 0 1 0
endloop
endfacet
facet normal 0 -1 0
outer loop
vertex 0 0 0
vertex 0 0 1
vertex 1 0 0
endloop
endfacet
endsolid tetra
STL
python3 - "$corpus/stl/tri.stl" <<'PY'
import struct, sys
with open(sys.argv[1], "wb") as f:
    f.write(b"binary".ljust(80, b" ") + struct.pack("<I", 1))
    f.write(struct.pack("<12fH", 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0))
PY

for target in stl study clump; do
  echo "== fuzz_$target: ${seconds} s =="
  (cd build-asan && ASAN_OPTIONS=detect_leaks=0 ./fuzz_$target -max_total_time="$seconds" -timeout=10 \
     -rss_limit_mb=2048 -print_final_stats=1 "corpus/$target" 2>&1 | tail -12)  # pipefail: a finding fails
done
