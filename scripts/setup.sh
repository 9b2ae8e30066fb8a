#!/usr/bin/env bash
# Installs the Debian packages the project needs (idempotent; runs apt-get only when something is missing).
set -euo pipefail
PKGS=(g++ make cmake libocct-foundation-dev libocct-modeling-data-dev libocct-modeling-algorithms-dev
      libocct-data-exchange-dev libtbb-dev libeigen3-dev libboost-dev catch2 nlohmann-json3-dev
      freecad pybind11-dev python3-dev xvfb xauth clang libclang-rt-14-dev)
missing=()
for p in "${PKGS[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "setup: installing ${missing[*]}"
  SUDO=""; [ "$(id -u)" -ne 0 ] && SUDO=sudo
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi
