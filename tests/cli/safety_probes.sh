#!/bin/bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Sweeps, batches and every subcommand under the probes a shared cluster's users make: a user's
# file in a sweep's start folder, an export into a start folder while the sweep runs, names that
# are not UTF-8, that hold control characters or are megabytes long, two batches on one folder,
# shards from different lists, edited jobs resumed, job names that collide with the batch's own
# files. Each ends with its documented exit code and one escaped error line, never an abort
# (134), and leaves no lock or staging folder behind. Run by ctest (cli_safety_probes).
#
#   tests/cli/safety_probes.sh DFORM SAMPLES
set -u
dform=$(realpath "$1")
samples=$(realpath "$2")
work=$(mktemp -d "${TMPDIR:-/tmp}/dform-safety.XXXXXX")
trap 'rm -rf "$work"' EXIT
cd "$work" || exit 2
fwd="$samples/forward"
pair="$fwd/ellipses-a.svg $fwd/ellipses-b.svg"
failures=0

fail() {
  echo "FAIL: $*" >&2
  failures=$((failures + 1))
}

# Runs COMMAND... with stdout and stderr into out.txt and err.txt; its exit code in $got.
run() {
  "$@" >"$work/out.txt" 2>"$work/err.txt"
  got=$?
}

# check_error NAME MENTION: stderr is one line "dform: error: ..." without a control character,
# mentioning MENTION.
check_error() {
  local name=$1 mention=$2 lines
  lines=$(wc -l <"$work/err.txt")
  [ "$lines" = 1 ] || fail "$name: $lines lines on stderr: $(head -c 400 "$work/err.txt")"
  grep -q '^dform: error: ' "$work/err.txt" || fail "$name: not an error line: $(head -c 200 "$work/err.txt")"
  LC_ALL=C grep -q '[[:cntrl:]]' <(tr -d '\n' <"$work/err.txt") && fail "$name: a control character on stderr"
  grep -qF -- "$mention" "$work/err.txt" || fail "$name: does not mention '$mention': $(head -c 400 "$work/err.txt")"
  [ "$(wc -c <"$work/err.txt")" -lt 2000 ] || fail "$name: an error line of $(wc -c <"$work/err.txt") bytes"
}

# expect NAME CODE MENTION -- COMMAND...
expect() {
  local name=$1 code=$2 mention=$3
  shift 4
  run "$@"
  [ "$got" = "$code" ] || fail "$name: exit $got, expected $code: $(head -c 400 "$work/err.txt")"
  check_error "$name" "$mention"
}

# No lock file, staging or old folder left anywhere under the work folder.
no_leftovers() {
  local left
  left=$(find "$work" -name '.*.dform-*' -o -name '.dform-batch*' | head -5)
  [ -z "$left" ] || fail "$1: left behind: $left"
}

# --- Sweep: a user's file in a start folder is never swapped away ----------------------------
"$dform" sweep $pair --starts 2 --resolution 30 --no-export -q -o W >/dev/null 2>&1 || fail "the first sweep"
echo notes >W/start-0/notes.txt
expect "sweep over a start folder with a user's file" 6 "W/start-0/notes.txt" -- \
  "$dform" sweep $pair --starts 2 --resolution 30 --no-export -q -o W
[ -e W/start-0/notes.txt ] || fail "the sweep removed W/start-0/notes.txt"
rm W/start-0/notes.txt
mkdir W/start-5
echo x >W/start-5/thesis.tex
expect "sweep over a start folder it would not make" 6 "W/start-5/thesis.tex" -- \
  "$dform" sweep $pair --starts 2 --resolution 30 --no-export -q -o W
[ -e W/start-5/thesis.tex ] || fail "the sweep removed W/start-5/thesis.tex"
rm -r W/start-5
no_leftovers "refused sweeps"

# --- Sweep: an export into a start folder while the sweep runs fails, never reports a lost success
"$dform" sweep $pair --starts 3 --resolution 90 --model paper --threads 1 --no-export -o W \
  >/dev/null 2>"$work/sweep.txt" &
sweep=$!
# Until it has staged its folder (then it holds the start folders' locks too).
for _ in $(seq 6000); do
  ls -a | grep -q '^\.W\.dform-new\.' && break
  kill -0 "$sweep" 2>/dev/null || break
  sleep 0.02
done
sleep 0.2  # it locks the start folders right after staging
kill -0 "$sweep" 2>/dev/null || fail "the sweep ended before the export was tried"
expect "export into a start folder during a sweep" 6 "another dform run" -- "$dform" export W/start-0 -q
wait "$sweep" || fail "the sweep beside the export: exit $?: $(head -c 300 "$work/sweep.txt")"
"$dform" validate W/start-0 >/dev/null 2>&1 || fail "W/start-0 does not validate after the sweep"
no_leftovers "sweep and export"

# --- Names: not UTF-8, control characters, very long --------------------------------------------
latin=$'ell\xe9'
cp "$fwd/ellipses-a.svg" "$latin-a.svg"
cp "$fwd/ellipses-b.svg" "$latin-b.svg"
cp "$samples/inverse/saddle.obj" "$latin.obj"
control=$'a\nb\x1b[31m'
long=$(head -c 100000 /dev/zero | tr '\0' 'n')
# An input named in Latin-1 is an ordinary input: the runs succeed, their reports name it.
run "$dform" forward "$latin-a.svg" "$latin-b.svg" --resolution 30 -q -o "$latin-fwd"
[ "$got" = 0 ] || fail "forward of a Latin-1 name: exit $got: $(head -c 300 "$work/err.txt")"
run "$dform" validate "$latin-fwd"
[ "$got" = 0 ] || fail "validate of a Latin-1 result: exit $got: $(head -c 300 "$work/err.txt")"
run "$dform" export "$latin-fwd" -q
[ "$got" = 0 ] || fail "export of a Latin-1 result: exit $got: $(head -c 300 "$work/err.txt")"
run "$dform" inverse "$latin.obj" --resolution 30 -q --no-export -o "$latin-inv"
[ "$got" = 0 ] || fail "inverse of a Latin-1 name: exit $got: $(head -c 300 "$work/err.txt")"
run "$dform" sweep "$latin-a.svg" "$latin-b.svg" --starts 2 --resolution 30 -q -o "$latin-sweep"
[ "$got" = 0 ] || fail "sweep of a Latin-1 name: exit $got: $(head -c 300 "$work/err.txt")"
# A job file named in Latin-1 (JSON itself holds UTF-8 text only): its batch result folder is.
printf '{"mode": "forward", "piece_a": "%s", "piece_b": "%s", "resolution": 30}\n' \
  "$fwd/ellipses-a.svg" "$fwd/ellipses-b.svg" >"$latin-job.json"
run "$dform" run "$latin-job.json" -q --no-export -o "$latin-run"
[ "$got" = 0 ] || fail "run of a Latin-1 job: exit $got: $(head -c 300 "$work/err.txt")"
printf '%s\n' "$work/$latin-job.json" >latin-list.txt
run "$dform" batch latin-list.txt -q --no-export -o "$latin-batch"
[ "$got" = 0 ] || fail "batch of a Latin-1 job: exit $got: $(head -c 300 "$work/err.txt")"
python3 - "$latin-batch/batch.json" <<'EOF' || fail "batch of a Latin-1 job: the manifest is not valid JSON"
import json, sys
rows = json.load(open(sys.argv[1], encoding="utf-8"))["rows"]
assert len(rows) == 1 and rows[0]["status"] == "done", rows
EOF
[ -e "$latin-batch/$latin-job/report.json" ] || fail "batch of a Latin-1 job: no result in $latin-job/"
no_leftovers "Latin-1 names"

# Names that name nothing: one escaped error line each, exit 3, nothing left.
huge=$(head -c 10000000 /dev/zero | tr '\0' 'n')
# The name of each kind of hostile name, naming no file.
name_of() {
  case $1 in
    latin) echo "$latin-missing" ;;
    control) echo "$control" ;;
    long) echo "$long" ;;
    huge) echo "$huge" ;;
  esac
}
for kind in latin control long; do
  name=$(name_of $kind)
  expect "forward, $kind name" 3 "dform: error:" -- "$dform" forward "$name.svg" "$fwd/circle.svg" -q -o o-$kind
  expect "inverse, $kind name" 3 "dform: error:" -- "$dform" inverse "$name.obj" -q -o o-$kind
  expect "sweep, $kind name" 3 "dform: error:" -- "$dform" sweep "$name.svg" "$fwd/circle.svg" --starts 2 -q -o o-$kind
  expect "run, $kind name" 3 "dform: error:" -- "$dform" run "$name.json" -q -o o-$kind
  expect "batch, $kind name" 3 "dform: error:" -- "$dform" batch "$name.txt" -q -o o-$kind
  expect "export, $kind name" 3 "dform: error:" -- "$dform" export "$name" -q
  expect "validate, $kind name" 3 "dform: error:" -- "$dform" validate "$name"
  # The studio reads its files before it serves anything (a timeout, should it serve instead).
  expect "studio, $kind name" 3 "dform: error:" -- timeout 20 "$dform" studio "$name.svg" "$fwd/circle.svg" --no-browser
  [ -e o-$kind ] && fail "$kind name: a failed run created o-$kind"
done
# The same names inside files: a job naming them, a list of them, a list of random bytes.
for kind in latin control huge; do
  name=$(name_of $kind)
  # JSON escapes the control characters; the Latin-1 byte stays raw (not valid UTF-8 JSON).
  printf '%s.svg' "$name" | python3 -c 'import json, sys; name = sys.stdin.buffer.read().decode("utf-8", "surrogateescape"); sys.stdout.buffer.write(json.dumps({"mode": "forward", "piece_a": "@", "piece_b": "x.svg"}).replace("\"@\"", json.dumps(name, ensure_ascii=False)).encode("utf-8", "surrogateescape"))' >job-$kind.json
  run "$dform" run job-$kind.json -q -o o-$kind
  case $got in 3 | 4) ;; *) fail "run of a job naming a $kind file: exit $got" ;; esac
  check_error "run of a job naming a $kind file" "dform: error:"
  printf '%s\n' "$name.json" >list-$kind.txt
  run "$dform" batch list-$kind.txt -q --no-export -o b-$kind
  if [ $kind = huge ]; then
    # No folder can have that name: refused before anything runs.
    [ "$got" = 4 ] || fail "batch of a list naming a $kind file: exit $got: $(head -c 300 "$work/err.txt")"
    check_error "batch of a list naming a $kind file" "list-$kind.txt"
    [ -e b-$kind ] && fail "the refused batch created b-$kind"
    continue
  fi
  [ "$got" = 3 ] || fail "batch of a list naming a $kind file: exit $got: $(head -c 300 "$work/err.txt")"
  check_error "batch of a list naming a $kind file" "dform: error:"
  python3 -c 'import json,sys; json.load(open(sys.argv[1], encoding="utf-8"))' b-$kind/batch.json 2>/dev/null ||
    fail "batch of a list naming a $kind file: batch.json is not valid UTF-8 JSON"
done
# A job naming a 10 MB file name: the manifest's message is cut as messages are.
printf '{"mode": "forward", "piece_a": "%s.svg", "piece_b": "%s", "resolution": 30}' \
  "$huge" "$fwd/ellipses-b.svg" >mjobs-long-value.json
mkdir mjobs && mv mjobs-long-value.json mjobs/long-value.json
run "$dform" batch mjobs -q --no-export -o b-long
check_error "batch of a job with a 10 MB value" "long-value"
[ "$(wc -c <b-long/batch.json)" -lt 20000 ] || fail "a 10 MB value is kept whole in the manifest ($(wc -c <b-long/batch.json) bytes)"
head -c 4000 /dev/urandom >random.txt
run "$dform" batch random.txt -q --no-export -o b-random
[ "$got" = 134 ] && fail "batch of a list of random bytes aborted"
[ "$got" = 0 ] && fail "batch of a list of random bytes: exit 0"
check_error "batch of a list of random bytes" "dform: error:"
no_leftovers "names"

# --- Batch: a lock on OUT -------------------------------------------------------------------------
mkdir jobs
for start in 0 0.1 0.2 0.3; do
  printf '{"mode": "forward", "piece_a": "%s", "piece_b": "%s", "resolution": 60, "model": "paper", "start_b": %s}\n' \
    "$fwd/ellipses-a.svg" "$fwd/ellipses-b.svg" "$start" >"jobs/j$start.json"
done
"$dform" batch jobs --no-export -q --threads 1 -o B >/dev/null 2>"$work/first.txt" &
first=$!
for _ in $(seq 6000); do
  [ -e B/batch.json ] && break
  sleep 0.02
done
expect "a second batch on the same folder" 6 "another dform batch" -- "$dform" batch jobs --no-export -q -o B
wait "$first" || fail "the first batch: exit $?: $(head -c 300 "$work/first.txt")"
python3 - B/batch.json <<'EOF' || fail "the first batch's manifest"
import json, sys
rows = json.load(open(sys.argv[1]))["rows"]
assert [r["status"] for r in rows] == ["done"] * 4, [(r["name"], r["status"], r["message"]) for r in rows]
EOF
# Shards of different lists do not merge.
printf '%s\n' jobs/j0.json jobs/j0.1.json jobs/j0.2.json jobs/j0.3.json >in-order.txt
printf '%s\n' jobs/j0.3.json jobs/j0.2.json jobs/j0.1.json jobs/j0.json >reordered.txt
sed -i 's/"resolution": 60/"resolution": 30/' jobs/*.json
"$dform" batch in-order.txt --shard 1/2 --no-export -q -o S >/dev/null 2>&1
"$dform" batch reordered.txt --shard 2/2 --no-export -q -o S >/dev/null 2>&1
expect "merge of shards from different lists" 4 "batch-shard-" -- "$dform" batch --merge S
# Shard numbers past int.
expect "a shard number past int" 2 "--shard" -- "$dform" batch jobs --shard 1/4294967298 -q -o S2
expect "a shard number past int" 2 "--shard" -- "$dform" batch jobs --shard 4294967297/4294967298 -q -o S2
[ -e S2 ] && fail "a refused batch created its folder"
# Job names that are the batch's own files: refused before anything runs.
mkdir clash
cp jobs/j0.json clash/gallery.html.json
cp jobs/j0.json clash/batch.json.json
expect "job names colliding with the batch's files" 4 "gallery.html" -- "$dform" batch clash --no-export -q -o C
[ -e C ] && fail "a refused batch created its folder"
# --resume reruns a job whose file changed since.
mkdir rjobs
cp jobs/j0.json rjobs/a.json
"$dform" batch rjobs --no-export -q -o R >/dev/null 2>&1 || fail "the batch to resume"
sed -i 's/"resolution": 30/"resolution": 36/' rjobs/a.json
"$dform" batch rjobs --no-export -q --resume -o R >/dev/null 2>&1 || fail "the resumed batch"
python3 - R/a/report.json <<'EOF' || fail "--resume kept the result of a job file edited since"
import json, sys
assert json.load(open(sys.argv[1]))["job"]["resolution"] == 36
EOF
# --resume reruns a job whose input file changed since (its hash in the manifest).
mkdir ijobs
cp "$fwd/ellipses-a.svg" "$fwd/ellipses-b.svg" ijobs/
printf '{"mode": "forward", "piece_a": "%s", "piece_b": "%s", "resolution": 30}\n' \
  "$work/ijobs/ellipses-a.svg" "$work/ijobs/ellipses-b.svg" >ijobs/i.json
"$dform" batch ijobs --no-export -q -o I >/dev/null 2>&1 || fail "the batch whose input changes"
sed -i 's/stroke-width="0.3"/stroke-width="0.4"/' ijobs/ellipses-b.svg
"$dform" batch ijobs --no-export -q --resume -o I >/dev/null 2>&1 || fail "the batch resumed after its input changed"
python3 - I/i/report.json "$(sha256sum ijobs/ellipses-b.svg | cut -d' ' -f1)" <<'EOF' ||
import json, sys
assert json.load(open(sys.argv[1]))["inputs"]["piece_b"]["sha256"] == sys.argv[2]
EOF
  fail "--resume kept the result of a job whose input changed since"
# A failing batch ends with one error line.
mkdir fjobs
printf '{"mode": "forward", "piece_a": "nowhere.svg", "piece_b": "x.svg"}' >fjobs/lost.json
run "$dform" batch fjobs --no-export -q -o F
[ "$got" = 3 ] || fail "a failing batch: exit $got"
check_error "a failing batch" "lost"
# A forged manifest row: the merged gallery links only to folders the batch made.
python3 - F/batch.json <<'EOF'
import json, sys
m = json.load(open(sys.argv[1]))
m["rows"].append(dict(m["rows"][0], index=5, name="../../zz", job="zz.json"))
json.dump(m, open(sys.argv[1], "w"))
EOF
"$dform" batch --merge F >/dev/null 2>&1
grep -q 'zz' F/gallery.html 2>/dev/null && grep -q 'href="\.\./\.\./zz' F/gallery.html && fail "the gallery links to a forged row's ../../zz"
no_leftovers "batches"

# --- Edges ----------------------------------------------------------------------------------------
# One number grammar: a number no double holds is out of range (exit 4) in OBJ and JSON alike.
for number in 1e999 1e-999; do
  printf 'v 0 0 0\nv %s 0 0\nv 1 1 0\nv 0 1 1\nv 2 2 2\nl 1 2 3 4 5 1\n' "$number" >n.obj
  expect "OBJ $number" 4 "'$number' is out of range" -- "$dform" inverse n.obj -q -o o-num
  printf '{"points": [[0, 0, 0], [%s, 0, 0], [1, 1, 0], [0, 1, 1], [2, 2, 2]]}' "$number" >n.json
  expect "JSON $number" 4 "'$number' is out of range" -- "$dform" inverse n.json -q -o o-num
done
# A negative or zero root size is refused by name, not mirrored or read as no shape.
for size in -300mm 0mm; do
  echo "<svg xmlns='http://www.w3.org/2000/svg' width='$size' height='300mm' viewBox='0 0 300 300'><circle cx='150' cy='150' r='100'/></svg>" >root.svg
  expect "root width $size" 4 "root.svg: has a root 'width' of $size" -- "$dform" forward root.svg "$fwd/circle.svg" -q -o o-root
done
# A failed run creates nothing: not its folder, not the folder's parents.
expect "a failed run in new folders" 3 "nowhere.svg" -- "$dform" forward nowhere.svg "$fwd/circle.svg" -q -o new/deeper/out
[ -e new ] && fail "a failed run created new/deeper"
# A sweep that solves no start fails as forward does (unequal perimeters: 4), creates nothing
# and leaves an earlier sweep where it was.
expect "a sweep solving no start" 4 "the perimeters differ" -- \
  "$dform" sweep "$fwd/circle.svg" "$fwd/ellipses-a.svg" --starts 2 -q -o new/deeper/sweep
[ -e new ] && fail "a sweep that solved nothing created new/deeper"
before=$(find W -type f -exec sha256sum {} + | sort)
expect "a sweep solving no start over an earlier sweep" 4 "the perimeters differ" -- \
  "$dform" sweep "$fwd/circle.svg" "$fwd/ellipses-a.svg" --starts 2 -q -o W
[ "$(find W -type f -exec sha256sum {} + | sort)" = "$before" ] || fail "a sweep that solved nothing replaced W"
# validate checks what report.json says of how the result was made.
"$dform" forward $pair --resolution 30 --model paper --no-export -q -o paper >/dev/null 2>&1 || fail "the paper run"
cp paper/report.json paper-report.json
"$dform" validate paper >/dev/null 2>&1 || fail "the paper result does not validate"
for edit in 'r["model"]["name"] = "exact"' 'r["schema_version"] = 99' 'r["metrics"]["extra_figure"] = 1' \
  'r["inputs"] = {}' 'r["job"]["resolution"] = 60' 'r["job"]["piece_a"] = "/elsewhere/other.svg"'; do
  python3 -c "import json; r = json.load(open('paper-report.json')); $edit; json.dump(r, open('paper/report.json', 'w'))"
  run "$dform" validate paper
  [ "$got" = 7 ] || fail "validate of a report.json with $edit: exit $got"
done
cp paper-report.json paper/report.json
# An exact result relabelled paper or general keeps the exact engine's entries: refused too.
"$dform" forward $pair --resolution 30 --no-export -q -o exact >/dev/null 2>&1 || fail "the exact run"
cp exact/report.json exact-report.json
for name in paper general; do
  python3 -c "import json; r = json.load(open('exact-report.json')); r['model']['name'] = '$name'; json.dump(r, open('exact/report.json', 'w'))"
  run "$dform" validate exact
  [ "$got" = 7 ] || fail "validate of an exact result relabelled $name: exit $got"
done
cp exact-report.json exact/report.json
no_leftovers "edges"

if [ "$failures" -gt 0 ]; then
  echo "$failures probe(s) failed" >&2
  exit 1
fi
echo "every safety probe ended as documented"
