#!/usr/bin/env bash
# Installs what is missing, builds handlab, and starts the desktop app. With no display it
# says so and draws the task scene headless into scene.png instead.
set -euo pipefail
cd "$(dirname "$0")/.."

scripts/install-deps.sh
cmake --preset release  # the tree scripts/test.sh builds and tests too (CMakePresets.json)
cmake --build build -j "$(nproc)"

if [ -n "${DISPLAY:-}" ] || [ -n "${WAYLAND_DISPLAY:-}" ]; then
  exec build/app/handlab "$@"
fi
echo "run.sh: no display; rendering the scene headless (start the app with: xvfb-run -a build/app/handlab)"
build/app/handlab-cli render --out scene.png
