#!/usr/bin/env bash
# The live path measured in the app (docs/performance.md, "The live Leap path"): a real
# recording served as the Leap service serves a device (WebSocket JSON v6 on loopback, at
# the recording's own frame rate, looped), a participant's session started in the app on
# the soft hand with the live Leap tracker, and after the first trial's warm-up SECONDS of
# latency (frame arrival to the picture on screen), dropped frames and display rate,
# written as JSON to OUT. Without a display it runs under xvfb-run.
#   scripts/live-latency.sh [RECORDING=data/leap/pinch-57fps.json.lz] [SECONDS=30]
#                           [OUT=build/live-latency.json] [extra handlab options...]
set -euo pipefail
cd "$(dirname "$0")/.."
recording=${1:-data/leap/pinch-57fps.json.lz} seconds=${2:-30} out=${3:-build/live-latency.json}
shift $(( $# < 3 ? $# : 3 ))
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build --target handlab handlab-cli -j "$(nproc)" >/dev/null
work=$(mktemp -d)
trap 'kill "$server" 2>/dev/null || true; rm -rf "$work"' EXIT
db="$work/live.db"
build/app/handlab-cli study create --protocol studies/fine-manipulation-2021.json --db "$db" >/dev/null
build/app/handlab-cli participant add --db "$db" --id P01 --age 30 --sex X --handedness right \
  --hand-length 0.18 --vr-experience none >/dev/null
port=$((20000 + RANDOM % 20000))
build/app/handlab --serve-recording "$recording" --port "$port" &
server=$!
sleep 1
run=(build/app/handlab --study "$db" --participant P01 --tracker leap --world soft
     --leap-address "ws://127.0.0.1:$port" --start --measure-latency "$seconds"
     --latency-json "$out" "$@")
export HOME="$work"  # the app's settings (recent files) stay out of the user's
if [ -n "${DISPLAY:-}" ]; then
  "${run[@]}"
else
  xvfb-run -a -s "-screen 0 1400x900x24" "${run[@]}"
fi
cat "$out"
