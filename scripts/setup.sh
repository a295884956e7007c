#!/usr/bin/env bash
# Installs the Debian packages breastfit needs (only the missing ones), then configures and builds.
# Usage: scripts/setup.sh [--no-build] [--build-dir DIR] [--type Release|Debug|RelWithDebInfo]
set -euo pipefail

here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build_dir="$here/build"
build_type="Release"
do_build=1
while [ $# -gt 0 ]; do
  case "$1" in
    --no-build) do_build=0 ;;
    --build-dir) build_dir="$2"; shift ;;
    --type) build_type="$2"; shift ;;
    -h|--help) sed -n 2,3p "$0"; exit 0 ;;
    *) echo "setup.sh: unknown option '$1'" >&2; exit 2 ;;
  esac
  shift
done

packages=(
  build-essential cmake ninja-build pkg-config
  libeigen3-dev nlohmann-json3-dev libcli11-dev libtinygltf-dev libstb-dev
  libgtest-dev libgmock-dev libbenchmark-dev libnanoflann-dev
  python3-numpy python3-scipy python3-matplotlib
  libcpp-httplib-dev chromium
  pybind11-dev python3-dev python3-pytest python3-distributed
  zlib1g-dev libssl-dev libdeflate-dev nettle-dev
)

# Node.js and npm for the workstation's page: Debian's, unless a node with npm is already there
# (another distribution of Node.js may provide npm itself and conflict with Debian's package).
if ! command -v npm >/dev/null 2>&1; then packages+=(nodejs npm); fi

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -gt 0 ]; then
  echo "setup: installing missing Debian packages: ${missing[*]}"
  if [ "$(id -u)" -ne 0 ]; then
    if command -v sudo >/dev/null 2>&1; then SUDO=sudo; else
      echo "setup: not root and no sudo: install these packages as root first: ${missing[*]}" >&2
      exit 1
    fi
  else
    SUDO=""
  fi
  export DEBIAN_FRONTEND=noninteractive
  $SUDO apt-get update -qq
  $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
else
  echo "setup: all Debian packages present"
fi

# The workstation's page (three.js) and its browser test (playwright-core), pinned by
# web/package-lock.json. Playwright drives Debian's chromium: it downloads no browser.
echo "setup: npm ci in web/"
(cd "$here/web" && PLAYWRIGHT_SKIP_BROWSER_DOWNLOAD=1 npm ci --no-audit --no-fund --loglevel=error)

if [ "$do_build" = 1 ]; then
  cmake -S "$here" -B "$build_dir" -G Ninja -DCMAKE_BUILD_TYPE="$build_type"
  cmake --build "$build_dir" -j "$(nproc)"
fi
