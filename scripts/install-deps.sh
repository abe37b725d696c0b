#!/usr/bin/env bash
# Installs every Debian 12 package handlab needs to build, test and run.
# Idempotent and non-interactive: when everything is present it installs nothing.
set -euo pipefail

packages=(
  # toolchain
  build-essential cmake ninja-build pkg-config clang-format ccache
  # Qt 6: widgets, OpenGL widgets, SVG, WebSockets (+ test module in qt6-base-dev)
  qt6-base-dev qt6-base-dev-tools libqt6opengl6-dev qt6-svg-dev qt6-websockets-dev
  qt6-qpa-plugins libgl-dev
  # offscreen OpenGL rendering
  libosmesa6-dev zlib1g-dev
  # numerics, meshing, storage, distributions
  libeigen3-dev libtet1.5-dev libsqlite3-dev sqlite3 libboost-math-dev
  # tests and benchmarks (Bullet: the simulator's peer benchmark, docs/performance.md)
  libgtest-dev libgmock-dev libbenchmark-dev libbullet-dev
  # GUI and report checks
  xvfb xauth poppler-utils
  # the Slurm test: a single-node cluster on this machine (scripts/slurm-local.sh)
  slurm-wlm munge
  # scripts/cluster-plan.py (the planning table of docs/cluster.md)
  python3
  # OpenXR and Vulkan: the headers (their loaders are opened at run time where a headset is
  # asked for), and what the `openxr` test's runtime, Monado, needs to build and run headless
  # with Vulkan on the CPU (scripts/build-monado.sh, tests/openxr)
  libopenxr-dev libopenxr-loader1 libvulkan-dev glslang-tools mesa-vulkan-drivers
  libx11-xcb-dev libxrandr-dev libxcb-randr0-dev libcjson-dev libbsd-dev libudev-dev libegl-dev
  libwayland-dev wayland-protocols libdrm-dev
  # the Debian package: its checks, and the clean Debian 12 root it is tested in
  # (scripts/package.sh, tests/package/package-test.sh)
  lintian mmdebstrap
)

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q '^install ok installed$'; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#packages[@]} packages present"
  exit 0
fi

echo "install-deps: installing ${missing[*]}"
sudo=""
if [ "$(id -u)" -ne 0 ]; then sudo="sudo"; fi
export DEBIAN_FRONTEND=noninteractive
$sudo apt-get update -qq
$sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
echo "install-deps: done"
