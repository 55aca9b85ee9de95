#!/usr/bin/env bash
# Installs the Debian packages stickslip needs, only those that are missing.
# Usage: scripts/deps.sh [test|demo|bench|all]   (all is the default)
# bench: also Boost (odeint, headers) and SUNDIALS (CVODE) for the peer benchmark (scripts/peers.sh).
set -euo pipefail
what=${1:-all}
pkgs=(cmake g++ make libeigen3-dev libspectra-dev googletest libgtest-dev libbenchmark-dev)
case "$what" in
  demo|all) pkgs+=(python3-matplotlib) ;;
  bench) pkgs+=(libboost-dev libsundials-dev) ;;
esac
missing=()
for p in "${pkgs[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "stickslip: installing missing Debian packages: ${missing[*]}"
  SUDO=""
  if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
  export DEBIAN_FRONTEND=noninteractive
  $SUDO apt-get update -qq
  $SUDO apt-get install -y --no-install-recommends "${missing[@]}"
fi
