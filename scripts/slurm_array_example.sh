#!/usr/bin/env bash
# One dabench experiment as a SLURM array job: a task per shard, then one job that merges them.
#
#   bash scripts/slurm_array_example.sh EXPERIMENT.ini N [OUT]
#
# run on a login node, from the dabench folder, submits
#   1. an array job of N tasks; task K runs
#        dabench run EXPERIMENT.ini --shard K/N --out OUT.shards/K --threads $SLURM_CPUS_PER_TASK --resume
#      (--resume: a task that is preempted and requeued continues its shard instead of
#      starting over; on a fresh folder it just starts);
#   2. a job that starts once every task has succeeded (--dependency=afterok) and runs
#        dabench merge OUT OUT.shards/1 ... OUT.shards/N
#      which checks that the N shards are one plan's, each once and complete, and writes the
#      trials.csv, summary.csv and meta.json of the unsharded run into OUT.
# OUT defaults to results/<experiment name>. Shard K holds the blocks of 8 trials numbered
# K-1, K-1+N, K-1+2N, ... of the run (round robin, so every shard gets a share of each sweep
# point), so N up to (points x trials) / 8 keeps every task busy. If a task failed, resubmit
# just it (sbatch --array=K scripts/slurm_array_example.sh EXPERIMENT.ini N OUT), then run the
# merge by hand; `dabench merge` names any missing or unfinished shard.
#
# Adjust the #SBATCH lines (or pass sbatch options through SBATCH_* environment variables) to
# the cluster; DABENCH names the program (default ./build/dabench). Paths are passed quoted.
#SBATCH --job-name=dabench-shard
#SBATCH --cpus-per-task=4
#SBATCH --time=04:00:00
#SBATCH --requeue
#SBATCH --output=dabench-shard-%A_%a.log
set -euo pipefail
DABENCH=${DABENCH:-./build/dabench}

if [ -n "${SLURM_ARRAY_TASK_ID:-}" ]; then  # inside the array: run this task's shard
  experiment=$1 shards=$2 out=$3
  exec "$DABENCH" run "$experiment" --shard "$SLURM_ARRAY_TASK_ID/$shards" --out "$out.shards/$SLURM_ARRAY_TASK_ID" \
    --threads "${SLURM_CPUS_PER_TASK:-1}" --resume
fi

if [ $# -lt 2 ] || [ $# -gt 3 ]; then
  echo "usage: bash scripts/slurm_array_example.sh EXPERIMENT.ini N [OUT]" >&2
  exit 2
fi
experiment=$1 shards=$2
out=${3:-results/$(basename "$experiment" .ini)}
if ! [[ $shards =~ ^[1-9][0-9]*$ ]]; then
  echo "slurm_array_example.sh: N must be a positive integer, not '$shards'" >&2
  exit 2
fi
"$DABENCH" run --help >/dev/null  # fails early if DABENCH is not a dabench

array_job=$(sbatch --parsable --array="1-$shards" "$0" "$experiment" "$shards" "$out")
folders=()
for k in $(seq 1 "$shards"); do folders+=("$out.shards/$k"); done
merge_command=$(printf '%q ' "$DABENCH" merge "$out" "${folders[@]}")
merge_job=$(sbatch --parsable --dependency="afterok:${array_job%%;*}" --job-name=dabench-merge \
  --output=dabench-merge-%j.log --wrap "$merge_command")
echo "submitted array job $array_job ($shards shards of $experiment) and merge job $merge_job; results in $out"
