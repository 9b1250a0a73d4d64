#!/usr/bin/env bash
# Fuzzes the model loader and the derivation for SECONDS (default 60): builds fuzz/fuzz_model.cpp
# with clang++ and libFuzzer in build-fuzz/ (or $PFGEN_FUZZ_BUILD_DIR), seeds it with
# examples/*.yaml and tests/data/bad/*.yaml, and runs it with a time limit per input and a memory
# limit. Findings (crash-*, timeout-*, oom-*) go to build-fuzz/findings/; each one becomes a
# fixture in tests/data/bad with its expected message in tests/test_bad_input.cpp.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
seconds="${1:-60}"
target="${2:-model}"  # model, or record: the record reader and RecordRun (fuzz/fuzz_record.cpp)
build="${PFGEN_FUZZ_BUILD_DIR:-$root/build-fuzz}"
launcher=()
if command -v ccache >/dev/null; then launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache); fi
cmake -S "$root" -B "$build" -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=RelWithDebInfo "${launcher[@]}" \
  -DPFGEN_BUILD_FUZZERS=ON -DPFGEN_BUILD_TESTS=OFF >/dev/null
if [ "$target" = record ]; then
  # Seeds: the example records; findings go to build-fuzz/findings-record/.
  cmake --build "$build" -j"$(nproc)" --target pfgen_fuzz_record
  mkdir -p "$build/corpus-record" "$build/seeds-record" "$build/findings-record"
  for f in "$root"/examples/records/*.csv; do head -c 4096 "$f" > "$build/seeds-record/$(basename "$f")"; done
  exec env ASAN_OPTIONS=detect_leaks=0 "$build/fuzz/pfgen_fuzz_record" "$build/corpus-record" "$build/seeds-record" \
    -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -max_len=4096 \
    -artifact_prefix="$build/findings-record/" -print_final_stats=1
fi
cmake --build "$build" -j"$(nproc)" --target pfgen_fuzz_model
mkdir -p "$build/corpus" "$build/seeds" "$build/findings"
cp "$root"/examples/*.yaml "$root"/tests/data/bad/*.yaml "$build/seeds/"
# tests/data: user filters with define:, delayed and sampled test models, sums inside products.
for f in "$root"/tests/data/*.yaml; do cp "$f" "$build/seeds/data_$(basename "$f")"; done
for f in "$root"/examples/*/*.yaml; do cp "$f" "$build/seeds/$(basename "$(dirname "$f")")_$(basename "$f")"; done
# The first directory collects new inputs; the seeds are read only.
# -timeout 10: a model that takes longer to load and derive is a finding (a missing limit);
# -rss_limit_mb 2048: so is one that needs more memory; detect_leaks=0: a leak is not a finding here
# (scripts/sanitize-tests.sh checks leaks on the test suite).
ASAN_OPTIONS=detect_leaks=0 "$build/fuzz/pfgen_fuzz_model" "$build/corpus" "$build/seeds" \
  -dict="$root/fuzz/model.dict" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -max_len=4096 \
  -artifact_prefix="$build/findings/" -print_final_stats=1
