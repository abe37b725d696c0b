#!/usr/bin/env bash
# Runs K simulated N-participant studies of the ISMAR 2021 protocol on the soft hand (seeds
# FIRST, FIRST+1, ...) and sets them side by side with the paper's results (`handlab-cli
# replications`: per condition the trials completed; per test the statistic and p of each
# study, their median and range, and how many studies found it). A study already in OUT is
# not rerun. docs/simulated-participants.md, "A simulated study" and "Studies side by side".
#   scripts/simulated-studies.sh [K=10] [N=20] [FIRST=1] [OUT=build/simulated-studies]
set -euo pipefail
cd "$(dirname "$0")/.."
k=${1:-10} n=${2:-20} first=${3:-1} out=${4:-build/simulated-studies}
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build --target handlab-cli -j "$(nproc)" >/dev/null
mkdir -p "$out"
studies=()
for ((s = first; s < first + k; ++s)); do
  db="$out/study-n$n-seed$s.db"
  if [ ! -f "$db" ]; then
    # Written under another name and renamed when whole: an interrupted study is run again.
    rm -f "$db.running"*
    build/app/handlab-cli simulate --protocol studies/fine-manipulation-2021.json \
      --participants "$n" --seed "$s" --world soft --db "$db.running" \
      --json "$out/study-n$n-seed$s.simulate.json"
    mv "$db.running" "$db"
  fi
  studies+=("$db")
done
build/app/handlab-cli replications "${studies[@]}" \
  --published studies/fine-manipulation-2021-published.json --json "$out/replications.json"
