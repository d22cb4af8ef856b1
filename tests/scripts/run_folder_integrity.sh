#!/usr/bin/env bash
# A run folder that two processes, a hand edit or a full pipe cannot corrupt unseen (issue 47),
# each case against BUILD_DIR/dabench:
#   - the folder lock: a second run, --resume, --force or merge on a folder in use refuses at
#     once with one line naming the holder; a lock left by a SIGKILLed run is taken over;
#   - stdout: every command's output to /dev/full or to a closed stdout is exit 1, one line;
#   - checksums: a row edited, cut short or deleted by hand is named by --resume and by merge
#     before anything is computed, and the folder is left as it was;
#   - merge: shards of another build are refused unless --allow-mixed (then recorded); a full
#     disk names the merged file and its reason, not a shard (needs root for a tmpfs);
#   - messages and statuses: SIGHUP, a deleted meta.json, a UTF-8 byte order mark, a 4 KiB path,
#     a path that is not UTF-8, a NUL byte in a weights file, compare/schedule on a killed run,
#     --force over a symbolic link, a full disk at start-up (exit 1), a read-only folder.
# Usage: run_folder_integrity.sh BUILD_DIR
set -euo pipefail
dabench=$(cd "$1" && pwd)/dabench
root=$(cd "$(dirname "$0")/../.." && pwd)
python=/usr/bin/python3
export DABENCH_PROGRESS=0
work=$(mktemp -d "${TMPDIR:-/tmp}/dabench-folder-XXXXXX")
cleanup() {
  for mounted in "$work"/tmpfs-*; do mountpoint -q "$mounted" 2> /dev/null && umount "$mounted"; done
  jobs -p | xargs -r kill -KILL 2> /dev/null || true
  rm -rf "$work"
}
trap cleanup EXIT
cd "$work"
fail() { echo "run_folder_integrity: FAILED: $*" >&2; exit 1; }
# refuses STATUS PATTERN COMMAND...: COMMAND exits STATUS with one line on stderr matching PATTERN.
refuses() {
  local status=$1 pattern=$2; shift 2
  local got=0
  "$@" > out.log 2> err.log || got=$?
  [ "$got" = "$status" ] || { cat err.log; fail "$* exited $got, not $status"; }
  [ "$(wc -l < err.log)" = 1 ] || { cat err.log; fail "$*: not one line on stderr"; }
  grep -qE -- "$pattern" err.log || { cat err.log; fail "$*: the line does not match '$pattern'"; }
}
same() { "$python" "$root/scripts/same_results.py" "$1" "$2" > same.log || { cat same.log; fail "$2 differs from $1"; }; }
digest() { find "$1" -type f ! -name .dabench.lock | sort | xargs sha1sum | sha1sum; }  # a dead run's lock is taken over

cp "$root"/tests/data/experiments/{grid,long}.ini .
sed -i "s/^trials = .*/trials = 4000/" long.ini  # long enough to interrupt, short enough to rerun
"$dabench" run grid.ini --out ref --threads 2 2> /dev/null
for k in 1 2; do "$dabench" run grid.ini --out shard$k --shard $k/2 --threads 1 2> /dev/null; done

# ---- the folder lock ---------------------------------------------------------------------------
"$dabench" run long.ini --out busy --threads 1 2> /dev/null &
holder=$!
for _ in $(seq 1 100); do [ -s busy/.dabench.lock ] && break; sleep 0.05; done
[ -s busy/.dabench.lock ] || fail "no lock file while a run is in progress"
in_use="^dabench: busy: in use by dabench pid $holder on .* since [0-9T:-]+Z \(run\); wait for it to end or stop it$"
refuses 2 "$in_use" "$dabench" run long.ini --out busy --resume
refuses 2 "$in_use" "$dabench" run long.ini --out busy --force
refuses 2 "$in_use" "$dabench" merge busy shard1 shard2 --force
{ kill -KILL "$holder" && wait "$holder"; } 2> /dev/null || true
[ -f busy/.dabench.lock ] || fail "a SIGKILLed run's lock file is gone (the stale-lock case is not tested)"
"$dabench" run long.ini --out busy --threads 2 --resume 2> resume.log || { cat resume.log; fail "--resume did not take over a dead run's lock"; }
[ ! -e busy/.dabench.lock ] || fail "the lock file stays after the run"
"$dabench" run long.ini --out long-ref --threads 2 2> /dev/null
same long-ref busy
# Two --resume at once: one runs, the other refuses; the files are an uninterrupted run's.
rm -rf twice && (timeout -s KILL 1 "$dabench" run long.ini --out twice --threads 1 2> /dev/null || true) 2> /dev/null
statuses=()
"$dabench" run long.ini --out twice --threads 1 --resume 2> first.log & first=$!
"$dabench" run long.ini --out twice --threads 1 --resume 2> second.log & second=$!
wait "$first" && statuses+=(0) || statuses+=($?)
wait "$second" && statuses+=(0) || statuses+=($?)
[ "$(printf '%s\n' "${statuses[@]}" | sort | tr '\n' ' ')" = "0 2 " ] ||
  { cat first.log second.log; fail "two --resume at once exited ${statuses[*]}, not 0 and 2"; }
grep -qh "in use by dabench pid" first.log second.log || { cat first.log second.log; fail "the refused --resume does not name the holder"; }
same long-ref twice
echo "run_folder_integrity: lock: a second run, --resume, --force and merge refused with the holder named; a dead run's lock taken over; two --resume at once: one ran"

# ---- stdout ------------------------------------------------------------------------------------
printf '0.5,0.2\n0.3,0.1\n' > weights.csv
for command in "--version" "--help" "list" "run --help" "solve --algorithm exact --weights weights.csv" \
               "compare ref --algorithms bp,exact" "schedule ref"; do
  refuses 1 "^dabench: standard output: write failed \(No space left on device\)$" bash -c "'$dabench' $command > /dev/full"
  refuses 1 "^dabench: standard output: write failed \(Bad file descriptor\)$" bash -c "'$dabench' $command >&-"
done
echo "run_folder_integrity: stdout: every command's output to /dev/full or a closed stdout is exit 1 with one line"

# ---- hand-edited rows --------------------------------------------------------------------------
(timeout -s KILL 1 "$dabench" run long.ini --out partial --threads 1 2> /dev/null || true) 2> /dev/null
[ "$(wc -l < partial/trials.csv)" -gt 200 ] || fail "the run to edit wrote too few rows in 1 s"
edited() {  # edited WHAT SED-SCRIPT LINE: --resume of a copy with SED-SCRIPT applied names LINE
  rm -rf copy && cp -r partial copy && sed -i "$2" copy/trials.csv
  local before
  before=$(digest copy)
  refuses 2 "^dabench: copy/trials.csv:$3: not the row written there .*; cannot resume \(use --force to start over\)$" \
    "$dabench" run long.ini --out copy --resume
  [ "$(digest copy)" = "$before" ] || fail "$1: the refused --resume changed the folder"
}
edited "a value changed" '100s/,0\./,1./' 100
edited "a row cut short" '120s/.\{12\}$//' 120
edited "a row deleted" '140d' 140
echo "run_folder_integrity: checksums: an edited, cut and deleted row each named by --resume (line 100, 120, 140), folder untouched"

# ---- merge -------------------------------------------------------------------------------------
cp -r shard1 bad1 && sed -i '7s/,0\./,1./' bad1/trials.csv
refuses 2 "^dabench: bad1/trials.csv:7: not the row the shard wrote" "$dabench" merge merged bad1 shard2
[ ! -e merged ] || fail "a refused merge left its output folder"
cp -r shard2 other2 && sed -i 's/"version": "[^"]*"/"version": "0.0.1"/' other2/meta.json
refuses 2 "^dabench: other2: shard 2/2 was written by dabench 0\.0\.1 .* by dabench .*; merge them with --allow-mixed" \
  "$dabench" merge merged shard1 other2
"$dabench" merge merged shard1 other2 --allow-mixed 2> /dev/null
"$python" - merged/meta.json << 'PY' || fail "merge --allow-mixed: meta.json does not record it"
import json, sys
meta = json.load(open(sys.argv[1]))
assert meta["allow_mixed"] is True and len(meta["shard_builds"]) == 2, meta
assert meta["shard_builds"][1].startswith("dabench 0.0.1 "), meta["shard_builds"]
PY
same ref merged
echo "run_folder_integrity: merge: an edited shard row named; another build refused, then merged with --allow-mixed recorded"

# ---- messages and statuses ---------------------------------------------------------------------
timeout -s HUP 1 "$dabench" run long.ini --out hup --threads 1 2> hup.log && status=0 || status=$?
grep -q '"status": "interrupted"' hup/meta.json || fail "after SIGHUP meta.json is not 'interrupted'"
grep -q "^dabench: interrupted after .* trials; finish with: .* --resume$" hup.log || { cat hup.log; fail "SIGHUP: no 'finish with' line"; }
cp -r hup killed && sed -i 's/"status": "interrupted"/"status": "running"/' killed/meta.json
refuses 2 "^dabench: compare: killed: the run is still running, or was killed \(meta.json\), not complete" \
  "$dabench" compare killed --algorithms bp,exact
refuses 2 "^dabench: schedule: hup: the run is interrupted \(meta.json\), not complete" "$dabench" schedule hup
rm hup/meta.json
refuses 2 "^dabench: hup: cannot resume: meta.json is missing" "$dabench" run long.ini --out hup --resume
printf '\xef\xbb\xbf' > bom.ini && cat grid.ini >> bom.ini
"$dabench" run bom.ini --out bom --threads 2 2> bom.log || { cat bom.log; fail "an experiment with a UTF-8 byte order mark is refused"; }
same ref bom
long_path=$(printf 'd%.0s/' $(seq 1 2100))
refuses 2 "^dabench: .{20,300} \.\.\. .*: cannot create output folder \(File name too long\)$" "$dabench" run grid.ini --out "$long_path"
[ "$(wc -c < err.log)" -lt 700 ] || fail "the message for a 4 KiB path is $(wc -c < err.log) bytes"
"$dabench" run grid.ini --out "$(printf 'latin\xe9')" --threads 2 2> /dev/null
"$python" -c "import json, sys; m = json.load(open(sys.argv[1], encoding='utf-8')); assert '\ufffd' in m['command_line'], m['command_line']" \
  "$(printf 'latin\xe9')/meta.json" || fail "meta.json of a path that is not UTF-8 is not valid JSON"
printf '0.5,ab\0cd\n' > nul.csv
refuses 2 "^dabench: nul.csv:1: column 2: 'ab\\\\x00cd' is not a number$" "$dabench" solve --algorithm exact --weights nul.csv
cp -r ref linked && mv linked/trials.csv precious.csv && ln -s "$work/precious.csv" linked/trials.csv
before=$(sha1sum < precious.csv)
"$dabench" run grid.ini --out linked --force --threads 2 2> /dev/null
[ "$(sha1sum < precious.csv)" = "$before" ] || fail "--force wrote through a symbolic link"
[ ! -L linked/trials.csv ] || fail "--force left trials.csv a symbolic link"
echo "run_folder_integrity: messages: SIGHUP interrupted with its resume line; killed runs refused by compare and schedule; meta.json missing named; BOM read; 4 KiB path shortened; Latin-1 path valid JSON; NUL shown; --force replaced a symlink"

if [ "$(id -u)" = 0 ] && mkdir tmpfs-full && mount -t tmpfs -o size=1m tmpfs tmpfs-full 2> /dev/null; then
  dd if=/dev/zero of=tmpfs-full/ballast bs=4096 count=255 2> /dev/null || true
  refuses 1 "^dabench: tmpfs-full/run/.*: write failed \(No space left on device\)$" "$dabench" run grid.ini --out tmpfs-full/run
  rm -rf tmpfs-full/run tmpfs-full/ballast
  bytes=$(cat shard1/trials.csv shard2/trials.csv | wc -c)
  dd if=/dev/zero of=tmpfs-full/ballast bs=4096 count=$(( 256 - 3 - bytes / 2 / 4096 )) 2> /dev/null || true
  refuses 1 "^dabench: tmpfs-full/merged/trials.csv.merging: write failed \(No space left on device\)$" \
    "$dabench" merge tmpfs-full/merged shard1 shard2
  rm -rf tmpfs-full/ballast tmpfs-full/merged && cp -r ref tmpfs-full/ro && mount -o remount,ro tmpfs-full
  refuses 1 "^dabench: tmpfs-full/ro/.dabench.lock: cannot create the folder's lock file \(Read-only file system\)$" \
    "$dabench" run grid.ini --out tmpfs-full/ro --force
  echo "run_folder_integrity: full disk: at start-up exit 1 naming the file; merge names its own file, not a shard; read-only folder: one line, exit 1"
else
  echo "run_folder_integrity: full-disk and read-only checks skipped: cannot mount a tmpfs here"
fi
echo "run_folder_integrity: all passed"
