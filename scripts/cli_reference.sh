#!/usr/bin/env bash
# The README's command-line reference, generated from the binary's own help: `seedcal --help` and
# the `--help` of every subcommand it lists, at every level (run, calibrate, study trend, ...), each
# in a fenced block under its own heading, between the README's markers
#   <!-- cli-reference:begin -->  and  <!-- cli-reference:end -->
#
# Usage:
#   scripts/cli_reference.sh BINARY                     print the block (markers included)
#   scripts/cli_reference.sh --check README.md BINARY   exit 0 when README.md's block is the generated
#                                                       one; else print a diff and exit 1
#   scripts/cli_reference.sh --write README.md BINARY   replace README.md's block by the generated one
# e.g. `bash scripts/cli_reference.sh --write README.md build/seedcal` after changing a help text.
# Exit 2 on bad usage, a binary that fails, or a README without exactly one pair of markers.
#
# The help text is CLI11's, which is deterministic; the one thing in it that depends on the
# machine is the program name in each "Usage:" line, which CLI11 takes from argv[0] (build/seedcal,
# an absolute path under ctest, ...): it is written as `seedcal` here. Defaults that depend on the
# machine (the thread count) are not printed by the binary ("default: all cores"), so nothing else
# is filtered. Trailing blanks are dropped so that an editor that strips them does not break the
# check.
set -euo pipefail
shopt -s inherit_errexit

readonly begin_marker='<!-- cli-reference:begin -->'
readonly end_marker='<!-- cli-reference:end -->'

usage() {
  echo "usage: $0 BINARY | --check README.md BINARY | --write README.md BINARY" >&2
  exit 2
}

mode=print
readme=
case "${1:-}" in
  --check | --write)
    [ $# -eq 3 ] || usage
    mode="${1#--}"
    readme="$2"
    binary="$3"
    ;;
  -* | '') usage ;;
  *)
    [ $# -eq 1 ] || usage
    binary="$1"
    ;;
esac
[ -x "$binary" ] || { echo "$0: $binary: not an executable" >&2; exit 2; }

# The help of one command (its words after the program name), normalised as said above.
help_of() {
  local out
  if ! out="$("$binary" "$@" --help)"; then
    echo "$0: '$(echo "$binary" "$@" --help)' failed" >&2
    exit 2
  fi
  printf '%s\n' "$out" | sed -E -e 's/^Usage: [^ ]+/Usage: seedcal/' -e 's/[[:space:]]+$//'
}

# The subcommands a help text lists: the first word of each indented line of its "Subcommands:"
# section, in the order CLI11 prints them (the order they were added).
subcommands_in() {
  awk '/^Subcommands:$/ { on = 1; next } on && /^[^ ]/ { on = 0 } on && /^  [a-z]/ { print $1 }'
}

# One heading and fenced block per command, depth first: `seedcal`, `seedcal run`, ...,
# `seedcal study`, `seedcal study multicontact`, ...
emit() {
  local text sub
  text="$(help_of "$@")"
  printf '### `%s`\n\n```text\n%s\n```\n\n' "$(echo seedcal "$@")" "$text"
  for sub in $(printf '%s\n' "$text" | subcommands_in); do
    emit "$@" "$sub"
  done
}

generate() {
  echo "$begin_marker"
  echo '<!-- Generated from the help texts by scripts/cli_reference.sh; edit those, then run'
  echo '     `bash scripts/cli_reference.sh --write README.md build/seedcal`. -->'
  echo
  emit
  echo "$end_marker"
}

# README.md's block, markers included; exit 2 unless it holds exactly one begin and one end
# marker, in that order.
readme_block() {
  local begins ends
  begins=$(grep -cxF "$begin_marker" "$readme" || true)
  ends=$(grep -cxF "$end_marker" "$readme" || true)
  if [ "$begins" != 1 ] || [ "$ends" != 1 ]; then
    echo "$0: $readme: needs exactly one line '$begin_marker' and one '$end_marker'" >&2
    exit 2
  fi
  awk -v b="$begin_marker" -v e="$end_marker" '$0 == b { on = 1 } on { print } $0 == e { on = 0 }' "$readme"
}

generated="$(generate)"
case "$mode" in
  print)
    printf '%s\n' "$generated"
    ;;
  check)
    [ -f "$readme" ] || { echo "$0: $readme: no such file" >&2; exit 2; }
    current="$(readme_block)"
    if [ "$current" != "$generated" ]; then
      echo "$readme: the command-line reference differs from the binary's help" \
           "(bash scripts/cli_reference.sh --write $readme $binary updates it):"
      diff -u --label "$readme" --label "$binary --help" <(printf '%s\n' "$current") \
        <(printf '%s\n' "$generated") || true
      exit 1
    fi
    ;;
  write)
    [ -f "$readme" ] || { echo "$0: $readme: no such file" >&2; exit 2; }
    readme_block >/dev/null
    tmp="$(mktemp "$(dirname "$readme")/.cli_reference.XXXXXX")"
    trap 'rm -f "$tmp"' EXIT
    block_file="$(mktemp)"
    trap 'rm -f "$tmp" "$block_file"' EXIT
    printf '%s\n' "$generated" >"$block_file"
    awk -v b="$begin_marker" -v e="$end_marker" -v f="$block_file" '
      $0 == b { while ((getline line < f) > 0) print line; skip = 1; next }
      $0 == e { skip = 0; next }
      !skip { print }' "$readme" >"$tmp"
    chmod --reference="$readme" "$tmp" 2>/dev/null || true
    mv "$tmp" "$readme"
    ;;
esac
