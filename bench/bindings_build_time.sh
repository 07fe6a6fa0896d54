#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# Build time of the generated ISO 14649 bindings (generated/), Release, -j2,
# without ccache. The runtime library is timed the same way as the baseline
# of the same run. Wall time depends on what else the machine runs; CPU
# time (user) is given too.
#
#   bench/bindings_build_time.sh [BUILD_DIR]   (default: a new temporary directory)
set -euo pipefail
cd "$(dirname "$0")/.."
build="${1:-$(mktemp -d /tmp/stepnc-bindings-build.XXXXXX)}"
export CCACHE_DISABLE=1  # compile for real even where ccache is the compiler launcher
cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DSTEPNC_BUILD_TESTS=OFF -DSTEPNC_BUILD_BENCH=OFF \
  > /dev/null
times="$build/build_times.txt"

# Times the compilation of a target's own objects (its dependencies are
# built first, untimed); appends "wall user" seconds to $times.
timed_build() {
  cmake --build "$build" -j2 --target "$1" > /dev/null
  find "$build" -path "*CMakeFiles/$1.dir/*.o" -delete
  /usr/bin/time -f "%e %U" -a -o "$times" cmake --build "$build" -j2 --target "$1" > /dev/null
}

: > "$times"
timed_build stepnc_runtime
timed_build stepnc_iso14649
read -r runtime_wall runtime_user < <(sed -n 1p "$times")
read -r bindings_wall bindings_user < <(sed -n 2p "$times")
printf 'runtime library (baseline): %6.1f s wall, %6.1f s CPU\n' "$runtime_wall" "$runtime_user"
printf 'ISO 14649 bindings:         %6.1f s wall, %6.1f s CPU (%s lines in %s files; goal < 60 s)\n' \
  "$bindings_wall" "$bindings_user" "$(cat generated/*.h generated/*.cc | wc -l)" \
  "$(ls generated/*.h generated/*.cc | wc -l)"
printf 'ratio bindings/runtime:     %6.2f (wall)\n' "$(echo "$bindings_wall / $runtime_wall" | bc -l)"
