#!/usr/bin/env bash
# Builds Monado, the open-source OpenXR runtime the `openxr` tests run against, from its source
# tarball into a cache outside the source tree (once: a built cache is left as it is), and
# prints the runtime's manifest (for XR_RUNTIME_JSON). A test dependency, never part of handlab.
#
# The tarball: $HANDLAB_MONADO_TARBALL, else monado-598080453.tar.gz in shared/third_party
# beside this source tree or beside the tree it was cloned from.
set -euo pipefail
repo=$(cd "$(dirname "$0")/.." && pwd)
name=monado-598080453
sha256=887f990ab1ac7d9b9fdf2fef32fcc09d12b447c0aec28c76f33f8390a9f928d7
cache=${HANDLAB_MONADO_CACHE:-${XDG_CACHE_HOME:-$HOME/.cache}/handlab/$name}
manifest=$cache/build/openxr_monado-dev.json

if [ -f "$manifest" ] && [ -f "$cache/build/src/xrt/targets/openxr/libopenxr_monado.so" ]; then
  echo "$manifest"
  exit 0
fi

find_tarball() {
  if [ -n "${HANDLAB_MONADO_TARBALL:-}" ]; then echo "$HANDLAB_MONADO_TARBALL"; return; fi
  local origin
  origin=$(git -C "$repo" config --get remote.origin.url 2>/dev/null || true)
  for dir in "$repo/.." "${origin:+$origin/..}"; do
    [ -n "$dir" ] && [ -f "$dir/shared/third_party/$name.tar.gz" ] &&
      { echo "$dir/shared/third_party/$name.tar.gz"; return; }
  done
  return 1
}
tarball=$(find_tarball) || {
  echo "build-monado: $name.tar.gz not found (set HANDLAB_MONADO_TARBALL, or keep shared/third_party beside the source tree)" >&2
  exit 1
}
if ! echo "$sha256  $tarball" | sha256sum -c --status; then
  echo "build-monado: $tarball is not Monado $name (sha256 differs)" >&2
  exit 1
fi

echo "build-monado: building $name into $cache (about a minute on 2 cores)" >&2
rm -rf "$cache"
mkdir -p "$cache"
tar -xzf "$tarball" -C "$cache"
# The service off: the runtime loads into the application's process. No QWERTY driver (it
# needs SDL), no tests, no docs.
cmake -S "$cache/$name" -B "$cache/build" -G Ninja -DCMAKE_BUILD_TYPE=Release \
  -DXRT_FEATURE_SERVICE=OFF -DXRT_BUILD_DRIVER_QWERTY=OFF -DBUILD_TESTING=OFF -DBUILD_DOC=OFF \
  >"$cache/configure.log" 2>&1 || { cat "$cache/configure.log" >&2; exit 1; }
ninja -C "$cache/build" >"$cache/build.log" 2>&1 || { tail -50 "$cache/build.log" >&2; exit 1; }
echo "$manifest"
