#!/usr/bin/env bash
# The whole test suite, in stages. Expects scripts/setup.sh to have built build/ (any preset).
# Stages: 1. Release suite (ctest, every label).
set -euo pipefail
cd "$(dirname "$0")/.."
jobs=$(nproc)

echo "== stage 1: Release test suite =="
ctest --test-dir build --output-on-failure -j "$jobs"
