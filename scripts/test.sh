#!/usr/bin/env bash
# Installs what is missing, builds handlab with warnings as errors, and runs the whole test
# suite: once in the Release build, once more with AddressSanitizer and UBSan (Qt-free parts).
set -euo pipefail
cd "$(dirname "$0")/.."
jobs=$(nproc)

scripts/install-deps.sh

# No test may replace a device: /dev/null as it was before the suite, checked at the end.
null_before=$(stat -c '%F %t:%T %i' /dev/null)
check_dev_null() {
  if [ "$(stat -c '%F %t:%T %i' /dev/null)" != "$null_before" ]; then
    echo "test.sh: /dev/null is no longer the device it was ($(stat -c '%F' /dev/null))" >&2
    exit 1
  fi
  echo "test.sh: /dev/null is still the character device it was"
}

# The Release tree is scripts/run.sh's (the same preset): after run.sh nothing is rebuilt.
cmake --preset release
cmake --build build -j "$jobs"
cmake --preset sanitize

# The sanitizer tree builds while the Release tests run, at the lowest priority: the tests
# leave part of the cores idle (Slurm's daemons, Xvfb, child processes waited for) and the
# build takes what they leave, so the tests run as fast as alone.
build_log=build-sanitize/build.log
# Its own process group (job control on for the launch), so that a failed test stops the
# compilers too; not its own session (setsid), whose scheduler group would share the cores
# equally with the tests' whatever its nice value.
set -m
nice -n 19 cmake --build build-sanitize -j "$jobs" >"$build_log" 2>&1 &
build=$!
set +m
trap 'kill -- -"$build" 2>/dev/null || true' EXIT
ctest --test-dir build --output-on-failure -j "$jobs"
if ! wait "$build"; then
  cat "$build_log"
  echo "test.sh: the sanitizer build failed (its output above, and in $build_log)" >&2
  exit 1
fi
trap - EXIT
echo "test.sh: sanitizer tree built while the Release tests ran ($build_log)"
ctest --test-dir build-sanitize --output-on-failure -j "$jobs"
check_dev_null
