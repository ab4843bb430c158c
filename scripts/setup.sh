#!/usr/bin/env bash
# One-time machine set-up for scpdyn (idempotent: every step whose result is present is skipped).
#  1. Debian packages: compilers, Open MPI, METIS, parallel HDF5, yaml-cpp, GoogleTest,
#     Google Benchmark, Python plotting (h5py, matplotlib), gmsh, ccache.
#  2. Kokkos 3.4.1 with OpenMP + Serial, built from Debian's Trilinos 13.2 source package
#     (Debian's binary Kokkos is Serial-only) into a cache prefix outside the repository.
# Prints the Kokkos prefix on the last line of stdout.
set -euo pipefail

CACHE_ROOT="${SCPDYN_CACHE:-${XDG_CACHE_HOME:-$HOME/.cache}/scpdyn}"
KOKKOS_PREFIX="$CACHE_ROOT/kokkos-3.4.1-openmp"
TRILINOS_VERSION="13.2.0-4"

log() { echo "[setup] $*" >&2; }
die() { echo "[setup] ERROR: $*" >&2; exit 1; }

SUDO=""
if [ "$(id -u)" != 0 ]; then SUDO="sudo"; fi

PACKAGES=(
  g++ cmake make ccache pkg-config dpkg-dev
  libopenmpi-dev openmpi-bin
  libmetis-dev
  libhdf5-openmpi-dev
  libyaml-cpp-dev
  libgtest-dev libgmock-dev
  libbenchmark-dev
  python3 python3-numpy python3-h5py python3-matplotlib python3-meshio
  gmsh
)

missing_packages() {
  local p missing=()
  for p in "${PACKAGES[@]}"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
  done
  echo "${missing[@]:-}"
}

apt_updated=0
apt_update_once() {
  if [ "$apt_updated" = 0 ]; then
    log "apt-get update"
    $SUDO apt-get update -qq >&2 || die "apt-get update failed"
    apt_updated=1
  fi
}

# ---- 1. Debian packages --------------------------------------------------------------------
missing=$(missing_packages)
if [ -n "$missing" ]; then
  apt_update_once
  log "installing: $missing"
  # shellcheck disable=SC2086
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends $missing >&2 \
    || die "apt-get install failed for: $missing"
fi

# ---- 2. Kokkos with OpenMP ------------------------------------------------------------------
if [ -f "$KOKKOS_PREFIX/.scpdyn-complete" ]; then
  log "Kokkos (OpenMP+Serial) present at $KOKKOS_PREFIX"
  echo "$KOKKOS_PREFIX"
  exit 0
fi

SRC_LIST=/etc/apt/sources.list.d/scpdyn-deb-src.sources
if ! grep -rqs "^Types:.*deb-src" /etc/apt/sources.list.d/ && ! grep -qs "^deb-src" /etc/apt/sources.list; then
  # Derive a deb-src stanza from the machine's own Debian entry (same URIs and keyring).
  base=/etc/apt/sources.list.d/debian.sources
  [ -f "$base" ] || die "no $base to derive a deb-src entry from; add a deb-src line for bookworm main by hand"
  uris=$(awk '/^URIs:/{print $2; exit}' "$base")
  key=$(awk '/^Signed-By:/{print $2; exit}' "$base")
  [ -n "$uris" ] || die "could not read URIs from $base"
  log "adding deb-src entry derived from $base"
  printf 'Types: deb-src\nURIs: %s\nSuites: bookworm\nComponents: main\nSigned-By: %s\n' "$uris" "$key" \
    | $SUDO tee "$SRC_LIST" >/dev/null
  apt_updated=0
fi
apt_update_once

WORK="$CACHE_ROOT/kokkos-build"
mkdir -p "$WORK"
cd "$WORK"
if ! ls trilinos_13.2.0.orig.tar.* >/dev/null 2>&1; then
  log "downloading Debian source package trilinos=$TRILINOS_VERSION"
  apt-get source --download-only "trilinos=$TRILINOS_VERSION" >&2 || die "apt-get source trilinos=$TRILINOS_VERSION failed"
fi
tarball=$(ls trilinos_13.2.0.orig.tar.* | head -n1)
if [ ! -d kokkos-src ]; then
  log "extracting packages/kokkos from $tarball"
  rm -rf extract && mkdir extract
  tar -xf "$tarball" -C extract --wildcards '*/packages/kokkos/*' || die "could not extract Kokkos from $tarball"
  mv extract/*/packages/kokkos kokkos-src
  rm -rf extract
fi
log "configuring Kokkos (OpenMP + Serial, C++17, Release)"
rm -rf build
cmake -S kokkos-src -B build -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_STANDARD=17 \
  -DCMAKE_CXX_COMPILER=g++ -DKokkos_ENABLE_OPENMP=ON -DKokkos_ENABLE_SERIAL=ON \
  -DKokkos_ENABLE_TESTS=OFF -DBUILD_SHARED_LIBS=OFF -DCMAKE_POSITION_INDEPENDENT_CODE=ON \
  -DCMAKE_INSTALL_PREFIX="$KOKKOS_PREFIX" >&2 || die "Kokkos configure failed"
log "building Kokkos"
cmake --build build -j"$(nproc)" >&2 || die "Kokkos build failed"
cmake --install build >&2 || die "Kokkos install failed"
touch "$KOKKOS_PREFIX/.scpdyn-complete"
rm -rf build kokkos-src "$WORK"/trilinos_*
log "Kokkos installed at $KOKKOS_PREFIX"
echo "$KOKKOS_PREFIX"
