#!/usr/bin/env bash
# Installs every Debian package erythro needs, non-interactively. Idempotent: when
# everything is present it installs nothing and does not touch the network.
set -euo pipefail

PACKAGES=(
  build-essential cmake git
  libeigen3-dev libhdf5-dev hdf5-tools
  libtomlplusplus-dev libcli11-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  python3 python3-numpy python3-scipy python3-matplotlib python3-h5py python3-sympy
  paraview python3-paraview   # the output test opens run.xdmf with ParaView's XDMF reader (pvbatch)
  clang libomp-dev            # ci/fuzz.sh: libFuzzer is clang's; OpenMP for clang is libomp
)
# Optional: headless Chromium to look at the V&V report (reports/screenshot.sh).
if [[ ${ERYTHRO_BROWSER:-0} == 1 ]]; then
  PACKAGES+=(chromium)
fi

missing=()
for p in "${PACKAGES[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [[ ${#missing[@]} -eq 0 ]]; then
  echo "install-deps: all ${#PACKAGES[@]} packages present"
  exit 0
fi

echo "install-deps: installing ${missing[*]}"
SUDO=""
if [[ $(id -u) -ne 0 ]]; then SUDO="sudo"; fi
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
