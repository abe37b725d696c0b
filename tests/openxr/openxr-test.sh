#!/usr/bin/env bash
# handlab against a real OpenXR runtime: Monado (scripts/build-monado.sh builds it once into a
# cache), its null compositor and Vulkan on the CPU (lavapipe).
#  1. the simulated headset: `xr list` finds the runtime and its headset; `xr hands` says in
#     one line that it tracks no hands; `xr show` draws the task scene into both eyes'
#     swapchains, paced by the runtime, and reads each image back before releasing it: the
#     cube where each eye's projection puts it, every frame as drawn, the session ended cleanly;
#     `session run --display headset` shows a scripted participant's two trials there;
#  2. the remote driver, fed two hands over its TCP socket by remote_hands.c (built against
#     Monado's own header): `xr hands` records them through XR_EXT_hand_tracking at 120 Hz, and
#     the tracked skeleton fits the joints the runtime gives (`tracking info --fit`);
#  3. a session on the remote driver's right hand, held open: `session run --tracker openxr`
#     calibrates with the open palm and runs two trials in real time, their frames logged at
#     120 Hz and exported as a Leap session's are; then the same in the headset, the hands
#     from the headset's own session, and the time from a hand frame to the headset showing it.
#  4. the app (GUI_TESTS, the gui_tests executable): the headset chosen in its session panel
#     runs one trial there.
# Usage: openxr-test.sh HANDLAB_CLI SOURCE_DIR WORK_DIR [GUI_TESTS]
set -euo pipefail
cli=$1 source=$2 work=$3 gui_tests=${4:-}
rm -rf "$work" && mkdir -p "$work"
fail() { echo "openxr-test: $*" >&2; exit 1; }
driver=""
trap '[ -n "$driver" ] && kill "$driver" 2>/dev/null || true' EXIT

manifest=$("$source/scripts/build-monado.sh") || fail "Monado could not be built (above)"
monado=$(dirname "$(dirname "$manifest")")
export XR_RUNTIME_JSON=$manifest XRT_COMPOSITOR_NULL=1 XRT_LOG=warning
export VK_ICD_FILENAMES=/usr/share/vulkan/icd.d/lvp_icd.x86_64.json
[ -f "$VK_ICD_FILENAMES" ] || fail "no lavapipe ($VK_ICD_FILENAMES: mesa-vulkan-drivers)"
json_has() { grep -q -- "$2" "$1" || fail "$1 lacks $2: $(cat "$1")"; }
# A study of tests/openxr/headset-protocol.json (two 2-second trials) with one participant.
new_study() {
  "$cli" study create --protocol "$source/tests/openxr/headset-protocol.json" --db "$1" >/dev/null
  "$cli" participant add --db "$1" --id P1 --age 30 --sex F --handedness right \
    --hand-length 0.18 --vr-experience none >/dev/null
}

# app_test FILTER NAME: the gui_tests FILTER under Xvfb; each eye's last image kept in $work/NAME.
app_test() {
  mkdir -p "$work/$2"
  command -v xvfb-run >/dev/null || fail "no xvfb-run (xvfb: scripts/install-deps.sh)"
  HANDLAB_HEADSET_SCREENSHOTS=$work/$2 QT_QPA_PLATFORM=xcb \
    xvfb-run -a -s "-screen 0 1280x1024x24" timeout 300 "$gui_tests" --gtest_filter="$1" \
    >"$work/$2.txt" 2>&1 ||
    fail "the app, $1: $(grep -m5 -E 'Failure|rror|Expected|Which is|Actual' "$work/$2.txt")"
  grep -qE '\[  PASSED  \] [1-9][0-9]* test' "$work/$2.txt" ||
    fail "the app's $1 did not run: $(tail -3 "$work/$2.txt")"
  for eye in left right; do
    [ -s "$work/$2/app-eye-$eye.png" ] || fail "no picture of the app's $eye eye in $2"
  done
  grep -h '^headset' "$work/$2.txt" || fail "the app's $1 printed no headset figures"
}

# 1. The simulated headset.
export XDG_CONFIG_HOME=$work/simulated SIMULATED_ENABLE=1
"$cli" xr list --json "$work/list.json" >"$work/list.txt" 2>"$work/list.log" ||
  fail "xr list: $(tail -1 "$work/list.log")"
json_has "$work/list.json" '"runtime_name": "Monado'
json_has "$work/list.json" '"name": "Monado: Simulated HMD"'
json_has "$work/list.json" '"hand_tracking_extension": true'
json_has "$work/list.json" '"tracks_hands": false'
if "$cli" xr hands --seconds 1 >"$work/none.txt" 2>"$work/none.log"; then
  fail "xr hands ran on a runtime without hands"
fi
grep -q '^handlab-cli xr: the OpenXR runtime tracks no left hand' "$work/none.log" ||
  fail "xr hands without hands: $(cat "$work/none.log")"
"$cli" xr show --seconds 2 --screenshot "$work/eyes" --json "$work/show.json" \
  >"$work/show.txt" 2>"$work/show.log" || fail "xr show: $(tail -1 "$work/show.log")"
python3 - "$work/show.json" <<'EOF' || fail "xr show: $(cat "$work/show.json")"
import json, sys
r = json.load(open(sys.argv[1]))
n = r["frames_drawn"]
assert n >= 10, r
# Every frame waited for once, begun once and ended once; at most the first not drawn.
assert r["frames_waited"] == r["frames_begun"] == r["frames_ended"], r
assert r["frames_ended"] - n <= 1, r
assert r["cube_seen_left"] == n and r["cube_seen_right"] == n, r
assert r["read_back_as_drawn"] == n, r
assert r["end_state"] == "exiting", r
# The cameras against the world: the cube, nearer than infinity, further right in the left eye
# than in the right; the table below the eyes, in the pictures' lower half.
(lx, ly), (rx, ry) = r["cube_pixel_left"], r["cube_pixel_right"]
assert lx > rx, r
assert ly > r["eye_height"] / 2 and ry > r["eye_height"] / 2, r
EOF
for eye in left right; do
  [ -s "$work/eyes/eye-$eye.png" ] || fail "no picture of the $eye eye's swapchain image"
done
cmp -s "$work/eyes/eye-left.png" "$work/eyes/eye-right.png" &&
  fail "both eyes' images are the same: no stereo"
new_study "$work/shown.db"
timeout 120 "$cli" session run --db "$work/shown.db" --participant P1 --display headset \
  --json "$work/shown.json" >"$work/shown.txt" 2>"$work/shown.log" ||
  fail "session run --display headset: $(tail -1 "$work/shown.log")"
python3 - "$work/shown.json" <<'EOF' || fail "session run --display headset: $(cat "$work/shown.json")"
import json, sys
r = json.load(open(sys.argv[1]))
assert r["trials_run"] == 2 and r["schedule_complete"], r
h = r["headset"]
n = h["frames_shown"]
assert n >= 20, h  # two 2-second trials in real time, at the runtime's pace
assert h["frames_waited"] == h["frames_begun"] == h["frames_ended"], h
assert h["read_back_as_drawn"] == n, h
# The cube where each eye's projection puts it, but where the hand covers its centre.
assert h["cube_seen_left"] >= n / 2 and h["cube_seen_right"] >= n / 2, h
EOF
# The app: the headset chosen in its session panel, one trial shown there (a QTest of the real
# widgets under Xvfb, tests/app/app_headset_test.cpp).
if [ -n "$gui_tests" ]; then app_test 'AppHeadset.*' simulated; fi
unset SIMULATED_ENABLE

# 2. The remote driver, two hands over its socket.
# A port no one listens on (the remote driver's hub binds it in handlab's process).
port=$(python3 -c 'import socket; s = socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])')
mkdir -p "$work/remote/monado"
echo "{\"active\": \"remote\", \"remote\": {\"version\": 0, \"port\": $port, \"view_count\": 2}}" \
  >"$work/remote/monado/config_v0.json"
export XDG_CONFIG_HOME=$work/remote
remote=$monado/monado-598080453/src/xrt
cc -O2 -I"$remote/drivers/remote" -I"$remote/include" -I"$remote/auxiliary" \
  "$source/tests/openxr/remote_hands.c" -lm -o "$work/remote_hands"
"$work/remote_hands" "$port" 5 &
driver=$!
"$cli" xr hands --seconds 3 --out "$work/hands.hlrec" --json "$work/hands.json" \
  >"$work/hands.txt" 2>"$work/hands.log" || fail "xr hands: $(tail -1 "$work/hands.log")"
wait "$driver" || fail "the remote driver's client failed"
json_has "$work/hands.json" '"runtime_name": "Monado'
python3 - "$work/hands.json" <<'EOF' || fail "xr hands: $(cat "$work/hands.json")"
import json, sys
r = json.load(open(sys.argv[1]))
# 3 s at 120 Hz; a loaded machine (the suite runs two tests at once) delays some frames.
assert 280 <= r["frames"] <= 400, r
assert 95 <= r["frame_rate_hz"] <= 121, r
assert r["left_hands"] >= 280 and r["right_hands"] >= 280, r
EOF
"$cli" tracking info "$work/hands.hlrec" --fit --json "$work/fit.json" >"$work/fit.txt" ||
  fail "tracking info of the recorded hands"
python3 - "$work/fit.json" <<'EOF' || fail "the fit of the runtime's hands: $(cat "$work/fit.json")"
import json, sys
r = json.load(open(sys.argv[1]))
# The fingers closed and opened: the thumb's tip came within 3 cm of the index's and went 9 cm off.
assert r["thumb_index_mm"]["min"] < 30 and r["thumb_index_mm"]["max"] > 90, r
fits = {f["side"]: f for f in r["fit"]}
for side in ("left", "right"):
    f = fits[side]
    assert f["frames"] >= 280, f
    assert f["residual_mean_mm"] < 2.0 and f["residual_max_mm"] < 10.0, f  # 1.2 and 6.3 mm
EOF
# 3. A session with OpenXR hands.
new_study "$work/study.db"
"$work/remote_hands" "$port" 30 open &
driver=$!
timeout 120 "$cli" session run --db "$work/study.db" --participant P1 --tracker openxr \
  --json "$work/session.json" >"$work/session.txt" 2>"$work/session.log" ||
  fail "session run --tracker openxr: $(tail -1 "$work/session.log")"
kill "$driver" 2>/dev/null || true
json_has "$work/session.json" '"trials_run": 2'
json_has "$work/session.json" '"schedule_complete": true'
"$cli" export --db "$work/study.db" --out "$work/export" --frames >/dev/null
python3 - "$work/export/frames.csv" <<'EOF' || fail "the session's frames: $(head -3 "$work/export/frames.csv")"
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
for manipulation in ("gross", "fine"):
    trial = [r for r in rows if r["manipulation"] == manipulation]
    assert len(trial) == 240, (manipulation, len(trial))  # 2 s at 120 Hz
    # A trial's first frames may come before the runtime locates the hand on a loaded machine:
    # no simulated hand yet (NA), a tenth of a second at most, and only before the first hand.
    first = next(k for k, r in enumerate(trial) if r["aperture"] != "NA")
    assert first <= 12, (manipulation, first)
    # The runtime's open hand, retargeted: the pads apart, the hand above the floor.
    hand = trial[first:]
    assert all(float(r["aperture"]) > 0.05 and float(r["index_tip_y"]) > 0.02 for r in hand), hand[0]
EOF
# The same in the headset: the hands from the headset's own session.
new_study "$work/both.db"
"$work/remote_hands" "$port" 30 open &
driver=$!
timeout 120 "$cli" session run --db "$work/both.db" --participant P1 --tracker openxr \
  --display headset --json "$work/both.json" >"$work/both.txt" 2>"$work/both.log" ||
  fail "session run --tracker openxr --display headset: $(tail -1 "$work/both.log")"
kill "$driver" 2>/dev/null || true
python3 - "$work/both.json" <<'EOF' || fail "hands and headset together: $(cat "$work/both.json")"
import json, sys
r = json.load(open(sys.argv[1]))
assert r["trials_run"] == 2 and r["schedule_complete"], r
h = r["headset"]
n = h["frames_shown"]
assert n >= 20 and h["read_back_as_drawn"] == n, h
assert h["cube_seen_left"] >= n / 2 and h["cube_seen_right"] >= n / 2, h
# From a hand frame (located at a frame's predicted display time) to the first frame showing
# it: at least one frame later; one of the runtime's 20 Hz frames on an idle machine, at most a
# few on a loaded one.
l = h["latency_ms"]
assert l["samples"] >= n / 2 and 0 < l["median"] <= 100 and l["max"] <= 300, l
EOF
# The app on the headset's own hands.
if [ -n "$gui_tests" ]; then
  "$work/remote_hands" "$port" 30 open &
  driver=$!
  app_test 'AppHeadsetHands.*' hands
  kill "$driver" 2>/dev/null || true
fi
cat "$work/show.txt" "$work/shown.txt" "$work/hands.txt" "$work/fit.txt" "$work/session.txt" \
  "$work/both.txt"
echo "openxr-test: passed"
