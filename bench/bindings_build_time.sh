#!/usr/bin/env bash
# Build time of the generated ISO 14649 bindings (generated/), Release, -j2,
# in a fresh build directory without ccache. The runtime library is built
# first and timed as the baseline of the same run.
#
#   bench/bindings_build_time.sh [BUILD_DIR]   (default: a temporary directory)
set -euo pipefail
cd "$(dirname "$0")/.."
build="${1:-$(mktemp -d /tmp/stepnc-bindings-build.XXXXXX)}"
cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_COMPILER_LAUNCHER= \
  -DSTEPNC_BUILD_TESTS=OFF -DSTEPNC_BUILD_BENCH=OFF > /dev/null
seconds() { local start=$(date +%s.%N); "$@" > /dev/null; echo "$(date +%s.%N) - $start" | bc; }
runtime=$(seconds cmake --build "$build" -j2 --target stepnc_runtime)
bindings=$(seconds cmake --build "$build" -j2 --target stepnc_iso14649)
lines=$(cat generated/*.h generated/*.cc | wc -l)
printf 'runtime library (baseline): %6.1f s\n' "$runtime"
printf 'ISO 14649 bindings:         %6.1f s  (%s lines in %s files; goal < 60 s)\n' \
  "$bindings" "$lines" "$(ls generated/*.h generated/*.cc | wc -l)"
printf 'ratio bindings/runtime:     %6.2f\n' "$(echo "$bindings / $runtime" | bc -l)"
