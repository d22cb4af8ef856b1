#!/usr/bin/env bash
# Faults that must lose nothing (issue 29):
#  - disk full: a run of each problem kind into a small tmpfs stops at the first failed write
#    with exit status 1 and one line naming the file, the system's reason and the --resume
#    command; every file holds whole rows (trials.csv whole items); after the space is freed,
#    that command ends with the files of an uninterrupted run. Needs root to mount tmpfs;
#    elsewhere it says so and skips these checks.
#  - SIGKILL at random moments (fixed seeds) of a threaded run and of an `mpirun` job (mpirun and
#    every rank at once, as a lost allocation), then --resume: the files of an uninterrupted run every time.
# Usage: tests/scripts/faults.sh [BUILD_DIR]   (default build)
set -euo pipefail
cd "$(dirname "$0")/../.."
root=$(pwd)
build=$(cd "${1:-build}" && pwd)
dabench="$build/dabench"
python=/usr/bin/python3
export DABENCH_PROGRESS=0
work=$(mktemp -d)
full="$work/full"
cleanup() {
  mountpoint -q "$full" 2> /dev/null && umount "$full"
  rm -rf "$work"
}
trap cleanup EXIT
cd "$work"

fail() { echo "test_faults: $*"; exit 1; }
same() {  # same EXPECTED ACTUAL: the same files, every CSV equal timings aside
  [ "$(ls "$1" | tr '\n' ' ')" = "$(ls "$2" | tr '\n' ' ')" ] || fail "$2 holds $(ls "$2" | tr '\n' ' '), not $(ls "$1" | tr '\n' ' ')"
  "$python" "$root/scripts/same_results.py" "$1" "$2" > same.log || { cat same.log; fail "$2 differs from $1"; }
}
whole_rows() {  # whole_rows FOLDER ROWS_PER_ITEM: every file ends with a newline, trials.csv holds whole items
  "$python" - "$1" "$2" << 'PY' || fail "$1: not whole rows"
import csv, os, sys
folder, per_item = sys.argv[1], int(sys.argv[2])
for name in sorted(os.listdir(folder)):
    if not name.endswith(".csv"):
        continue
    text = open(os.path.join(folder, name), newline="").read()
    assert text.endswith("\n"), f"{name}: cut inside a row"
    rows = list(csv.reader(text.splitlines()))
    assert all(len(row) == len(rows[0]) for row in rows), f"{name}: a row with a wrong field count"
    if name == "trials.csv":
        assert (len(rows) - 1) % per_item == 0, f"trials.csv: {len(rows) - 1} rows, not whole items of {per_item}"
PY
}

cp "$root"/tests/data/experiments/{single,multi,tracking,tbd,long}.ini .
declare -A per_item=([single]=3 [multi]=1 [tracking]=2 [tbd]=1)
for kind in single multi tracking tbd; do
  "$dabench" run $kind.ini --out $kind-ref --threads 2 2> /dev/null
done

# ---- disk full ---------------------------------------------------------------------------------
mkdir -p "$full"
if ! mount -t tmpfs -o size=4m tmpfs "$full" 2> mount.log; then
  echo "test_faults: disk-full checks skipped: cannot mount a tmpfs here ($(head -c 200 mount.log))"
else
  for kind in single multi tracking tbd; do
    # Room for a quarter, a half and three quarters of the run's bytes (tmpfs counts 4 KiB
    # pages; meta.json's replacement needs one more while it is written): the first failed write
    # falls on trials.csv or on a per-item file.
    bytes=$(cat $kind-ref/*.csv | wc -c)
    named=()
    for quarters in 1 2 3; do
      free_pages=$(( $(ls $kind-ref | wc -l) + 1 + bytes * quarters / 4 / 4096 ))
      rm -rf "${full:?}"/*
      dd if=/dev/zero of="$full/ballast" bs=4096 count=$(( 1024 - free_pages )) 2> /dev/null
      status=0
      "$dabench" run $kind.ini --out "$full/run" --threads 2 2> err.log || status=$?
      [ "$status" -eq 1 ] || { cat err.log; fail "$kind on a full disk: exit status $status, not 1"; }
      [ "$(wc -l < err.log)" -eq 1 ] || { cat err.log; fail "$kind on a full disk: not one line"; }
      grep -q "write failed (No space left on device) after .* trials (whole rows kept); free space, then finish with: .* --resume" err.log ||
        { cat err.log; fail "$kind on a full disk: the line does not name the reason and the resume command"; }
      named+=("$(sed -n 's|^dabench: .*/run/\([a-z.]*\): write failed.*|\1|p' err.log)")
      whole_rows "$full/run" "${per_item[$kind]}"
      rm "$full/ballast"
      resume=$(sed -n 's/.*then finish with: //p' err.log)
      eval "$resume" 2> resume.log || { cat resume.log; fail "$kind: resume after freeing space failed"; }
      same $kind-ref "$full/run"
    done
    if [ $kind != single ] && ! printf '%s\n' "${named[@]}" | grep -qv '^trials.csv$'; then
      fail "$kind: no disk-full attempt fell on a per-item file (${named[*]})"
    fi
    echo "test_faults: $kind: disk full at ${named[*]}: one line, whole rows; resumed: equal to the uninterrupted run"
  done
fi

# ---- SIGKILL at random moments ----------------------------------------------------------------
"$dabench" run long.ini --out long-ref --threads 2 2> /dev/null
kill_at() {  # kill_at DELAY COMMAND...: starts it, and after DELAY s SIGKILLs every process of it (mpirun and its ranks)
  local delay=$1; shift
  ("$@" > /dev/null 2>&1 || true) 2> /dev/null &  # its shell's "Killed" report goes nowhere
  local job=$!
  sleep "$delay"
  pkill -KILL -f "dabench run long.ini --out killed" || true  # the ranks are not in mpirun's process group
  wait "$job" || true
}
RANDOM=29  # fixed seed: the same moments on every run
mpirun=(mpirun --allow-run-as-root --oversubscribe)
for attempt in 1 2 3 4; do
  delay=$(printf '%d.%03d' $(( RANDOM % 2 )) $(( RANDOM % 1000 )))
  rm -rf killed
  kill_at "$delay" "$dabench" run long.ini --out killed --threads 2
  rows=$(( $( (cat killed/trials.csv 2> /dev/null || true) | wc -l) ))
  "$dabench" run long.ini --out killed --threads 2 --resume 2> resume.log || { cat resume.log; fail "resume after SIGKILL at ${delay} s failed"; }
  same long-ref killed
  echo "test_faults: threads: SIGKILL at ${delay} s (${rows} lines written), resumed: equal to the uninterrupted run"
done
if command -v mpirun > /dev/null && [ -f "$build/libdabench_mpi.so" ]; then
  for attempt in 1 2; do
    delay=$(printf '%d.%03d' $(( attempt )) $(( RANDOM % 1000 )))
    rm -rf killed
    kill_at "$delay" "${mpirun[@]}" -np 2 "$dabench" run long.ini --out killed --threads 1
    for _ in $(seq 1 50); do pgrep -f "dabench run long.ini --out killed" > /dev/null || break; sleep 0.1; done
    pgrep -f "dabench run long.ini --out killed" > /dev/null && fail "a rank survived SIGKILL"
    rows=$(( $( (cat killed/trials.csv 2> /dev/null || true) | wc -l) ))
    "${mpirun[@]}" -np 2 "$dabench" run long.ini --out killed --threads 1 --resume > /dev/null 2> resume.log ||
      { cat resume.log; fail "mpirun resume after SIGKILL at ${delay} s failed"; }
    same long-ref killed
    echo "test_faults: mpirun: SIGKILL of the job at ${delay} s (${rows} lines written), resumed: equal to the uninterrupted run"
  done
else
  echo "test_faults: mpirun checks skipped: no mpirun or no $build/libdabench_mpi.so"
fi
echo "test_faults: all passed"
