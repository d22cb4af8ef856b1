#!/usr/bin/env bash
# Open MPI runs (docs/clusters.md, "Running on a cluster: Open MPI"), on loopback:
#  - a small experiment of each problem kind under `mpirun -np 2` (1 thread per rank) and
#    `-np 3` (2 threads per rank) writes the files of a single-process run (scripts/same_results.py:
#    every CSV field but the timings; meta.json records ranks, threads per rank and hosts);
#  - shards run under mpirun (`--shard K/N` of a multi-scan and a tracking run), merged, equal it too;
#  - mpirun interrupted (SIGINT, as Ctrl-C) stops after the blocks in flight, says how to resume,
#    and --resume under mpirun ends with the files of an uninterrupted run;
#  - a rank killed mid-run aborts the job, and --resume loses nothing that was written;
#  - a missing experiment is one error line from rank 0, and dabench without mpirun never
#    loads the MPI module.
# Usage: tests/scripts/mpi.sh [BUILD_DIR]   (default build; needs openmpi-bin, see scripts/setup.sh)
set -euo pipefail
cd "$(dirname "$0")/../.."
root=$(pwd)
build=$(cd "${1:-build}" && pwd)
dabench="$build/dabench"
[ -f "$build/libdabench_mpi.so" ] || { echo "test_mpi: $build/libdabench_mpi.so missing (configure with libopenmpi-dev installed)"; exit 1; }
mpirun=(mpirun --allow-run-as-root --oversubscribe)
python=/usr/bin/python3
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"

quiet() {  # quiet LOG COMMAND...: runs it, shows its output only when it fails
  local log=$1; shift
  "$@" > "$log" 2>&1 || { cat "$log"; echo "test_mpi: failed: $*"; exit 1; }
}
same() {  # same() EXPECTED ACTUAL: CSVs equal timings aside (quiet unless different)
  "$python" "$root/scripts/same_results.py" "$1" "$2" > same.log || { cat same.log; echo "test_mpi: $2 differs from $1"; exit 1; }
}
meta_field() { "$python" -c 'import json,sys; print(json.dumps(json.load(open(sys.argv[1]))[sys.argv[2]]))' "$1/meta.json" "$2"; }
expect() {  # expect WHAT ACTUAL EXPECTED
  [ "$2" = "$3" ] || { echo "test_mpi: $1: got $2, expected $3"; exit 1; }
}

# The system tests' experiments, with fewer trials: each runs three ways here.
cp "$root"/tests/data/experiments/{single,multi,tracking,tbd,long}.ini .
declare -A trials=([single]=25 [multi]=10 [tracking]=4 [tbd]=10 [long]=3500)
for name in "${!trials[@]}"; do sed -i "s/^trials = .*/trials = ${trials[$name]}/" $name.ini; done

for kind in single multi tracking tbd; do
  quiet run.log "$dabench" run $kind.ini --out $kind-1 --threads 1
  quiet run.log "${mpirun[@]}" -np 2 "$dabench" run $kind.ini --out $kind-np2 --threads 1
  quiet run.log "${mpirun[@]}" -np 3 "$dabench" run $kind.ini --out $kind-np3 --threads 2
  for run in np2 np3; do
    same $kind-1 $kind-$run
    expect "$kind-$run files" "$(ls $kind-$run | tr '\n' ' ')" "$(ls $kind-1 | tr '\n' ' ')"
  done
  expect "$kind-np3 ranks" "$(meta_field $kind-np3 ranks)" 3
  expect "$kind-np3 rank_threads" "$(meta_field $kind-np3 rank_threads)" "[2, 2, 2]"
  expect "$kind-np2 status" "$(meta_field $kind-np2 status)" '"complete"'
  echo "test_mpi: $kind: -np 2 and -np 3 equal the single-process run"
done

# Shards under mpirun: each shard's (item, algorithm) units spread over the ranks; merged, the
# shards are the single-process run.
for kind in multi tracking; do
  for k in 1 2 3; do
    quiet run.log "${mpirun[@]}" -np 2 "$dabench" run $kind.ini --shard $k/3 --out $kind-shard-$k --threads 2
  done
  quiet run.log "$dabench" merge $kind-merged $kind-shard-1 $kind-shard-2 $kind-shard-3
  same $kind-1 $kind-merged
  echo "test_mpi: $kind: 3 shards, each under mpirun -np 2, merged: equal to the single-process run"
done

# long.ini at 3500 trials: long enough to interrupt (mpirun takes up to a second to pass a signal
# on), about 3 s on two cores.
quiet run.log "$dabench" run long.ini --out long-1 --threads 2

wait_for_rows() {  # wait_for_rows FOLDER: until its trials.csv holds some blocks
  for _ in $(seq 1 600); do
    [ -f "$1/trials.csv" ] && [ "$(wc -l < "$1/trials.csv")" -gt 1 ] && return 0
    sleep 0.05
  done
  echo "test_mpi: no rows appeared in $1"; exit 1
}

# Ctrl-C: mpirun passes it on; rank 0 finishes the blocks in flight and prints the resume command.
"${mpirun[@]}" -np 2 "$dabench" run long.ini --out long-int --threads 1 2> int.log &
job=$!
wait_for_rows long-int
kill -INT $job
status=0; wait $job || status=$?
rows=$(($(wc -l < long-int/trials.csv) - 1))
[ "$rows" -lt $((2 * 3500 * 3)) ] || { echo "test_mpi: the run finished before the interrupt"; exit 1; }
# mpirun's own status for a job it was told to stop is 1 (each rank exits 130, as dabench does alone).
expect "interrupted mpirun exit status" "$status" 1
# Where rank 0 drew the progress line (progress_under_mpirun) its carriage returns share the
# text line with the resume line: split on them before matching the line's start.
tr '\r' '\n' < int.log | grep -q "^dabench: interrupted after [0-9]* of 7000 trials; finish with: mpirun -np 2 .* --resume$" ||
  { echo "test_mpi: no resume line after Ctrl-C: $(tail -c 300 int.log)"; exit 1; }
quiet run.log "${mpirun[@]}" -np 2 "$dabench" run long.ini --out long-int --threads 1 --resume
same long-1 long-int
expect "long-int resumed" "$(meta_field long-int resumed)" true
echo "test_mpi: interrupted at $rows rows, resumed under mpirun: equal to the uninterrupted run"

# A rank dies: mpirun aborts the job; --resume keeps what was written and ends identical.
"${mpirun[@]}" -np 3 "$dabench" run long.ini --out long-kill --threads 1 2> kill.log &
job=$!
wait_for_rows long-kill
victim=""
for pid in $(pgrep -f "dabench run long.ini --out long-kill"); do
  if tr '\0' '\n' < /proc/$pid/environ 2> /dev/null | grep -qx "OMPI_COMM_WORLD_RANK=2"; then victim=$pid; fi
done
[ -n "$victim" ] || { echo "test_mpi: rank 2 not found"; exit 1; }
written=$(cat long-kill/trials.csv)
kill -KILL "$victim"
status=0; wait $job || status=$?
[ "$status" -ne 0 ] || { echo "test_mpi: mpirun exited 0 after a rank was killed"; exit 1; }
case "$(cat long-kill/trials.csv)" in
  "$written"*) ;;
  *) echo "test_mpi: rows written before the kill changed"; exit 1 ;;
esac
quiet run.log "${mpirun[@]}" -np 2 "$dabench" run long.ini --out long-kill --threads 1 --resume
same long-1 long-kill
echo "test_mpi: rank 2 killed, job aborted, resumed: equal to the uninterrupted run"

# Errors: one line, from rank 0 only; without mpirun the module is never loaded.
status=0; "${mpirun[@]}" -np 2 "$dabench" run missing.ini 2> err.log > /dev/null || status=$?
[ "$status" -ne 0 ] || { echo "test_mpi: a missing experiment exited 0"; exit 1; }
expect "error lines from the ranks" "$(grep -c '^dabench: ' err.log)" 1
status=0; DABENCH_MPI_MODULE=/nonexistent/libdabench_mpi.so "$dabench" run single.ini --out plain --threads 1 2> err.log || status=$?
expect "plain run with no module" "$status" 0
status=0; OMPI_COMM_WORLD_SIZE=1 DABENCH_MPI_MODULE=/nonexistent/libdabench_mpi.so "$dabench" run single.ini --out x 2> err.log || status=$?
expect "missing module exit status" "$status" 2
expect "missing module message lines" "$(wc -l < err.log)" 1
echo "test_mpi: all passed"
