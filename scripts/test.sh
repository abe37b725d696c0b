#!/usr/bin/env bash
# Installs what is missing, builds handlab with warnings as errors, and runs the whole test
# suite: once in the Release build, once more with AddressSanitizer and UBSan (Qt-free parts).
set -euo pipefail
cd "$(dirname "$0")/.."
jobs=$(nproc)

scripts/install-deps.sh

cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release -DHANDLAB_WERROR=ON
cmake --build build -j "$jobs"
ctest --test-dir build --output-on-failure -j "$jobs"

cmake -S . -B build-sanitize -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DHANDLAB_WERROR=ON \
  -DHANDLAB_SANITIZE=ON -DHANDLAB_BUILD_APP=OFF -DHANDLAB_BUILD_BENCHMARKS=OFF
cmake --build build-sanitize -j "$jobs"
ctest --test-dir build-sanitize --output-on-failure -j "$jobs"
