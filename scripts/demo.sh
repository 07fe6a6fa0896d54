#!/usr/bin/env bash
# Set up, build in Release, and run the main job on a shipped input:
# compile the ISO 14649 schemas in schemas/ and print what expressc understood.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
build="${STEPNC_BUILD_DIR:-build/release}"
cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release
cmake --build "$build" --target expressc
"$build/expressc/expressc" --summary schemas/*.exp
