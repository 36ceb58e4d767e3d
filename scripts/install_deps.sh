#!/usr/bin/env bash
# Installs the Debian packages treesketch needs, only those that are missing, and laz-perf from
# npm (the independent LAZ decoder the LAZ tests compare with) into .deps/laz-perf. Idempotent.
# Usage: scripts/install_deps.sh [--gui] [--fuzz]   (--gui adds the windowing/OpenGL packages and
# xvfb; --fuzz adds clang and its libFuzzer runtime, for `make fuzz` only). The Python module's
# packages (pybind11, NumPy, pytest, Matplotlib for the example) are added unless
# TREESKETCH_PYTHON=0.
set -euo pipefail
pkgs=(build-essential cmake pkg-config libeigen3-dev libembree-dev libtbb-dev libnanoflann-dev
      libcli11-dev nlohmann-json3-dev libgtest-dev libgmock-dev libbenchmark-dev)
gui=(libglfw3-dev libglew-dev libimgui-dev libstb-dev xvfb xauth libgl1-mesa-dri)
if [[ "${1:-}" == "--gui" || "${TREESKETCH_GUI:-1}" == "1" ]]; then pkgs+=("${gui[@]}"); fi
python=(python3-dev python3-pybind11 python3-numpy python3-pytest python3-matplotlib)
if [[ "${TREESKETCH_PYTHON:-1}" == "1" ]]; then pkgs+=("${python[@]}"); fi
fuzz=(clang libclang-rt-14-dev)
if [[ " $* " == *" --fuzz "* ]]; then pkgs+=("${fuzz[@]}"); fi
# node and npm for the LAZ oracle tests (Debian's packages, unless a node with its own npm is there)
if ! command -v node > /dev/null || ! command -v npm > /dev/null; then pkgs+=(nodejs npm); fi
missing=()
for p in "${pkgs[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]} > 0)); then
  echo "install_deps: installing ${missing[*]}" >&2
  SUDO=""
  if [[ $(id -u) -ne 0 ]]; then SUDO="sudo"; fi
  export DEBIAN_FRONTEND=noninteractive
  $SUDO apt-get update -qq
  $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi
# laz-perf 0.0.7 (the version that decoded ../shared/data/real/treels_spruce_decoded.xyz), where
# CMake's TS_LAZ_ORACLE_DIR looks by default. Without it the LAZ oracle tests skip, saying so.
oracle="${TREESKETCH_LAZ_ORACLE_DIR:-$(cd "$(dirname "$0")/.." && pwd)/.deps/laz-perf}"
if [[ ! -f "$oracle/node_modules/laz-perf/package.json" ]]; then
  echo "install_deps: npm install laz-perf@0.0.7 in $oracle" >&2
  mkdir -p "$oracle"
  (cd "$oracle" && npm install --no-audit --no-fund --silent laz-perf@0.0.7) ||
    echo "install_deps: npm install laz-perf failed; the LAZ oracle tests will be skipped" >&2
fi
