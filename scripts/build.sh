#!/usr/bin/env bash
# Configures and builds dabench (Release, -O3) into ./build: the CLI, tests and benchmarks.
set -euo pipefail
cd "$(dirname "$0")/.."
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build -j"$(nproc)"
