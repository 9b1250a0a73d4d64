#!/usr/bin/env bash
# The README's main job, as far as pfgen goes today: install missing packages,
# build, derive paper 000's example filters (Basin, Perez, Skliar 2006, eqs
# 21-26), print them, typeset them as a PDF and generate their C++. Simulation against a truth
# comes with the runtime (issue 5).
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
"$root/scripts/install-deps.sh"
"$root/scripts/build.sh"
build="${PFGEN_BUILD_DIR:-$root/build}"
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
