#!/usr/bin/env bash
# Configures and builds a Clang 14 build folder with sanitizers (-O1 -g1, asserts on; -O1 compiles
# in half -O2's time; no benchmarks, no MPI module, no Python module), for scripts/test_sanitizers.sh and scripts/fuzz.sh.
# The libraries are unity builds (their files compiled in batches, each header parsed once per
# batch) and programs link with lld: both only to build faster. Ninja and ccache as in build.sh.
# Usage: scripts/sanitizer_build.sh FOLDER SANITIZERS [CMAKE_OPTION...] [--target T...]
#   e.g. scripts/sanitizer_build.sh build-asan "address;undefined" -DDABENCH_BUILD_FUZZERS=ON
set -euo pipefail
cd "$(dirname "$0")/.."
folder=$1 sanitizers=$2
shift 2
options=() targets=()
while [ $# -gt 0 ]; do
  if [ "$1" = --target ]; then targets+=(--target "$2"); shift 2; else options+=("$1"); shift; fi
done
generator=()
[ -f "$folder/CMakeCache.txt" ] || ! command -v ninja > /dev/null || generator=(-G Ninja)
CC=clang-14 CXX=clang++-14 cmake "${generator[@]}" -S . -B "$folder" -DCMAKE_BUILD_TYPE=Sanitize -DCMAKE_CXX_FLAGS_SANITIZE="-O1 -g1" \
  -DDABENCH_SANITIZERS="$sanitizers" -DCMAKE_UNITY_BUILD=ON \
  -DCMAKE_EXE_LINKER_FLAGS=--ld-path=/usr/bin/ld.lld-14 -DDABENCH_BUILD_BENCHMARKS=OFF -DDABENCH_WITH_MPI=OFF -DDABENCH_BUILD_PYTHON=OFF "${options[@]}" > /dev/null
cmake --build "$folder" -j"$(nproc)" "${targets[@]}" > "$folder/build.log" 2>&1 || { tail -40 "$folder/build.log"; exit 1; }
