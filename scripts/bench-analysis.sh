#!/usr/bin/env bash
# Times handlab's full analysis of the 2x2x5 design at N = 20 and N = 10,000 and, in the same
# run and on the same data, R's (afex + emmeans). Installs R from Debian if it is missing.
set -euo pipefail
cd "$(dirname "$0")/.."
if ! command -v Rscript >/dev/null || ! Rscript -e 'library(afex); library(emmeans)' >/dev/null 2>&1; then
  sudo=""; [ "$(id -u)" -ne 0 ] && sudo="sudo"
  $sudo env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends \
    r-base-core r-cran-afex r-cran-emmeans r-cran-car >/dev/null
fi
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build --target handlab_bench -j "$(nproc)" >/dev/null
tmp=$(mktemp -d)
for n in 20 10000; do build/tests/bench/handlab_bench --write-study-csv "$tmp/study_$n.csv" "$n"; done
taskset -c 0 build/tests/bench/handlab_bench --benchmark_filter=FullStudyAnalysis --benchmark_repetitions=5 \
  --benchmark_report_aggregates_only=true
Rscript scripts/bench_analysis.R "$tmp/study_20.csv" 20
Rscript scripts/bench_analysis.R "$tmp/study_10000.csv" 5
rm -rf "$tmp"
