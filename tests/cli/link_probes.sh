#!/bin/bash
# SPDX-License-Identifier: GPL-3.0-or-later
# What another user of a shared project folder can plant or do beside a run: a symbolic link at
# every lock and temporary path of forward, inverse, run, sweep, batch and export (the link's
# target is never written, the run exits 6 with one line), a run into a folder that a sweep or a
# run is replacing (refused, exit 6), a file saved into such a folder meanwhile (kept, said so), a
# result folder read for an export elsewhere on a read-only mount (exported), a batch into a
# read-only mount and a sweep on a full disk (exit 6, saying why). Run by ctest (cli_link_probes).
#
#   tests/cli/link_probes.sh DFORM SAMPLES
set -u
dform=$(realpath "$1")
samples=$(realpath "$2")
work=$(mktemp -d "${TMPDIR:-/tmp}/dform-links.XXXXXX")
trap 'rm -rf "$work"' EXIT
cd "$work" || exit 2
fwd="$samples/forward"
pair="$fwd/ellipses-a.svg $fwd/ellipses-b.svg"
quick="--resolution 30 --no-export -q"
jobs="--no-export -q"  # run and batch: the resolution is the job's
failures=0

fail() {
  echo "FAIL: $*" >&2
  failures=$((failures + 1))
}

# Runs COMMAND... with stderr into err.txt; its exit code in $got.
run() {
  "$@" >/dev/null 2>"$work/err.txt"
  got=$?
}

# expect_refusal NAME MENTION -- COMMAND...: exit 6, one error line mentioning MENTION, the victim
# untouched.
expect_refusal() {
  local name=$1 mention=$2 lines
  shift 3
  echo "the victim's own words" >"$work/victim.txt"
  run "$@"
  [ "$got" = 6 ] || fail "$name: exit $got, expected 6: $(head -c 400 "$work/err.txt")"
  lines=$(wc -l <"$work/err.txt")
  [ "$lines" = 1 ] || fail "$name: $lines lines on stderr: $(head -c 400 "$work/err.txt")"
  grep -q '^dform: error: ' "$work/err.txt" || fail "$name: not an error line: $(head -c 200 "$work/err.txt")"
  grep -qF -- "$mention" "$work/err.txt" || fail "$name: does not mention '$mention': $(head -c 400 "$work/err.txt")"
  [ "$(cat "$work/victim.txt")" = "the victim's own words" ] || fail "$name: the link's target was written"
}

# plant PATH: a symbolic link to the victim at PATH.
plant() { ln -sfn "$work/victim.txt" "$1"; }

# expect_link_refusal NAME PATH -- COMMAND...: as expect_refusal, COMMAND run in a process whose
# id is known beforehand (exec keeps it), after a link to the victim is planted at PATH with "PID"
# replaced by that id; the message must name the path planted, which is removed afterwards.
expect_link_refusal() {
  local name=$1 path=$2 planted
  shift 3
  expect_refusal "$name" "${path//PID/}" -- bash -c \
    'planted=${1//PID/$$}; ln -sfn "$2" "$planted"; echo "$planted" >"$3"; shift 3; exec "$@"' \
    _ "$path" "$work/victim.txt" "$work/planted.txt" "$@"
  planted=$(cat "$work/planted.txt")
  grep -qF -- "$planted" "$work/err.txt" || fail "$name: does not name $planted: $(head -c 300 "$work/err.txt")"
  [ -L "$planted" ] || fail "$name: the link at $planted was removed"
  rm -f "$planted"
}

# --- Lock files -----------------------------------------------------------------------------------
"$dform" forward $pair $quick -o R || fail "the first forward run"
"$dform" inverse "$samples/inverse/saddle.obj" $quick -o I || fail "the first inverse run"
printf '{"mode": "forward", "piece_a": "%s", "piece_b": "%s", "resolution": 30}\n' \
  "$fwd/ellipses-a.svg" "$fwd/ellipses-b.svg" >job.json
"$dform" sweep $pair --starts 2 $quick -o W || fail "the first sweep"
mkdir jobs && cp job.json jobs/j0.json
for lock in .R.dform-lock .I.dform-lock .J.dform-lock .W.dform-lock W/.start-0.dform-lock \
  B/.dform-batch.lock B/.batch-shard-1-of-2.json.dform-lock B/.j0.dform-lock .E.dform-lock; do
  mkdir -p B
  plant "$lock"
  case $lock in
    .R.*) expect_refusal "forward, a link at $lock" "$lock is a symbolic link" -- "$dform" forward $pair $quick -o R
      expect_refusal "export, a link at $lock" "$lock is a symbolic link" -- "$dform" export R -q
      expect_refusal "export -o, a link at the read lock $lock" "$lock is a symbolic link" -- "$dform" export R -o E -q ;;
    .I.*) expect_refusal "inverse, a link at $lock" "$lock is a symbolic link" -- "$dform" inverse "$samples/inverse/saddle.obj" $quick -o I ;;
    .J.*) expect_refusal "run, a link at $lock" "$lock is a symbolic link" -- "$dform" run job.json $jobs -o J ;;
    .W.* | W/*) expect_refusal "sweep, a link at $lock" "$lock is a symbolic link" -- "$dform" sweep $pair --starts 2 $quick -o W ;;
    B/.dform-batch.lock) expect_refusal "batch, a link at $lock" "$lock is a symbolic link" -- "$dform" batch jobs $jobs -o B ;;
    B/.batch-shard*) expect_refusal "a batch shard, a link at $lock" "$lock is a symbolic link" -- "$dform" batch jobs --shard 1/2 $jobs -o B ;;
    B/.j0.*) expect_refusal "batch, a link at a job's lock $lock" "$lock is a symbolic link" -- "$dform" batch jobs $jobs -o B ;;
    .E.*) expect_refusal "export -o, a link at $lock" "$lock is a symbolic link" -- "$dform" export R -o E -q ;;
  esac
  rm "$lock"
done
[ -e "$work/E" ] && fail "a refused export created E"

# --- Staging folders and temporary files: their paths hold the process id -------------------------
expect_link_refusal "forward, a link at its staging folder" .R.dform-new.PID -- "$dform" forward $pair $quick -o R
expect_link_refusal "forward, a link at its old folder" .R.dform-old.PID -- "$dform" forward $pair $quick -o R
expect_link_refusal "inverse, a link at its staging folder" .I.dform-new.PID -- "$dform" inverse "$samples/inverse/saddle.obj" $quick -o I
expect_link_refusal "run, a link at its staging folder" .J.dform-new.PID -- "$dform" run job.json $jobs -o J
expect_link_refusal "sweep, a link at its staging folder" .W.dform-new.PID -- "$dform" sweep $pair --starts 2 $quick -o W
expect_link_refusal "batch, a link at its manifest's temporary file" B/batch.json.tmp.PID -- "$dform" batch jobs $jobs -o B
expect_link_refusal "batch, a link at a job's staging folder" B/.j0.dform-new.PID -- "$dform" batch jobs $jobs -o B
expect_link_refusal "export, a link at its staging folder" .R.dform-new.PID -- "$dform" export R -q
expect_link_refusal "export -o, a link at its staging folder" .E.dform-new.PID -- "$dform" export R -o E -q
"$dform" validate R >/dev/null 2>&1 || fail "R does not validate after the refused runs"

# --- A run inside a folder another run replaces, and a user's file saved into it meanwhile --------
# wait_staged NAME PID: until the run PID has staged NAME's new result (it then holds the lock).
wait_staged() {
  for _ in $(seq 6000); do
    ls -a | grep -q "^\.$1\.dform-new\." && return 0
    kill -0 "$2" 2>/dev/null || return 1
    sleep 0.02
  done
  return 1
}
for target in W R; do
  if [ $target = W ]; then
    "$dform" sweep $pair --starts 3 --resolution 90 --model paper --threads 1 --no-export -o W \
      >/dev/null 2>"$work/long.txt" &
  else
    "$dform" forward $pair --resolution 400 --model paper --no-export -o R >/dev/null 2>"$work/long.txt" &
  fi
  long=$!
  wait_staged $target $long || fail "$target: the long run ended before it was raced"
  kill -0 $long 2>/dev/null || fail "$target: the long run ended before it was raced"
  expect_refusal "a run into $target/start-5 while $target is replaced" "is being replaced by another dform run" -- \
    "$dform" forward $pair $quick -o $target/start-5
  expect_refusal "a run into $target/mine while $target is replaced" "is being replaced by another dform run" -- \
    "$dform" forward $pair $quick -o $target/mine
  echo "my notes" >$target/notes.txt
  kill -0 $long 2>/dev/null || fail "$target: the long run ended before the notes were saved"
  wait $long || fail "$target: the long run: exit $?: $(head -c 300 "$work/long.txt")"
  [ "$(cat $target/notes.txt 2>/dev/null)" = "my notes" ] || fail "$target: the notes saved meanwhile were swapped away"
  grep -q "warning: $target/notes.txt: appeared while dform was writing $target; kept in the new result" "$work/long.txt" ||
    fail "$target: the run did not say it kept the notes: $(head -c 300 "$work/long.txt")"
  [ -e $target/mine ] && fail "$target: a refused run wrote $target/mine"
  rm -f $target/notes.txt
done

# --- A read-only mount and a full disk (tmpfs in a mount namespace) ------------------------------
if unshare -rm true 2>/dev/null; then
  unshare -rm bash -c '
    mkdir ro && mount -t tmpfs -o size=16m tmpfs ro && cp -r R ro/R && mount -o remount,ro ro || exit 9
    "$1" export ro/R -o ro-export -q' _ "$dform" 2>"$work/err.txt"
  got=$?
  [ "$got" = 0 ] || fail "export of a result on a read-only mount into another folder: exit $got: $(head -c 300 "$work/err.txt")"
  [ -e ro-export/pattern.svg ] || fail "export of a read-only result: no pattern.svg in ro-export"
  # A batch that cannot create its folder there says why: the mount is read-only.
  unshare -rm bash -c '
    mount -t tmpfs -o size=1m,ro tmpfs ro || exit 9
    "$1" batch jobs --no-export -q -o ro/B' _ "$dform" 2>"$work/err.txt"
  got=$?
  [ "$got" = 6 ] || fail "a batch into a read-only mount: exit $got: $(head -c 300 "$work/err.txt")"
  grep -q "ro/B: cannot create the folder (Read-only file system)" "$work/err.txt" ||
    fail "a batch into a read-only mount names another cause: $(head -c 300 "$work/err.txt")"
  # A sweep on a disk that fills after its first start: its other starts are not written, and it
  # says so (exit 6), though what it wrote is in place.
  mkdir full
  unshare -rm bash -c '
    mount -t tmpfs -o size=380k tmpfs full || exit 9
    "$1" sweep "$2/ellipses-a.svg" "$2/ellipses-b.svg" --starts 4 --threads 1 --resolution 30 \
      --no-export -q -o full/W
    code=$?
    [ -e full/W/sweep.json ] && [ -e full/W/start-0/report.json ] || exit 8
    exit $code' _ "$dform" "$fwd" 2>"$work/err.txt"
  got=$?
  [ "$got" = 6 ] || fail "a sweep on a full disk: exit $got: $(head -c 300 "$work/err.txt")"
  grep -Eq "full/W: [123] of 4 starts were not written \(start-[123]" "$work/err.txt" ||
    fail "a sweep on a full disk does not name its unwritten starts: $(head -c 300 "$work/err.txt")"
else
  echo "skipped: the read-only mount and the full disk (no user namespaces here)"
fi

left=$(find "$work" \( -name '.*.dform-*' -o -name '.dform-batch*' \) -not -name '*.dform-kept.*' | head -5)
[ -z "$left" ] || fail "left behind: $left"
if [ "$failures" -gt 0 ]; then
  echo "$failures probe(s) failed" >&2
  exit 1
fi
echo "every link and race probe ended as documented"
