#!/usr/bin/env bash
# Installs every build, test and plot dependency of dabench from Debian packages (clang-14 and
# its runtimes and linker for the sanitizer builds and libFuzzer targets of scripts/test_sanitizers.sh;
# pybind11, numpy, pandas and pytest for the Python module in python/).
# Idempotent; run as root (or with sudo available). Nothing else is downloaded.
set -euo pipefail
packages=(
  g++ cmake make ninja-build ccache pkg-config
  libeigen3-dev libboost-program-options-dev libfmt-dev
  catch2 libbenchmark-dev
  libopenmpi-dev openmpi-bin
  python3-matplotlib python3-numpy python3-scipy python3-pandas python3-pytest python3-dev pybind11-dev
  python3-venv python3-pip python3-setuptools python3-wheel mkdocs pyflakes3
  clang-14 libclang-rt-14-dev libomp-14-dev llvm-14 lld-14
)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "setup: all dependencies present"
  exit 0
fi
SUDO=""
[ "$(id -u)" -eq 0 ] || SUDO="sudo"
echo "setup: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
echo "setup: done"
