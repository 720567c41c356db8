#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""--json on every command: exactly one JSON object on stdout, valid against
docs/cli-output.schema.json, for success, a usage error, an input error and a failed gate.

    json_contract.py DFORM SAMPLES SCHEMA
"""
import json
import os
import signal
import subprocess
import sys
import tempfile

import jsonschema

dform, samples, schema_path = sys.argv[1:4]
validator = jsonschema.Draft202012Validator(json.load(open(schema_path)))
failures = []
fwd = os.path.join(samples, "forward")
pair = [os.path.join(fwd, "ellipses-a.svg"), os.path.join(fwd, "ellipses-b.svg")]
saddle = os.path.join(samples, "inverse", "saddle.obj")


def check(name, args, exit_code, error_code=None, setting=None, expect=None):
    """Runs dform ARGS --json; one schema-valid object with EXIT_CODE and ERROR_CODE."""
    done = subprocess.run([dform, *args, "--json"], capture_output=True, text=True, timeout=600)
    try:
        out = json.loads(done.stdout)
    except json.JSONDecodeError as e:
        failures.append(f"{name}: stdout is not one JSON object ({e}): {done.stdout[:300]!r}")
        return None
    for problem in validator.iter_errors(out):
        failures.append(f"{name}: {problem.message} at {list(problem.path)}")
    if done.returncode != exit_code or out.get("exit_code") != exit_code:
        failures.append(f"{name}: exit {done.returncode} (object says {out.get('exit_code')}), "
                        f"expected {exit_code}: {done.stderr[:300]}")
    got = (out.get("error") or {}).get("code")
    if got != error_code:
        failures.append(f"{name}: error code {got}, expected {error_code}")
    if setting is not None and (out.get("error") or {}).get("setting") != setting:
        failures.append(f"{name}: error setting {(out.get('error') or {}).get('setting')}, "
                        f"expected {setting}")
    if error_code and out["error"]["message"] not in done.stderr:
        failures.append(f"{name}: the object's message is not the one on stderr")
    for key in expect or []:
        if key not in out:
            failures.append(f"{name}: no '{key}' in {sorted(out)}")
    return out


work = tempfile.mkdtemp(prefix="dform-json-")
os.chdir(work)
tight = os.path.join(work, "tight.json")
json.dump({"version": 1, "name": "tight", "limits": {"L_error": 1e-9}}, open(tight, "w"))
quick = ["--resolution", "30"]

# forward
check("forward", ["forward", *pair, *quick, "--no-export", "-o", "F"], 0,
      expect=["mode", "model", "figures", "gate", "output", "files"])
check("forward, usage", ["forward", *pair, "--resolution", "2", "-o", "F2"], 2, "usage",
      setting="resolution")
check("forward, no such input", ["forward", "missing.svg", pair[1], "-o", "F3"], 3,
      "input_unreadable")
out = check("forward, failed gate", ["forward", *pair, *quick, "--model", "paper", "--gate", tight,
                                     "-o", "P"], 7, "gate_failed", expect=["gate", "figures"])
if out and out.get("gate", {}).get("passed") is not False:
    failures.append("forward, failed gate: gate.passed is not false")
# inverse
check("inverse", ["inverse", saddle, *quick, "--no-export", "-o", "I"], 0,
      expect=["mode", "figures"])
check("inverse, usage", ["inverse", saddle, "--resolution", "2", "-o", "I2"], 2, "usage",
      setting="resolution")
check("inverse, no such input", ["inverse", "missing.obj", "-o", "I3"], 3, "input_unreadable")
tight_inverse = os.path.join(work, "tight-inverse.json")
json.dump({"version": 1, "name": "tight", "limits": {"L_max": 1e-16}},
          open(tight_inverse, "w"))
check("inverse, failed gate", ["inverse", saddle, *quick, "--gate", tight_inverse, "-o", "I4"], 7,
      "gate_failed")
# run
job = {"mode": "forward", "piece_a": pair[0], "piece_b": pair[1], "resolution": 30}
json.dump(job, open("job.json", "w"))
json.dump({**job, "model": "paper", "gate": tight}, open("tight-job.json", "w"))
check("run", ["run", "job.json", "--no-export", "-o", "J"], 0, expect=["mode", "figures"])
check("run, usage", ["run", "job.json", "--bogus", "-o", "J2"], 2, "usage")
check("run, no such input", ["run", "missing.json", "-o", "J3"], 3, "input_unreadable")
check("run, failed gate", ["run", "tight-job.json", "-o", "J4"], 7, "gate_failed")
# sweep: a start whose gate fails is a row, not an error
check("sweep", ["sweep", *pair, *quick, "--starts", "2", "--no-export", "-o", "W"], 0,
      expect=["starts", "output"])
check("sweep, usage", ["sweep", *pair, "--starts", "0", "-o", "W2"], 2, "usage")
check("sweep, no such input", ["sweep", "missing.svg", pair[1], "-o", "W3"], 3,
      "input_unreadable")
out = check("sweep, failed gates", ["sweep", *pair, *quick, "--starts", "2", "--model", "paper",
                                    "--gate", tight, "--no-export", "-o", "W4"], 0)
if out and any(s["gate_passed"] is not False for s in out.get("starts", [])):
    failures.append("sweep, failed gates: a start's gate_passed is not false")
# batch
os.mkdir("jobs")
json.dump(job, open("jobs/one.json", "w"))
os.mkdir("tight-jobs")
json.dump({**job, "model": "paper", "gate": tight}, open("tight-jobs/one.json", "w"))
check("batch", ["batch", "jobs", "--no-export", "-o", "B"], 0, expect=["jobs", "manifest"])
check("batch, usage", ["batch", "jobs", "--shard", "3/2", "-o", "B2"], 2, "usage")
check("batch, no such input", ["batch", "missing", "-o", "B3"], 3, "input_unreadable")
check("batch, failed gate", ["batch", "tight-jobs", "-o", "B4"], 7, "gate_failed")
# export (R: a result with its export; P: the paper result that failed the tight gate)
subprocess.run([dform, "forward", *pair, *quick, "-q", "-o", "R"], check=True)
check("export", ["export", "R", "-o", "E"], 0, expect=["profile", "output", "files"])
check("export, usage", ["export"], 2, "usage")
check("export, no such input", ["export", "missing", "-o", "E2"], 3, "input_unreadable")
check("export, failed gate", ["export", "P", "-o", "E3"], 7, "gate_failed",
      setting="export.export_anyway")
check("export, the profiles", ["export", "--list-profiles"], 0, expect=["profiles"])
# validate
check("validate", ["validate", "R"], 0, expect=["figures", "gate", "files"])
check("validate, usage", ["validate"], 2, "usage")
check("validate, no such input", ["validate", "missing"], 3, "input_unreadable")
check("validate, failed gate", ["validate", "P", "--gate", tight], 7, "gate_failed")
# studio: the object when it is up, then nothing more
check("studio, usage", ["studio", "a", "b", "c", "--no-browser"], 2, "usage")
check("studio, no such input", ["studio", "missing.svg", pair[1], "--no-browser"], 3,
      "input_unreadable")
studio = subprocess.Popen([dform, "studio", "--no-browser", "--json"], stdout=subprocess.PIPE,
                          stderr=subprocess.PIPE, text=True)
first = ""
while True:
    line = studio.stdout.readline()
    if not line:
        break
    first += line
    if line.startswith("}"):
        break
studio.send_signal(signal.SIGINT)
rest, _ = studio.communicate(timeout=60)
try:
    up = json.loads(first)
    for problem in validator.iter_errors(up):
        failures.append(f"studio: {problem.message}")
    if not up.get("url", "").startswith("http://127.0.0.1:") or up["exit_code"] != 0:
        failures.append(f"studio: {up}")
except json.JSONDecodeError:
    failures.append(f"studio: no JSON object when it was up: {first[:300]!r}")
if rest.strip():
    failures.append(f"studio: more on stdout after the object: {rest[:200]!r}")
# no command at all
out = check("no command", ["bogus"], 2, "usage")
if out and out["command"] is not None:
    failures.append("no command: command is not null")

if failures:
    print("\n".join(failures), file=sys.stderr)
    sys.exit(1)
print("every command printed one valid object")
