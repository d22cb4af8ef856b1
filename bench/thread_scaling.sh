#!/usr/bin/env bash
# Thread scaling of a dabench run (trials/s with 2 threads over 1), next to the scaling the
# machine itself delivers for two independent CPU-bound processes at the same moment: on
# shared or virtual machines the second CPU is not always really there, and a run cannot
# scale better than that.
#   usage: bash bench/thread_scaling.sh [EXPERIMENT.ini] [TRIALS]
set -euo pipefail
cd "$(dirname "$0")/.."
experiment=${1:-experiments/readme/bp-throughput.ini}
trials=${2:-10000}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

spin() { /usr/bin/python3 - <<'PY'
import time
t = time.perf_counter(); x = 1
for _ in range(6_000_000): x = (x * 6364136223846793005 + 1442695040888963407) & 0xFFFFFFFFFFFFFFFF
print(time.perf_counter() - t)
PY
}
one=$(spin)
two=$( (spin & spin & wait) | sort -n | tail -1)
machine=$(/usr/bin/python3 -c "print(f'{2 * $one / $two:.2f}')")

run() {
  local start end
  start=$(date +%s.%N)
  ./build/dabench run "$experiment" --trials "$trials" --threads "$1" --out "$out/t$1" --force 2>/dev/null
  end=$(date +%s.%N)
  /usr/bin/python3 -c "print($end - $start)"
}
t1=$(run 1)
t2=$(run 2)
/usr/bin/python3 - "$t1" "$t2" "$machine" "$out" <<'PY'
import json, sys
t1, t2, machine, out = float(sys.argv[1]), float(sys.argv[2]), sys.argv[3], sys.argv[4]
fractions = [json.load(open(f"{out}/t{k}/meta.json"))["work_fraction"] for k in (1, 2)]
print(f"machine: two independent processes run {machine}x as fast as one")
print(f"dabench: 1 thread {t1:.2f} s, 2 threads {t2:.2f} s -> {t1 / t2:.2f}x")
print(f"work_fraction (share of thread time in scenario + algorithms): {fractions[0]:.3f} / {fractions[1]:.3f}")
PY
