#!/usr/bin/env bash
# Installs the Debian packages stickslip needs, only those that are missing.
# Usage: scripts/deps.sh [test|demo|bench|all]   (all is the default)
# test: also Ninja (the suites' generator), Clang 14 (the sanitizer suite's compiler), pybind11, numpy and pytest (the Python
# module and its tests, docs/python.md), venv, setuptools, wheel and build (its pip install and wheel, offline) and
# Open MPI (the MPI sweep and its tests, docs/sweeps.md).
# bench: also Boost (odeint, headers) and SUNDIALS (CVODE) for the peer benchmark (scripts/peers.sh).
set -euo pipefail
what=${1:-all}
pkgs=(cmake g++ make libeigen3-dev libspectra-dev googletest libgtest-dev libbenchmark-dev)
case "$what" in
  test) pkgs+=(ninja-build clang-14 libclang-rt-14-dev python3-matplotlib python3-dev pybind11-dev python3-pybind11 python3-numpy python3-pytest
        python3-venv python3-setuptools python3-wheel python3-build libopenmpi-dev openmpi-bin) ;;
  demo) pkgs+=(python3-matplotlib) ;;
  all) pkgs+=(clang-14 libclang-rt-14-dev python3-matplotlib python3-dev pybind11-dev python3-pybind11 python3-numpy python3-pytest
              python3-venv python3-setuptools python3-wheel python3-build libopenmpi-dev openmpi-bin) ;;
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
