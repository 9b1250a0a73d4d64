#!/usr/bin/env bash
# Installs the Debian 12 packages pfgen needs that are not installed yet (apt-get update first).
# Needs root, or sudo when not root.
#   install-deps.sh main   what the README's main job runs: the pfgen program, pdflatex, gnuplot
#   install-deps.sh        everything: the main job's, and what the tests, the Python module and
#                          the embedded proof build and run
set -euo pipefail
main_job=(
  g++ make cmake pkg-config            # toolchain (simulate compiles its plugin with g++ too)
  libginac-dev libcln-dev              # symbolic derivation
  libeigen3-dev                        # numerics in the validator and the simulation runtime
  libyaml-cpp-dev libcli11-dev         # model files, command line
  libnlopt-dev                         # `pfgen fit`: the likelihood's maximisation
  texlive-latex-base                   # pdflatex for `pfgen latex` documents
  gnuplot-nox                          # `pfgen simulate --plot` (error plots, PNG via cairo or SVG)
)
tests=(
  clang                                # tests compile generated code with clang++ as well as g++
  catch2                               # tests
  python3-dev pybind11-dev             # the Python module (python/), built with pybind11
  python3-numpy python3-sympy python3-pytest  # its arrays, Filter.to_sympy, and its tests
  python3-pandas python3-matplotlib    # its optional Simulation.to_pandas and Simulation.plot (tested)
  python3-statsmodels                  # tests: exact Kalman likelihoods and fits to check `fit` against
  python3-yaml                         # benchmarks/bench_sympy_peer.py reads model files (SymPy peer)
  poppler-utils                        # pdftoppm: tests render LaTeX pages to check the layout
  gcc-arm-none-eabi libnewlib-arm-none-eabi libstdc++-arm-none-eabi-newlib  # embedded proof:
  qemu-system-arm                      # Cortex-M4F cross-compiler and emulator (embedded-check.sh)
)
# The Rust backend's tests compile its output with rustc: Debian's (1.63, the oldest the generated
# code keeps to) unless one is on PATH already (rustup's, for instance).
if ! command -v rustc >/dev/null 2>&1; then tests+=(rustc); fi
case "${1:-all}" in
  main) packages=("${main_job[@]}") ;;
  all) packages=("${main_job[@]}" "${tests[@]}") ;;
  *) echo "install-deps: unknown set '$1' (main or all)" >&2; exit 2 ;;
esac
missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all Debian packages present"
  exit 0
fi
echo "install-deps: installing ${missing[*]}"
SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
$SUDO apt-get update
DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y --no-install-recommends "${missing[@]}"
