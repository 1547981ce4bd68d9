#!/bin/sh
# Rebuilds the clump files the scenes use (docs/clumps.md): the paper's manual sphere counts per
# variety, the automatic fill at smoothness 2 and the paper's smallest automatic model. Run from
# the repository root:
#   sh data/clumps/generate.sh [path/to/seedcal]
set -e
SEEDCAL=${1:-build/seedcal}
build() { "$SEEDCAL" clump build --variety "$1" --method manual --spheres "$2" --out "data/clumps/$1-manual-$2.toml"; }
for n in 7 9 11; do build jinong1 $n; done
for n in 9 11 13; do build jinong2 $n; done
for n in 7 9 11; do build jinong3 $n; done
for v in jinong1 jinong2 jinong3; do
  "$SEEDCAL" clump build --variety $v --method auto --smoothness 2 --out "data/clumps/$v-auto-s2.toml"
done
# The paper's smallest automatic model of each variety (Table 4): 11, 13 and 11 spheres (the fill
# nearest 13 for Jinong 2 has 11: the count moves in steps).
for vn in jinong1:11 jinong2:13 jinong3:11; do
  v=${vn%:*} n=${vn#*:}
  "$SEEDCAL" clump build --variety $v --method auto --spheres $n --out "data/clumps/$v-auto-$n.toml"
done
