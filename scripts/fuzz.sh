#!/usr/bin/env bash
# Builds the libFuzzer targets with clang (ASan + UBSan) and fuzzes the tracker input
# readers for SECONDS (default 300), starting from the real recordings and test vectors.
#   scripts/fuzz.sh [SECONDS]
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-300}
command -v clang++ >/dev/null || { echo "fuzz.sh: clang++ is needed (apt-get install clang libclang-rt-14-dev)"; exit 1; }
cmake -S . -B build-fuzz -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_C_COMPILER=clang \
  -DHANDLAB_FUZZ=ON -DHANDLAB_BUILD_APP=OFF -DHANDLAB_BUILD_TESTS=OFF -DHANDLAB_BUILD_BENCHMARKS=OFF >/dev/null
cmake --build build-fuzz --target leap_input_fuzz -j "$(nproc)"
corpus=build-fuzz/corpus
mkdir -p "$corpus"
cp data/leap/*.lz "$corpus"/ 2>/dev/null || true
python3 - "$corpus" <<'PY'
import json, sys, os
for i, v in enumerate(json.load(open('tests/data/lzstring/vectors.json'))):
    open(os.path.join(sys.argv[1], 'vector%d' % i), 'w').write(v['base64'])
PY
build-fuzz/tests/fuzz/leap_input_fuzz "$corpus" -max_total_time="$seconds" -max_len=65536 -timeout=10 -rss_limit_mb=4096 \
  -print_final_stats=1 2>&1 | tail -25
