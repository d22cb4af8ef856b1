#!/usr/bin/env bash
# The whole test suite: install dependencies, build, run every Catch2 test through ctest, run
# Open MPI jobs on loopback (scripts/test_mpi.sh), inject faults (a full disk, SIGKILL; then
# --resume: scripts/test_faults.sh), then install into a temporary prefix and
# build and run examples/outside-project against it, then the suite under AddressSanitizer +
# UBSan, the fuzz targets and the runner's tests under ThreadSanitizer (scripts/test_sanitizers.sh).
set -euo pipefail
cd "$(dirname "$0")/.."
step() {  # step NAME COMMAND...: runs it, then prints how long it took
  local name=$1 start=$SECONDS
  shift
  "$@"
  echo "test: $name took $(( (SECONDS - start) / 60 )) min $(( (SECONDS - start) % 60 )) s"
}
step setup bash scripts/setup.sh
step build bash scripts/build.sh
step ctest ctest --test-dir build -j"$(nproc)" --output-on-failure
step test_mpi env DABENCH_PROGRESS=0 bash scripts/test_mpi.sh build
step test_faults bash scripts/test_faults.sh build
step test_outside_project bash scripts/test_outside_project.sh build
step test_sanitizers bash scripts/test_sanitizers.sh
echo "test: passed in $(( SECONDS / 60 )) min $(( SECONDS % 60 )) s"
