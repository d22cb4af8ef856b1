#!/usr/bin/env bash
# cmake/build_info.cmake on a scratch git repository: a clean tree records its commit as clean,
# a change under results/ (run outputs, committed reference results) keeps it clean, a changed
# tracked source file or a new untracked one makes it modified, and outside git it is unknown.
# Usage: build_info_provenance.sh CMAKE BUILD_INFO_CMAKE
set -euo pipefail
cmake_bin=$1 script=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
repo=$work/repo
mkdir -p "$repo/results/study" "$repo/src"
git -C "$repo" init -q
echo 'int main() {}' >"$repo/src/main.cpp"
echo 'a,b' >"$repo/results/study/summary.csv"
git -C "$repo" add . && git -C "$repo" -c user.name=t -c user.email=t@t commit -qm init
commit=$(git -C "$repo" rev-parse HEAD)

state() {  # the Provenance the script writes for SOURCE_DIR=$1
  rm -f "$work/out.cpp"
  "$cmake_bin" -DSOURCE_DIR="$1" -DOUTPUT="$work/out.cpp" -DVERSION=0 -DCOMPILER=c -DFLAGS=f -DBUILD_TYPE=b -P "$script"
  grep -o 'Provenance::[a-z]*' "$work/out.cpp"
}
expect() {  # expect WHAT GOT WANT
  if [ "$2" != "$3" ]; then echo "FAIL: $1: got $2, want $3"; exit 1; fi
  echo "ok: $1: $2"
}

expect "clean tree" "$(state "$repo")" "Provenance::clean"
grep -q "\"$commit\"" "$work/out.cpp" || { echo "FAIL: commit $commit not recorded"; exit 1; }
echo 'a,b,c' >"$repo/results/study/summary.csv"
echo '{}' >"$repo/results/study/meta.json"
expect "results/ changed and added" "$(state "$repo")" "Provenance::clean"
echo '// edit' >>"$repo/src/main.cpp"
expect "tracked source changed" "$(state "$repo")" "Provenance::modified"
git -C "$repo" checkout -q -- src/main.cpp
echo 'int f();' >"$repo/src/new.cpp"
expect "untracked source file" "$(state "$repo")" "Provenance::modified"
rm "$repo/src/new.cpp"
expect "back to clean" "$(state "$repo")" "Provenance::clean"
mkdir "$work/plain"
expect "outside git" "$(state "$work/plain")" "Provenance::unknown"
grep -q '"unknown"' "$work/out.cpp" || { echo "FAIL: commit outside git not \"unknown\""; exit 1; }
