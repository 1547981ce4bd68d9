#!/usr/bin/env bash
# The whole test suite, in stages. Expects scripts/setup.sh to have built build/ (the README's
# test command builds it with --preset ci: Release, warnings as errors).
#   0. Chromium (headless) for the report's browser test; LIGGGHTS for the export's cross-check.
#   1. Release suite: every ctest test (unit, physics, regression, cli, browser, validation).
#   2. ASan + UBSan + LeakSanitizer build (clang) of the same suite (tests labelled `slow` left out to
#      stay in budget; cli_scenes_mini_test runs every scene kind and the MPI executor in miniature).
#   3. The libFuzzer targets of that build (STL, PLY and OBJ, study and clump readers), 30 s each
#      (a short run in CI's budget; scripts/fuzz.sh alone runs 60 s or as long as asked).
# Set SEEDCAL_SKIP_SANITIZE=1 to run stage 1 only (local iteration), SEEDCAL_FUZZ_SECONDS=N to
# change the fuzzing time.
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/lib/packages.sh
jobs=$(nproc)
start=$(date +%s)

# The report's browser test (reports_browser_test, label `browser`) loads report.html in headless
# Chromium and skips without it: 24 packages, 122 MB, about 35 s to install (docs/reports.md).
echo "== stage 0: headless Chromium for the report's browser test, LIGGGHTS for the export's =="
ensure_packages chromium
# validation_export_settle_test runs the deck `seedcal export` writes in LIGGGHTS (Debian package
# liggghts, docs/export.md); it skips without it, and CI fails on that skip (below).
ensure_packages liggghts

# A skipped test shows as skipped; CI fails on any skip but these (name: why it may skip):
#   physics_determinism_test: the CPU has neither AVX2 nor AVX-512F, so only the one-lane kernel runs.
expected_skips="physics_determinism_test"
check_skips() {  # $1: ctest's output
  local skipped
  skipped=$(sed -n '/The following tests did not run:/,$p' "$1" | grep -o '[A-Za-z0-9_]* (Skipped)' | cut -d' ' -f1 || true)
  for t in $skipped; do
    if ! grep -qw "$t" <<<"$expected_skips"; then
      echo "unexpected skip: $t (scripts/test.sh lists the skips CI expects)"; return 1
    fi
  done
}

echo "== stage 1: Release test suite =="
ctest --test-dir build --output-on-failure -j "$jobs" | tee build/ctest-release.log
check_skips build/ctest-release.log

if [ "${SEEDCAL_SKIP_SANITIZE:-0}" != "1" ]; then
  echo "== stage 2: AddressSanitizer + UndefinedBehaviorSanitizer (clang, -O1) =="
  ensure_packages "${sanitizer_packages[@]}"
  cmake --preset asan >/dev/null
  cmake --build --preset asan -j "$jobs"
  # Leaks are detected in every test and in every seedcal process the tests start (the miniature
  # scenes and the two-rank MPI calibration of cli_scenes_mini_test among them); the suppressions
  # cover the MPI runtime only (tests/sanitize/lsan.supp).
  ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 LSAN_OPTIONS=suppressions=$PWD/tests/sanitize/lsan.supp:print_suppressions=0 \
  UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
    ctest --test-dir build-asan --output-on-failure -j "$jobs" -LE slow | tee build-asan/ctest-asan.log
  check_skips build-asan/ctest-asan.log

  echo "== stage 3: libFuzzer, ${SEEDCAL_FUZZ_SECONDS:-30} s per target =="
  bash scripts/fuzz.sh "${SEEDCAL_FUZZ_SECONDS:-30}"
fi
echo "== all stages passed in $(( $(date +%s) - start )) s =="
