#!/usr/bin/env bash
# Configures and builds pfgen (Release) into build/ (or $PFGEN_BUILD_DIR), with the test suite and
# the Python module: everything the README's test command runs. Arguments are targets to build
# instead of all (`scripts/build.sh pfgen`).
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
build="${PFGEN_BUILD_DIR:-$root/build}"
# Said each time: the main job configures the same directory without them (scripts/main-job.sh).
cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=Release -DPFGEN_BUILD_TESTS=ON -DPFGEN_BUILD_PYTHON=ON >/dev/null
targets=()
for target in "$@"; do targets+=(--target "$target"); done
cmake --build "$build" -j"$(nproc)" "${targets[@]}"
