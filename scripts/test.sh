#!/usr/bin/env bash
# The whole test suite: install dependencies, build, run every Catch2 test through ctest.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
bash scripts/build.sh
cd build
ctest -j"$(nproc)" --output-on-failure
