#!/bin/bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Replays hostile probes against build/dform: each must end with its documented
# exit code and one escaped line on stderr naming the file or option, and leave an output folder
# that holds exactly the old result or exactly the new one (it validates; or it is byte for byte
# what it was). Run by ctest (cli_probes) with the dform binary, the samples folder and whether
# the binary was built with AddressSanitizer (whose shadow memory no `ulimit -v` admits).
#
#   tests/cli/probes.sh DFORM SAMPLES [plain|sanitized]
set -u
dform=$(realpath "$1")
samples=$(realpath "$2")
build=${3:-plain}
work=$(mktemp -d "${TMPDIR:-/tmp}/dform-probes.XXXXXX")
trap 'rm -rf "$work"' EXIT
cd "$work" || exit 2
pair="$samples/forward/ellipses-a.svg $samples/forward/ellipses-b.svg"
failures=0

fail() {
  echo "FAIL: $*" >&2
  failures=$((failures + 1))
}

# The bytes of every file of a folder, as one digest (names included).
digest() { (cd "$1" && find . -type f -print0 | sort -z | xargs -0 sha256sum) | sha256sum; }

# expect NAME CODE MENTION -- COMMAND...: runs it, then checks the exit code, that stderr is one
# line "dform: error: ..." without a control character, and that it mentions MENTION.
expect() {
  local name=$1 code=$2 mention=$3
  shift 4
  "$@" >"$work/out.txt" 2>"$work/err.txt"
  local got=$?
  [ "$got" = "$code" ] || fail "$name: exit $got, expected $code: $(head -c 400 "$work/err.txt")"
  check_error "$name" "$mention"
}

check_error() {
  local name=$1 mention=$2
  local lines
  lines=$(wc -l <"$work/err.txt")
  [ "$lines" = 1 ] || fail "$name: $lines lines on stderr: $(head -c 400 "$work/err.txt")"
  grep -q '^dform: error: ' "$work/err.txt" || fail "$name: not an error line: $(head -c 200 "$work/err.txt")"
  LC_ALL=C grep -q '[[:cntrl:]]' <(tr -d '\n' <"$work/err.txt") &&
    fail "$name: a control character on stderr"
  grep -qF -- "$mention" "$work/err.txt" || fail "$name: does not mention '$mention': $(head -c 400 "$work/err.txt")"
}

validates() { "$dform" validate "$1" >/dev/null 2>&1 || fail "$2: $1 does not validate"; }

# A complete earlier result.
"$dform" forward $pair --resolution 30 -q -o res >/dev/null || fail "the first run"
before=$(digest res)

# Checked before the solve: nothing of the folder is touched.
expect "unknown profile" 2 "unknown profile" -- "$dform" forward $pair --resolution 250 -q --profile nope -o res
expect "missing profile file" 3 "$work/none.json" -- "$dform" forward $pair --resolution 250 -q --profile "$work/none.json" -o res
expect "missing gate file" 3 "$work/nogate.json" -- "$dform" forward $pair --resolution 250 -q --gate "$work/nogate.json" -o res
[ "$(digest res)" = "$before" ] || fail "a bad option changed the folder"

# A full disk (the file-size limit fails writes the same way): exit 6 naming the file, the old
# result kept, at every size from the first mesh to the report page.
for blocks in 2 8 40 200; do
  (ulimit -f "$blocks"; trap '' XFSZ; exec "$dform" forward $pair --resolution 36 -q -o res) >/dev/null 2>"$work/err.txt"
  got=$?
  [ "$got" = 6 ] || fail "disk full at $blocks KiB: exit $got"
  check_error "disk full at $blocks KiB" "res/"
  [ "$(digest res)" = "$before" ] || fail "disk full at $blocks KiB: the folder changed"
done
validates res "after the full disks"

# An inverse result then a forward one: no file of the first stays.
"$dform" inverse "$samples/inverse/saddle.obj" --resolution 30 -q -o res >/dev/null || fail "inverse run"
"$dform" forward $pair --resolution 30 -q -o res >/dev/null || fail "forward after inverse"
[ -e res/target-curve.obj ] && fail "the inverse run's target curve stayed"
validates res "forward after inverse"

# Two runs on one folder: the second fails at once; the first stops on SIGTERM, the folder kept.
before=$(digest res)
# The paper model at this resolution runs for seconds (the exact one would be done at once).
"$dform" forward $pair --resolution 250 --model paper -o res >/dev/null 2>"$work/first.txt" &
first=$!
for _ in $(seq 12000); do
  grep -q "meshed piece A with" "$work/first.txt" || ! kill -0 "$first" 2>/dev/null && break
  sleep 0.05
done
expect "second run" 6 "another dform run (process $first)" -- "$dform" inverse "$samples/inverse/saddle.obj" --resolution 30 -q -o res
expect "export meanwhile" 6 "another dform run" -- "$dform" export res -q
kill -TERM "$first"
wait "$first"
got=$?
[ "$got" = 143 ] || fail "the first run ended with $got on SIGTERM"
[ "$(digest res)" = "$before" ] || fail "the interrupted run changed the folder"

# Memory: under ulimit -v a large resolution is refused with one that fits, not bad_alloc.
if [ "$build" = sanitized ]; then
  echo "skipped: ulimit -v (AddressSanitizer build)"
else
  (ulimit -v 400000; exec "$dform" forward $pair --resolution 1000 -q --no-export -o big) >/dev/null 2>"$work/err.txt"
  got=$?
  [ "$got" = 2 ] || fail "ulimit -v: exit $got: $(head -c 300 "$work/err.txt")"
  check_error "ulimit -v" "a resolution of "
  # The same refusal offers the same resolution every time, and a run at that resolution passes
  # the check and runs to its end under the same limit.
  offers=$(for _ in 1 2 3 4 5; do
    (ulimit -v 400000; exec "$dform" forward $pair --resolution 200 --model paper -q --no-export -o big) 2>&1 |
      grep -o 'a resolution of [0-9]* or less fits'
  done | sort | uniq -c)
  [ "$(echo "$offers" | wc -l)" = 1 ] || fail "ulimit -v: different offers on identical runs: $offers"
  offer=$(echo "$offers" | grep -o 'of [0-9]*' | head -1 | cut -c4-)
  if [ -n "$offer" ]; then
    (ulimit -v 400000; exec "$dform" forward $pair --resolution "$offer" --model paper -q --no-export -o big) \
      >/dev/null 2>"$work/err.txt"
    got=$?
    [ "$got" = 0 ] || fail "ulimit -v: the offered resolution $offer: exit $got: $(head -c 300 "$work/err.txt")"
  else
    fail "ulimit -v: resolution 200 offered none: $offers"
  fi
fi

# A FIFO nobody writes: SIGTERM ends the run, naming it.
mkfifo fifo.svg
"$dform" forward fifo.svg "$samples/forward/circle.svg" -o fifo-out >/dev/null 2>"$work/err.txt" &
reader=$!
# Whether one of its threads (the one reading) waits in open() for a writer.
waiting_for_writer() {
  for wchan in /proc/$reader/task/*/wchan; do
    [ "$(cat "$wchan" 2>/dev/null)" = wait_for_partner ] && return 0
  done
  return 1
}
for _ in $(seq 12000); do
  waiting_for_writer || ! kill -0 "$reader" 2>/dev/null && break
  sleep 0.05
done
kill -TERM "$reader"
wait "$reader"
got=$?
[ "$got" = 143 ] || fail "FIFO: exit $got"
check_error "FIFO" "fifo.svg: interrupted while waiting to read it"

# Names and values in messages: one escaped line, long tokens cut.
expect "strange name" 3 'a\nb\x1b[31m.svg: no such file' -- "$dform" forward $'a\nb\x1b[31m.svg' "$samples/forward/circle.svg" -o o1
printf 'v 1%010000000dx 0 0\n' 0 >huge.obj
expect "huge number" 3 "huge.obj: line 1:" -- "$dform" inverse huge.obj -o o2
[ "$(wc -c <"$work/err.txt")" -lt 1000 ] || fail "the huge number was quoted whole"

# Units, ranges, sizes: their exact exit codes.
for size in 300furlong 100%; do
  echo "<svg xmlns='http://www.w3.org/2000/svg' width='$size' height='300mm' viewBox='0 0 300 300'><rect x='10' y='10' width='100' height='100'/></svg>" >root.svg
  expect "root width $size" 3 "root.svg: has an unknown unit in its 'width' attribute" -- "$dform" forward root.svg "$samples/forward/circle.svg" -o o3
done
printf 'v 0 0 0\nv 1e999 0 0\nv 1 1 0\nv 0 1 1\nv 2 2 2\nl 1 2 3 4 5 1\n' >far.obj
expect "OBJ 1e999" 4 "far.obj: line 2: '1e999' is out of range" -- "$dform" inverse far.obj -o o4
echo "<svg xmlns='http://www.w3.org/2000/svg' width='300mm' height='300mm' viewBox='0 0 300 300'><rect x='10' y='10' width='0.01' height='0.01'/></svg>" >tiny.svg
expect "tiny square" 4 "tiny.svg: " -- "$dform" forward tiny.svg "$samples/forward/circle.svg" -o o5

# validate trusts no report.json.
"$dform" inverse "$samples/inverse/saddle.obj" --resolution 30 -q --no-export -o inv >/dev/null || fail "inverse run"
cp inv/report.json good.json
printf '{"metrics": ' >inv/report.json
expect "report not JSON" 3 "inv/report.json: not valid JSON" -- "$dform" validate inv
echo '[]' >inv/report.json
expect "report []" 7 "inv/report.json" -- "$dform" validate inv
python3 -c 'import json,sys; r=json.load(open("good.json")); del r["metrics"]; json.dump(r, open("inv/report.json","w"))'
expect "report without metrics" 7 "metrics." -- "$dform" validate inv
python3 -c 'import json,sys; r=json.load(open("good.json")); r["mesh"]["vertices_a"]+=1; json.dump(r, open("inv/report.json","w"))'
expect "report with other mesh sizes" 7 "mesh.vertices_a" -- "$dform" validate inv
head -c 70000000 /dev/zero | tr '\0' ' ' >inv/report.json
expect "report over 64 MiB" 3 "inv/report.json: file is too large" -- "$dform" validate inv
cp good.json inv/report.json
validates inv "the restored inverse result"
rm inv/target-curve.obj
expect "inverse without its curve" 7 "mode" -- "$dform" validate inv

# export runs the gate itself: a stretched mesh whose report says "passed" is not exported.
"$dform" forward $pair --resolution 30 -q -o exp >/dev/null || fail "forward run"
python3 -c '
import sys
lines = []
for line in open("exp/piece-a-3d.obj"):
    f = line.split()
    if f and f[0] == "v":
        line = "v " + " ".join(repr(1.05 * float(x)) for x in f[1:4]) + "\n"
    lines.append(line)
open("exp/piece-a-3d.obj", "w").writelines(lines)'
before=$(digest exp)
expect "export of a failing result" 7 "exp: the result failed its quality gate" -- "$dform" export exp -q
[ "$(digest exp)" = "$before" ] || fail "the refused export changed the folder"

# Nothing left beside the folders.
leftovers=$(find . -maxdepth 1 -name '.*.dform-*')
[ -z "$leftovers" ] || fail "left beside the folders: $leftovers"

if [ "$failures" -gt 0 ]; then
  echo "$failures probe(s) failed" >&2
  exit 1
fi
echo "every probe ended as documented"
