#!/usr/bin/env bash
# The whole test suite under AddressSanitizer and UndefinedBehaviorSanitizer (docs/development.md):
# a separate build directory (build-sanitize/, or $PFGEN_SANITIZE_BUILD_DIR) with
# -fsanitize=address,undefined, then every ctest test except the embedded and package ones
# (they cross-compile or install, and run no pfgen code of their own under the sanitizers). The
# Python module is not built: python3 would have to load the ASan runtime first; the library it
# calls is the commands', which the tests cover here.
# Any finding fails the test that made it: UBSan halts on its first error, ASan on any memory
# error, LeakSanitizer on a leak at exit. Plugins that `pfgen simulate` compiles at run time are
# built without sanitizers (default_plugin_flags) and dlopen()ed into the sanitized process, which
# works: the ASan runtime is in the main program, and plugin code simply goes unchecked.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
build="${PFGEN_SANITIZE_BUILD_DIR:-$root/build-sanitize}"
flags="-fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=undefined"
launcher=()
if command -v ccache >/dev/null; then launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache); fi

# Exported before the build too: catch_discover_tests runs the test program to list its tests.
export ASAN_OPTIONS="detect_leaks=1:strict_string_checks=1:check_initialization_order=1"
export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1"
# print_suppressions=0: the tests count the lines on stderr.
export LSAN_OPTIONS="suppressions=$root/scripts/sanitize-suppressions.txt:print_suppressions=0"

start=$(date +%s)
cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo "${launcher[@]}" \
  "-DCMAKE_CXX_FLAGS=$flags" "-DCMAKE_EXE_LINKER_FLAGS=-fsanitize=address,undefined" \
  "-DCMAKE_SHARED_LINKER_FLAGS=-fsanitize=address,undefined" -DPFGEN_BUILD_PYTHON=OFF >/dev/null
cmake --build "$build" -j"$(nproc)"
ctest --test-dir "$build" --output-on-failure -j"$(nproc)" -LE 'embedded|package' "$@"
echo "sanitize-tests: build and tests took $(( $(date +%s) - start )) s"
