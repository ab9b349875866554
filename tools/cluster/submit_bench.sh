#!/bin/bash
# Submits a `foveal bench` sweep to Slurm: N array tasks (bench_array.sbatch, one shard
# each) and a merge job that runs when all of them have succeeded (and is cancelled if
# one fails). OUT_DIR must be on a file system every node sees. docs/bench.md.
# Usage: tools/cluster/submit_bench.sh [--wait] N OUT_DIR BENCH_OPTIONS...
#   --wait: return when the merge has finished, with its exit status.
# Extra sbatch options (partition, time, CPUs per task) go in SBATCH_* variables, e.g.
# SBATCH_PARTITION=gpu, SBATCH_TIMELIMIT=2:00:00 (they apply to the merge job too);
# FOVEAL_CPUS_PER_TASK (default 1) the CPUs of each shard; FOVEAL names the binary.
set -euo pipefail
here=$(dirname "$(readlink -f "$0")")
wait=()
if [[ ${1:-} == --wait ]]; then wait=(--wait); shift; fi
if (($# < 2)) || ! [[ $1 =~ ^[1-9][0-9]*$ ]]; then
  echo "usage: $0 [--wait] N OUT_DIR BENCH_OPTIONS..." >&2
  exit 2
fi
n=$1 out=$2
shift 2
# Absolute paths: a job may start elsewhere, with another PATH.
foveal=$(command -v "${FOVEAL:-foveal}") || { echo "$0: no foveal binary (set FOVEAL)" >&2; exit 2; }
foveal=$(readlink -f "$foveal")
mkdir -p "$out/logs"
out=$(readlink -f "$out")
array=$(sbatch --parsable --array=0-$((n - 1)) --cpus-per-task="${FOVEAL_CPUS_PER_TASK:-1}" --export=ALL,FOVEAL_SWEEP_OUT="$out",FOVEAL="$foveal" \
  --output="$out/logs/shard-%a.out" "$here/bench_array.sbatch" "$@")
array=${array%%;*}  # "ID;CLUSTER" on multi-cluster set-ups
shards=()
for k in $(seq 1 "$n"); do shards+=("$out/shard-$k"); done
echo "submitted: array job $array ($n shards) -> $out"
if ! merge=$(sbatch --parsable "${wait[@]}" --dependency=afterok:"$array" --kill-on-invalid-dep=yes \
  --job-name=foveal-bench-merge --output="$out/logs/merge.out" \
  --wrap "$(printf '%q ' "$foveal" bench merge --out "$out" "${shards[@]}")"); then
  echo "$0: the sweep failed: a shard or the merge (logs in $out/logs)" >&2
  exit 1
fi
merge=${merge%%;*}
if ((${#wait[@]})); then
  # sbatch --wait returns 0 for a merge cancelled because a shard failed: ask for its state.
  state=$(scontrol show job "$merge" -o 2>/dev/null | grep -o 'JobState=[A-Z_]*' || true)
  if [[ $state != JobState=COMPLETED ]]; then
    echo "$0: the sweep failed (merge job $merge: ${state:-no state}); shard logs in $out/logs" >&2
    exit 1
  fi
  echo "merge job $merge: done -> $out/bench.csv"
else
  echo "merge job $merge waits for the array -> $out/bench.csv"
fi
