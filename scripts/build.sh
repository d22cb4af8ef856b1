#!/usr/bin/env bash
# Configures and builds dabench (Release, -O3) into ./build: everything (the program and its MPI
# module, the Python package build/python/dabench for Debian's /usr/bin/python3, the tests and the
# benchmarks), or only the targets named, e.g. `scripts/build.sh dabench` (the program and its MPI module).
# A new build folder uses Ninja where it is installed (an existing one keeps its generator); every
# compilation goes through ccache where it is installed (CMakeLists.txt, DABENCH_CCACHE).
set -euo pipefail
cd "$(dirname "$0")/.."
generator=()
[ -f build/CMakeCache.txt ] || ! command -v ninja > /dev/null || generator=(-G Ninja)
cmake "${generator[@]}" -S . -B build -DCMAKE_BUILD_TYPE=Release -DPython3_EXECUTABLE=/usr/bin/python3 >/dev/null
targets=()
for target in "$@"; do targets+=(--target "$target"); done
cmake --build build -j"$(nproc)" "${targets[@]}"
