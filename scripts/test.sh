#!/usr/bin/env bash
# Installs what is missing, builds handlab with warnings as errors, and runs the whole test
# suite: once in the Release build, once more with AddressSanitizer and UBSan (Qt-free parts).
set -euo pipefail
cd "$(dirname "$0")/.."
jobs=$(nproc)

scripts/install-deps.sh

# The Release tree is scripts/run.sh's (the same preset): after run.sh nothing is rebuilt.
cmake --preset release
cmake --build build -j "$jobs"
ctest --test-dir build --output-on-failure -j "$jobs"

cmake --preset sanitize
cmake --build build-sanitize -j "$jobs"
ctest --test-dir build-sanitize --output-on-failure -j "$jobs"
