#!/usr/bin/env bash
# The whole test suite: install dependencies, build, run every Catch2 test through ctest, run
# Open MPI jobs on loopback (scripts/test_mpi.sh), inject faults (a full disk, SIGKILL; then
# --resume: scripts/test_faults.sh), then install into a temporary prefix and
# build and run examples/outside-project against it, then the suite under AddressSanitizer +
# UBSan, the fuzz targets and the runner's tests under ThreadSanitizer (scripts/test_sanitizers.sh).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
bash scripts/build.sh
(cd build && ctest -j"$(nproc)" --output-on-failure)
DABENCH_PROGRESS=0 bash scripts/test_mpi.sh build
bash scripts/test_faults.sh build
bash scripts/test_outside_project.sh build
bash scripts/test_sanitizers.sh
