#!/bin/bash
# A dform batch as a Slurm job array: each array task runs its slice of the jobs, then one task
# that depends on the array merges the slices' manifests (docs/batch.md).
#
#   sbatch --array=1-8 samples/batch/slurm-array.sh jobs.txt results   (or --array=0-7)
#   sbatch --dependency=afterany:<array job id> --wrap "build/dform batch --merge results"
#
# The array's tasks are the shards: their number is SLURM_ARRAY_TASK_COUNT and a task's shard is
# the place of its id among the array's ids, so 0- and 1-based arrays and evenly stepped ones
# (--array=0-14:2) run every job once. Ids without an even step (--array=1,2,5) are refused:
# their places cannot be told from Slurm's variables. The merge refuses (exit 5) while a task's
# jobs have not finished. Tasks that were cut short (time limit, node failure) are rerun with the
# same command: --resume skips the jobs their manifest has as finished. DFORM names the binary
# (default build/dform).
#SBATCH --job-name=dform-batch
#SBATCH --cpus-per-task=4
#SBATCH --time=02:00:00
#SBATCH --output=dform-batch-%A_%a.log
set -euo pipefail

usage="usage: sbatch --array=1-N slurm-array.sh JOBS.txt|DIR OUT"
jobs=${1:?$usage}
out=${2:?$usage}
dform=${DFORM:-build/dform}

fail() {
  echo "slurm-array.sh: error: $*" >&2
  exit 2
}

id=${SLURM_ARRAY_TASK_ID:-}
count=${SLURM_ARRAY_TASK_COUNT:-}
min=${SLURM_ARRAY_TASK_MIN:-}
max=${SLURM_ARRAY_TASK_MAX:-}
[ -n "$id" ] || fail "not a Slurm array task (SLURM_ARRAY_TASK_ID is not set): submit it with sbatch --array=1-N, or run '$dform batch $jobs -o $out --shard I/N' yourself"
for name in id count min max; do
  [[ ${!name} =~ ^[0-9]+$ ]] ||
    fail "SLURM_ARRAY_TASK_${name^^} is '${!name}', not a number: this script needs Slurm's array variables SLURM_ARRAY_TASK_ID, _COUNT, _MIN and _MAX"
done
# Decimal, whatever leading zeros: 08 is not octal here.
id=$((10#$id)) count=$((10#$count)) min=$((10#$min)) max=$((10#$max))
# The step between the array's ids: Slurm's own where it is the step of these ids, else the one
# that spaces COUNT ids evenly from MIN to MAX.
step=${SLURM_ARRAY_TASK_STEP:-0}
[[ $step =~ ^[0-9]+$ ]] || step=0
step=$((10#$step))
if [ "$count" -le 1 ]; then
  step=1
elif [ "$step" -eq 0 ] || [ $((step * (count - 1))) -ne $((max - min)) ]; then
  step=$(((max - min) / (count - 1)))
fi
if [ "$count" -lt 1 ] || [ "$step" -lt 1 ] || [ $((step * (count - 1))) -ne $((max - min)) ] ||
  [ "$id" -lt "$min" ] || [ "$id" -gt "$max" ] || [ $(((id - min) % step)) -ne 0 ]; then
  fail "array task $id of $count ids from $min to $max: the ids are not evenly spaced, so this task's shard cannot be told; submit with --array=A-B or --array=A-B:S"
fi
shard=$(((id - min) / step + 1))

# SIGTERM at the time limit: dform finishes no half result and the manifest lists what is done.
exec "$dform" batch "$jobs" -o "$out" --resume --quiet \
  --threads "${SLURM_CPUS_PER_TASK:-1}" \
  --shard "$shard/$count"
