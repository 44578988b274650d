#!/usr/bin/env bash
# Installs the Debian 12 packages stiction needs, only when some are missing, so that
# repeated `make test` runs stay fast. Idempotent; uses sudo when not root.
set -euo pipefail

packages=(
  build-essential cmake pkg-config git
  petsc-dev                 # PETSc 3.18 with MUMPS, hypre, SuiteSparse, SuperLU
  libhypre-dev              # hypre's own header and library (pulled in by petsc-dev; used directly)
  libscotch-dev             # Scotch's header and library (pulled in by petsc-dev; its random state is reset directly)
  libopenblas0-pthread      # mandatory: reference BLAS makes MUMPS 3-9x slower
  libopenmpi-dev openmpi-bin
  libeigen3-dev
  googletest libgtest-dev libgmock-dev
  libbenchmark-dev
  libgmsh-dev               # Gmsh 4.8 C++ API (OpenCASCADE)
  libtomlplusplus-dev
  libcli11-dev
  libfmt-dev
  libboost-dev
  nlohmann-json3-dev        # record/replay metadata
  zlib1g-dev                # zlib: compressed binary VTU output
  gnuplot-nox               # report plots (SVG), drawn by `stiction report` and the report scripts
  python3-matplotlib        # headless PNG of contact states (scripts/render-contact-states.py)
  libmumps-ptscotch-5.5     # MUMPS with Scotch, preloaded by hand for the ordering comparison (docs/method.md)
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  exit 0
fi

echo "install-deps: installing ${missing[*]}" >&2
sudo=""
if [ "$(id -u)" -ne 0 ]; then sudo="sudo"; fi
export DEBIAN_FRONTEND=noninteractive
$sudo apt-get update -qq
$sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
