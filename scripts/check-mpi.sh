#!/usr/bin/env bash
# The optional MPI build (docs/guide/mpi.md): installs Debian's Open MPI
# when missing, configures build-mpi/ (or $PFGEN_MPI_BUILD_DIR) with -DPFGEN_WITH_MPI=ON, builds
# pfgen and the MPI tests, and runs them (`ctest -L mpi`: mpirun -n 2 against the single process).
# Not part of scripts/run-tests.sh: the default build and CI need no MPI.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
build="${PFGEN_MPI_BUILD_DIR:-$root/build-mpi}"
missing=()
for p in libopenmpi-dev openmpi-bin; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  SUDO=""
  if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
  $SUDO apt-get update
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y --no-install-recommends "${missing[@]}"
fi
cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=Release -DPFGEN_WITH_MPI=ON >/dev/null
cmake --build "$build" -j"$(nproc)" --target pfgen pfgen_mpi_tests
ctest --test-dir "$build" --output-on-failure -L mpi
