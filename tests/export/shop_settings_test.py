#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""The hinge and the tick numbers reach the export from the command line and from a job file, as
the settings table (pipeline/settings.h) reads them, and report.json keeps them:

- `--numbers face|tabs|both` (forward and `dform export DIR`) and a job's "numbers": with `face`
  no number is on a tab, with `tabs` numbers move onto the tabs off the face, with `both` the
  tabs' numbers and the face's are both drawn;
- `--no-hinge` and a job's "hinge": false draw no hinge in plywood, `--hinge`, "hinge": true (or
  unset) draw one; "hinge": true on card is refused (exit 2, one line naming the setting) and
  writes nothing;
- report.json's job keeps the numbers and the hinge given (forward and run).

usage: shop_settings_test.py DFORM SAMPLES_DIR WORK_DIR
"""
import json
import os
import re
import shutil
import sys

from e2e_checks import check, failures, runner

DFORM, SAMPLES, WORK = sys.argv[1], os.path.abspath(sys.argv[2]), sys.argv[3]
A = os.path.join(SAMPLES, "forward", "ellipses-a.svg")
B = os.path.join(SAMPLES, "forward", "ellipses-b.svg")
SOLVE = ["--model", "exact", "--resolution", "60"]
run = runner(DFORM)


def fresh(name):
    out = os.path.join(WORK, name)
    shutil.rmtree(out, ignore_errors=True)
    return out


def labels(out):
    """(numbers on tabs, numbers on the face) in pattern.svg."""
    with open(os.path.join(out, "pattern.svg")) as f:
        svg = f.read()
    return (len(re.findall(r'id="[AB]-tick-\d+-tab-label"', svg)),
            len(re.findall(r'id="[AB]-tick-\d+-label"', svg)))


def hinges(out):
    with open(os.path.join(out, "pattern.json")) as f:
        return sum(len(p.get("hinges", [])) for p in json.load(f)["pieces"])


def exported(out):
    with open(os.path.join(out, "report.json")) as f:
        return json.load(f)["job"]["export"]


def ran(r, what):
    check(r.returncode == 0, f"{what}: exit {r.returncode}: {r.stderr.strip()}")


def job(name, export):
    path = os.path.join(WORK, name + ".json")
    with open(path, "w") as f:
        json.dump({"mode": "forward", "piece_a": A, "piece_b": B, "model": "exact",
                   "resolution": 60, "export": export}, f)
    return path


os.makedirs(WORK, exist_ok=True)
solved = fresh("solved")
ran(run("forward", A, B, *SOLVE, "--no-export", "-q", "-o", solved), "solve")

# Numbers: dform export DIR --numbers, then forward --numbers and a job file agree with it.
by = {}
for numbers in ("face", "tabs", "both"):
    out = fresh("export-" + numbers)
    ran(run("export", solved, "--profile", "print", "--numbers", numbers, "-q", "-o", out),
        f"export --numbers {numbers}")
    by[numbers] = labels(out)
face, tabs, both = by["face"], by["tabs"], by["both"]
check(face[0] == 0 and face[1] > 20, f"--numbers face: {face}")
check(tabs[0] > 10 and tabs[1] < face[1], f"--numbers tabs: {tabs} against face {face}")
check(both == (tabs[0], face[1]), f"--numbers both: {both}, tabs {tabs}, face {face}")
out = fresh("forward-both")
ran(run("forward", A, B, *SOLVE, "--profile", "print", "--numbers", "both", "-q", "-o", out),
    "forward --numbers both")
check(labels(out) == both and exported(out).get("numbers") == "both",
      f"forward --numbers both: {labels(out)}, export {both}, report.json {exported(out)}")
out = fresh("job-both")
ran(run("run", job("both", {"profile": "print", "numbers": "both"}), "-q", "-o", out), "job both")
check(labels(out) == both and exported(out).get("numbers") == "both",
      f"job numbers both: {labels(out)}, {exported(out)}")

# The hinge: on by default in plywood, off by --no-hinge or "hinge": false.
cases = [("forward-plywood", ["forward", A, B, *SOLVE, "--material", "plywood"], True),
         ("forward-no-hinge", ["forward", A, B, *SOLVE, "--material", "plywood", "--no-hinge"],
          False),
         ("export-no-hinge", ["export", solved, "--material", "plywood", "--no-hinge"], False),
         ("export-hinge", ["export", solved, "--material", "plywood", "--hinge"], True),
         ("job-hinge-off", ["run", job("off", {"material": "plywood", "hinge": False})], False),
         ("job-hinge-on", ["run", job("on", {"material": "plywood", "hinge": True})], True)]
for name, args, drawn in cases:
    out = fresh(name)
    ran(run(*args, "-q", "-o", out), name)
    check((hinges(out) > 0) == drawn, f"{name}: {hinges(out)} hinges")
    if args[0] != "export" and ("--no-hinge" in args or name.startswith("job")):
        check(exported(out).get("hinge") == drawn, f"{name}: report.json {exported(out)}")
out = fresh("job-card")
r = run("run", job("card", {"material": "card", "hinge": True}), "-q", "-o", out)
lines = r.stderr.strip().splitlines()
check(r.returncode == 2 and len(lines) == 1 and "hinge" in lines[0] and not os.path.exists(out),
      f"hinge on card: exit {r.returncode}, {lines}")

sys.exit(1 if failures else 0)
