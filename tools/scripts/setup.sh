#!/usr/bin/env bash
# Installs the Debian 12 packages kneesim needs (idempotent) and builds it in Release into build/.
# `setup.sh --packages-only [PACKAGE...]` installs them and the extra packages (e.g. clang for
# fuzz.sh) without building.
set -euo pipefail
cd "$(dirname "$0")/../.."
packages=(build-essential cmake libeigen3-dev libsundials-dev libfcl-dev libccd-dev
  libassimp-dev doctest-dev libtomlplusplus-dev libcli11-dev nlohmann-json3-dev
  libopenmpi-dev openmpi-bin python3-matplotlib
  calculix-ccx chromium libjs-three libssl-dev)
# calculix-ccx: the independent FE cross-check of the deformable insert; chromium: the report's
# browser test; libjs-three: the report's 3D view (inlined, nothing fetched at view time);
# libssl-dev: SHA-256 of the input files in the report's provenance
packages_only=0
if [ "${1:-}" = "--packages-only" ]; then
  packages_only=1
  shift
  packages+=("$@")
fi
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  sudo_cmd=""; [ "$(id -u)" -ne 0 ] && sudo_cmd="sudo"
  $sudo_cmd apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo_cmd apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi
[ $packages_only -eq 1 ] && exit 0
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build -j"$(nproc)"
