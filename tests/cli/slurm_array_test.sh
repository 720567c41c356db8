#!/bin/bash
# SPDX-License-Identifier: GPL-3.0-or-later
# samples/batch/slurm-array.sh under simulated Slurm arrays (its variables set as Slurm sets them,
# build/dform as DFORM): 0-based, 1-based, stepped and evenly spaced arrays each run every job of
# the list exactly once across their tasks, and the merge takes them all; ids that are not evenly
# spaced (a task off their grid) and a run outside Slurm end with one clear error line and exit 2.
#   tests/cli/slurm_array_test.sh build/dform samples/batch/slurm-array.sh
set -uo pipefail
dform=$(realpath "$1")
script=$(realpath "$2")
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work" || exit 1
failures=0
fail() {
  echo "FAIL: $*"
  failures=$((failures + 1))
}

# Eleven jobs (not a multiple of any array's size below) that fail at once, each with its row.
mkdir jobs
for k in $(seq -w 0 10); do
  printf '{"mode": "forward", "piece_a": "nowhere-%s.svg", "piece_b": "x.svg"}' "$k" >jobs/j$k.json
done

# Runs every task of an array with ids $@ (as Slurm numbers them) into out-$label; checks that the
# tasks' manifests hold every job once and that the merge takes them.
array() {
  local label=$1 step=$2
  shift 2
  local ids=("$@") min=$1 max=${!#} out=out-$label
  for id in "${ids[@]}"; do
    env SLURM_ARRAY_TASK_ID="$id" SLURM_ARRAY_TASK_COUNT=${#ids[@]} SLURM_ARRAY_TASK_MIN="$min" \
      SLURM_ARRAY_TASK_MAX="$max" ${step:+SLURM_ARRAY_TASK_STEP=$step} DFORM="$dform" \
      bash "$script" jobs "$out" >"$work/log.txt" 2>&1
    local got=$?
    # Every job fails (its piece is missing): the task exits as its first job does.
    [ "$got" = 3 ] || fail "$label: task $id exited $got: $(head -c 300 "$work/log.txt")"
  done
  python3 - "$out" "${#ids[@]}" <<'PYEOF' || fail "$label: the tasks did not run every job exactly once"
import collections, glob, json, sys
out, tasks = sys.argv[1], int(sys.argv[2])
manifests = sorted(glob.glob(out + "/batch-shard-*-of-*.json")) if tasks > 1 else [out + "/batch.json"]
assert len(manifests) == tasks, manifests
seen = collections.Counter(row["index"] for m in manifests for row in json.load(open(m))["rows"])
assert sorted(seen) == list(range(11)) and set(seen.values()) == {1}, dict(seen)
PYEOF
  "$dform" batch --merge "$out" >"$work/log.txt" 2>&1 ||
    fail "$label: the merge exited $?: $(head -c 300 "$work/log.txt")"
}

array zero-based "" 0 1 2 3 4 5 6 7
array one-based "" 1 2 3 4 5 6 7 8
array single "" 5
array stepped 2 0 2 4 6 8 10 12 14
array listed "" 3 6 9

# Outside Slurm: one line, exit 2, no bash "unbound variable".
env -u SLURM_ARRAY_TASK_ID -u SLURM_ARRAY_TASK_COUNT DFORM="$dform" bash "$script" jobs out-none \
  >"$work/log.txt" 2>&1
got=$?
[ "$got" = 2 ] || fail "outside Slurm: exit $got"
[ "$(wc -l <"$work/log.txt")" = 1 ] && grep -q "not a Slurm array task" "$work/log.txt" ||
  fail "outside Slurm: $(head -c 300 "$work/log.txt")"
[ -e out-none ] && fail "outside Slurm: the script ran a batch"

# Ids 1,2,5, not evenly spaced: Slurm's variables (3 ids from 1 to 5) read as 1,3,5, so task 2
# cannot tell its shard and says so; the merge then refuses, naming the jobs of shard 2 of 3.
for id in 1 2 5; do
  SLURM_ARRAY_TASK_ID=$id SLURM_ARRAY_TASK_COUNT=3 SLURM_ARRAY_TASK_MIN=1 SLURM_ARRAY_TASK_MAX=5 \
    DFORM="$dform" bash "$script" jobs out-uneven >"$work/log.txt" 2>&1
  got=$?
  if [ "$id" = 2 ]; then
    [ "$got" = 2 ] || fail "uneven ids: task 2 exited $got"
    [ "$(wc -l <"$work/log.txt")" = 1 ] && grep -q "not evenly spaced" "$work/log.txt" ||
      fail "uneven ids: task 2: $(head -c 300 "$work/log.txt")"
  fi
done
"$dform" batch --merge out-uneven >"$work/log.txt" 2>&1
got=$?
[ "$got" = 5 ] && grep -q "4 of 11 jobs have not finished in any manifest (#1, #4, #7, #10)" \
  "$work/log.txt" || fail "uneven ids: the merge exited $got: $(head -c 300 "$work/log.txt")"

[ "$failures" = 0 ] && echo "slurm-array.sh: every array covers every job once" || exit 1
