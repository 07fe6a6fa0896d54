#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# Set up, build in Release, and run the main job on a shipped input: post
# ISO 14649-11 Example 1 (samples/milling/example1.stp) to a Siemens 840D
# program with feature cycles, and print it.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
export CCACHE_BASEDIR="$PWD" CCACHE_NOHASHDIR=1
build="${STEPNC_BUILD_DIR:-build/release}"
cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release
cmake --build "$build" --target stepnc
"$build/cli/stepnc" post samples/milling/example1.stp --dialect siemens840d
