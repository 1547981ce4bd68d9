#!/usr/bin/env bash
# The key and metric tables of the scene docs, generated from each scene's schema declaration
# (calibrate/scenes/scene_schema.hpp, printed by `seedcal keys KIND --markdown`), between the
# markers
#   <!-- scene-keys:begin -->  and  <!-- scene-keys:end -->
# of docs/scenes/KIND.md for every kind `seedcal keys` lists, and of docs/scenes/README.md for the
# run report's metrics (`seedcal keys --markdown`).
#
# Usage:
#   scripts/scene_keys.sh --check DOCS_DIR BINARY   exit 0 when every block is the generated one;
#                                                   else print the diffs and exit 1
#   scripts/scene_keys.sh --write DOCS_DIR BINARY   replace every block by the generated one
# e.g. `bash scripts/scene_keys.sh --write docs/scenes build/seedcal` after changing a schema.
# Exit 2 on bad usage, a binary that fails, or a doc without exactly one pair of markers.
set -euo pipefail
shopt -s inherit_errexit

readonly begin_marker='<!-- scene-keys:begin -->'
readonly end_marker='<!-- scene-keys:end -->'

usage() {
  echo "usage: $0 --check DOCS_DIR BINARY | --write DOCS_DIR BINARY" >&2
  exit 2
}
[ $# -eq 3 ] || usage
case "$1" in
  --check | --write) mode="${1#--}" ;;
  *) usage ;;
esac
docs="$2"
binary="$3"
[ -d "$docs" ] || { echo "$0: $docs: not a directory" >&2; exit 2; }
[ -x "$binary" ] || { echo "$0: $binary: not an executable" >&2; exit 2; }

# The scene kinds with a schema: the words after the colon of `seedcal keys`'s first line.
kinds="$("$binary" keys | sed -n '1s/^[^:]*: *//p')"
[ -n "$kinds" ] || { echo "$0: '$binary keys' listed no scene kind" >&2; exit 2; }

# The generated block for one doc (markers included): $1 = kind, or "" for the run report.
generate() {
  local body
  if [ -n "$1" ]; then body="$("$binary" keys "$1" --markdown)"; else body="$("$binary" keys --markdown)"; fi
  echo "$begin_marker"
  echo '<!-- Generated from the scene'"'"'s schema by scripts/scene_keys.sh; edit the declaration in'
  echo '     calibrate/scenes/, then run `bash scripts/scene_keys.sh --write docs/scenes build/seedcal`. -->'
  echo
  printf '%s\n' "$body"
  echo "$end_marker"
}

doc_block() {  # $1 = file: its block, markers included
  local begins ends
  begins=$(grep -cxF "$begin_marker" "$1" || true)
  ends=$(grep -cxF "$end_marker" "$1" || true)
  if [ "$begins" != 1 ] || [ "$ends" != 1 ]; then
    echo "$0: $1: needs exactly one line '$begin_marker' and one '$end_marker'" >&2
    exit 2
  fi
  awk -v b="$begin_marker" -v e="$end_marker" '$0 == b { on = 1 } on { print } $0 == e { on = 0 }' "$1"
}

status=0
for kind in "" $kinds; do
  if [ -n "$kind" ]; then file="$docs/$kind.md"; else file="$docs/README.md"; fi
  [ -f "$file" ] || { echo "$0: $file: no such file" >&2; exit 2; }
  generated="$(generate "$kind")"
  current="$(doc_block "$file")"
  [ "$current" == "$generated" ] && continue
  if [ "$mode" == check ]; then
    echo "$file: the key tables differ from the scene's schema" \
         "(bash scripts/scene_keys.sh --write $docs $binary updates them):"
    diff -u --label "$file" --label "$binary keys ${kind:---markdown}" <(printf '%s\n' "$current") \
      <(printf '%s\n' "$generated") || true
    status=1
    continue
  fi
  block_file="$(mktemp)"
  tmp="$(mktemp "$(dirname "$file")/.scene_keys.XXXXXX")"
  printf '%s\n' "$generated" >"$block_file"
  awk -v b="$begin_marker" -v e="$end_marker" -v f="$block_file" '
    $0 == b { while ((getline line < f) > 0) print line; skip = 1; next }
    $0 == e { skip = 0; next }
    !skip { print }' "$file" >"$tmp"
  chmod --reference="$file" "$tmp" 2>/dev/null || true
  mv "$tmp" "$file"
  rm -f "$block_file"
done
exit "$status"
