#!/bin/sh
# SPDX-License-Identifier: GPL-3.0-or-later
# Runs every benchmark of docs/benchmarks.md on one build and writes their raw output to OUT
# (machine, commit, load average before and after each), and the two plots to docs/images/.
#
#   tests/bench/run_all.sh BUILD OUT      e.g. tests/bench/run_all.sh build /tmp/bench
#
# About 22 minutes on a 2-core machine; run it on a quiet machine, nothing else building. A
# benchmark that fails leaves its message in its file and the others still run.
set -u
root=$(cd "$(dirname "$0")/../.." && pwd)
build=$(cd "$1" && pwd)
out=$2
mkdir -p "$out"
bench=$build/tests/bench/dform_bench
# Debian's python3, which has python3-selenium for the studio bench, whatever else is first on
# the PATH (as the build's DFORM_PYTHON3).
python=/usr/bin/python3
load() { echo "$1: $(cut -d' ' -f1-3 /proc/loadavg)" >>"$out/load.txt"; }
{
  git -C "$root" log -1 --format='commit %h %cs %s'
  lscpu | grep -E '^Model name|^CPU\(s\)'
  grep MemTotal /proc/meminfo
  echo "kernel $(uname -r); $(g++ --version | head -1)"
} >"$out/machine.txt"
: >"$out/load.txt"
load "start"
"$bench" --repeats 3 >"$out/rows.txt" 2>&1; load "rows"
"$bench" --export --repeats 3 >"$out/export.txt" 2>&1; load "export"
"$bench" --scale --repeats 3 --plot "$root/docs/images/scaling.svg" >"$out/scale.txt" 2>&1
load "scale"
"$bench" --accuracy --repeats 3 --plot "$root/docs/images/accuracy-per-second.svg" \
  >"$out/accuracy.txt" 2>&1
load "accuracy"
"$python" "$root/tests/bench/cli_tables.py" "$build/dform" "$root/samples" >"$out/cli.txt" 2>&1
load "cli tables"
"$python" "$root/tests/bench/stop_latency.py" "$build/dform" "$root/samples" >"$out/stop.txt" 2>&1
load "stop latency"
"$python" "$root/tests/bench/studio_latency.py" "$build/dform" "$root/samples" >"$out/studio.txt" 2>&1
load "studio latency"
"$python" "$root/tests/bench/studio_latency.py" "$build/dform" "$root/samples" --instant \
  >"$out/studio-instant.txt" 2>&1
load "studio latency, instant answers"
"$python" "$root/tests/bench/studio_latency.py" "$build/dform" "$root/samples" --paper \
  --positions 50 --pause 0.1 >"$out/studio-paper.txt" 2>&1
load "studio latency, paper model"
"$python" "$root/tests/bench/studio_latency.py" "$build/dform" "$root/samples" --paper \
  --positions 120 --pause 0.0167 >"$out/studio-paper-60hz.txt" 2>&1
load "studio latency, paper model at 60 Hz"
"$bench" --starts --repeats 3 >"$out/starts.txt" 2>&1
load "solve of the non-convex pair from 40 starts"
echo "done: $out"
