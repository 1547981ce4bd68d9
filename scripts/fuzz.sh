#!/usr/bin/env bash
# Builds the libFuzzer targets in the clang sanitizer build (build-asan/, preset asan) and runs each for a bounded time on a seed
# corpus taken from data/ (STL, PLY and OBJ files are made here: small tetrahedra and a cube).
# Usage: scripts/fuzz.sh [SECONDS_PER_TARGET]   (default 60). A finding stops with exit 1 and
# leaves its input as build-asan/crash-* (add it to tests as a regression case).
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/lib/packages.sh
seconds="${1:-60}"
ensure_packages "${sanitizer_packages[@]}"
if [ ! -f build-asan/build.ninja ]; then cmake --preset asan >/dev/null; fi
cmake --build build-asan -j "$(nproc)" --target fuzz_stl fuzz_surface fuzz_study fuzz_clump

corpus=build-asan/corpus
rm -rf "$corpus"
mkdir -p "$corpus/stl" "$corpus/surface" "$corpus/study" "$corpus/clump"
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

cat > "$corpus/surface/tetra.obj" <<'OBJ'
# a tetrahedron
v 0 0 0
v 1 0 0
v 0 1 0
v 0 0 1
vn 0 0 1
f 1 3 2
f 1//1 2//1 4//1
f 1/1 4/1 3/1
f -3 -2 -1
OBJ
cat > "$corpus/surface/tetra.ply" <<'PLY'
ply
format ascii 1.0
comment a tetrahedron
element vertex 4
property float x
property float y
property float z
element face 4
property list uchar int vertex_indices
end_header
0 0 0
1 0 0
0 1 0
0 0 1
3 0 2 1
3 0 1 3
3 0 3 2
4 1 2 3 1
PLY
python3 - "$corpus/surface/tri.ply" <<'PY'
import struct, sys
with open(sys.argv[1], "wb") as f:
    f.write(b"ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty double x\nproperty double y\n"
            b"property double z\nelement face 1\nproperty list uchar uint vertex_indices\nend_header\n")
    f.write(struct.pack("<9d", 0, 0, 0, 1, 0, 0, 0, 1, 0) + struct.pack("<B3I", 3, 0, 1, 2))
PY

for target in stl surface study clump; do
  echo "== fuzz_$target: ${seconds} s =="
  (cd build-asan && ASAN_OPTIONS=detect_leaks=0 ./fuzz_$target -max_total_time="$seconds" -timeout=10 \
     -rss_limit_mb=2048 -print_final_stats=1 "corpus/$target" 2>&1 | tail -12)  # pipefail: a finding fails
done
