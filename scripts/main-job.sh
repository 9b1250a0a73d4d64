#!/usr/bin/env bash
# The README's main job: paper 000's example (Basin, Perez, Skliar 2006, section 4) end to end on
# a fresh machine. Installs missing packages, builds, derives the filters (eqs 21-26) and prints
# them, typesets them as a PDF, generates their C++, then compiles them with the truth into a
# plugin and runs the reproduction: 200 seeded runs to T = 9.2 of the optimal filter against the
# additive-noise filter, the textbook extended Kalman-Bucy filters and the paper's printed
# comparator. Ends with the summary table and the path of the error plot.
# It installs and builds only what it runs: the pfgen program (the test suite and the Python module
# are the test command's, scripts/run-tests.sh, which configures the same build directory with them).
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
"$root/scripts/install-deps.sh" main
build="${PFGEN_BUILD_DIR:-$root/build}"
cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=Release -DPFGEN_BUILD_TESTS=OFF -DPFGEN_BUILD_PYTHON=OFF >/dev/null
cmake --build "$build" -j"$(nproc)" --target pfgen
pfgen="$build/generator/pfgen"
model="$root/examples/basin2006_quadratic.yaml"
out="$build/main-job"
mkdir -p "$out"
for filter in optimal additive ekf-additive ekf ekf-printed; do
  echo "================================================================ $filter"
  "$pfgen" derive "$model" --filter "$filter"
done
"$pfgen" latex "$model" -o "$out/basin2006_quadratic.tex"
(cd "$out" && pdflatex -interaction=nonstopmode -halt-on-error basin2006_quadratic.tex >/dev/null)
echo "================================================================"
echo "LaTeX: $out/basin2006_quadratic.tex"
echo "PDF:   $out/basin2006_quadratic.pdf"
"$pfgen" codegen "$model" -o "$out/generated" --stats
echo "C++:   $out/generated/basin2006_quadratic/*.hpp"
echo "================================================================ simulation (Basin, Perez & Skliar 2006, section 4)"
# Settings from the model file's simulation: section (T = 9.2, dt = 1e-4, 200 runs, seed 1).
# The plugin is cached under the build directory; a second run starts at once.
"$pfgen" simulate "$model" --threads "$(nproc)" --cache-dir "$build/plugin-cache" \
  -o "$out/paper000.csv" --plot "$out/paper000_errors.png" --plot-ylim 10
