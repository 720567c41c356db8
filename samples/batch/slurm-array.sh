#!/bin/bash
# A dform batch as a Slurm job array: each array task runs its slice of the jobs, then one task
# that depends on the array merges the slices' manifests (docs/batch.md).
#
#   sbatch --array=1-8 samples/batch/slurm-array.sh jobs.txt results
#   sbatch --dependency=afterany:<array job id> --wrap "build/dform batch --merge results"
#
# Tasks that were cut short (time limit, node failure) are rerun with the same command: --resume
# skips the jobs their manifest has as finished.
#SBATCH --job-name=dform-batch
#SBATCH --cpus-per-task=4
#SBATCH --time=02:00:00
#SBATCH --output=dform-batch-%A_%a.log
set -euo pipefail

jobs=${1:?usage: sbatch --array=1-N slurm-array.sh JOBS.txt|DIR OUT}
out=${2:?usage: sbatch --array=1-N slurm-array.sh JOBS.txt|DIR OUT}
dform=${DFORM:-build/dform}

# SIGTERM at the time limit: dform finishes no half result and the manifest lists what is done.
exec "$dform" batch "$jobs" -o "$out" --resume --quiet \
  --threads "${SLURM_CPUS_PER_TASK:-1}" \
  --shard "${SLURM_ARRAY_TASK_ID}/${SLURM_ARRAY_TASK_COUNT}"
