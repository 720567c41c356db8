#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""--score-folds end to end: circle + square (exact model, resolution 100: 4 creases at ~66.7 deg
and gentle folds under 6 deg) exported with --score-folds DEG puts exactly the gentle folds of
report.json's model.folds with angle_deg >= DEG (the creases are drawn as crease lines already,
never scored twice) on the SCORE layer of pattern.svg and
pattern.dxf (read back with ezdxf) and in pattern.json, every line inside its piece;
`dform export` of the saved result draws the same lines; a paper-model result warns; bad values
exit 2 naming the option.

usage: score_folds_test.py DFORM SAMPLES_DIR WORK_DIR
"""
import json
import os
import re
import shutil
import sys

import ezdxf

from e2e_checks import check, failures, runner

DFORM, SAMPLES, WORK = sys.argv[1:4]
CIRCLE = os.path.join(SAMPLES, "forward", "circle.svg")
SQUARE = os.path.join(SAMPLES, "forward", "square.svg")
run = runner(DFORM)


def forward(out, *extra):
    shutil.rmtree(out, ignore_errors=True)
    r = run("forward", CIRCLE, SQUARE, "--model", "exact", "--resolution", "100", "-o", out, "-q",
            *extra)
    check(r.returncode == 0, f"forward {extra} exit {r.returncode}: {r.stderr.strip()}")
    return r


def svg_score_ids(out):
    text = open(os.path.join(out, "pattern.svg")).read()
    score = text[text.index('inkscape:label="Score"'):]
    score = score[:score.index("</g>")]
    return re.findall(r'id="([AB]-body-fold-\d+)', score)


def dxf_score_count(out):
    doc = ezdxf.readfile(os.path.join(out, "pattern.dxf"))
    return sum(1 for e in doc.modelspace() if e.dxf.layer == "SCORE")


def inside(loops, q):  # even-odd over every loop
    x, y = q
    n = 0
    for loop in loops:
        for (x0, y0), (x1, y1) in zip(loop, loop[1:] + loop[:1]):
            if (y0 > y) != (y1 > y) and x < x0 + (y - y0) * (x1 - x0) / (y1 - y0):
                n += 1
    return n % 2 == 1


def scored(out):
    pattern = json.load(open(os.path.join(out, "pattern.json")))
    lines = {}
    for piece in pattern["pieces"]:
        for f in piece.get("score_lines", []):
            check(f["kind"] == "fold", f"{f['id']}: kind {f['kind']}")
            lines[f["id"]] = (f["angle_deg"], f["lines"])
            for line in f["lines"]:
                check(len(line) >= 2, f"{f['id']}: a line of {len(line)} points")
                for a, b in zip(line, line[1:]):  # every segment's midpoint inside the material
                    mid = ((a[0] + b[0]) / 2, (a[1] + b[1]) / 2)
                    check(inside(piece["boundaries"], mid), f"{f['id']}: a line outside its piece")
    return lines


base = os.path.join(WORK, "none")
forward(base)
folds = json.load(open(os.path.join(base, "report.json")))["model"]["folds"]
check(sum(f["crease"] for f in folds) == 4 and len(folds) > 50, f"{len(folds)} folds")
base_dxf = dxf_score_count(base)
check(svg_score_ids(base) == [], "score lines without --score-folds")

# A threshold equal to a fold's angle (as report.json writes it) scores that fold: at least DEG.
gentle = sorted(f["angle_deg"] for f in folds if not f["crease"])
middle = repr(gentle[len(gentle) // 2])
for deg in ["10", "90", "0.5", middle]:
    out = os.path.join(WORK, "deg-" + deg)
    forward(out, "--score-folds", deg)
    want = sorted(a for a in gentle if a >= float(deg))
    lines = scored(out)
    check(sorted(a for a, _ in lines.values()) == want,
          f"--score-folds {deg}: pattern.json lists {len(lines)} folds, {len(want)} expected")
    check(sorted(svg_score_ids(out)) == sorted(lines),
          f"--score-folds {deg}: SVG score lines {len(svg_score_ids(out))}, pattern.json {len(lines)}")
    parts = sum(len(l) for _, l in lines.values())
    check(dxf_score_count(out) - base_dxf == parts,
          f"--score-folds {deg}: {dxf_score_count(out) - base_dxf} more DXF SCORE entities, {parts} expected")
    if deg == "10":
        check(want == [], f"--score-folds 10: {len(want)} folds; the 4 creases are crease lines")
    if deg == middle:
        check(0 < len(want) < len(gentle),
              f"--score-folds {deg}: {len(want)} of {len(gentle)} gentle folds: not a split")
        saved = scored(out)
        r = run("export", out, "--score-folds", deg, "-q")
        check(r.returncode == 0, f"export exit {r.returncode}: {r.stderr.strip()}")
        check(scored(out) == saved, "dform export gives other score lines than the run")
    if deg == "90":
        check(want == [], "folds of 90 degrees or more")

paper = os.path.join(WORK, "paper")
shutil.rmtree(paper, ignore_errors=True)
r = run("forward", CIRCLE, SQUARE, "--model", "paper", "-o", paper, "--score-folds", "10")
check(r.returncode == 0 and "no folds known: the paper model's result has none" in r.stderr,
      f"paper model: exit {r.returncode}, no warning: {r.stderr.strip()}")
check(scored(paper) == {}, "paper model: score lines")

for bad in ["-1", "nan", "181", "ten"]:
    r = run("forward", CIRCLE, SQUARE, "-o", os.path.join(WORK, "bad"), "--score-folds", bad)
    lines = r.stderr.strip().splitlines()
    check(r.returncode == 2 and len(lines) == 1 and "--score-folds" in lines[0],
          f"--score-folds {bad}: exit {r.returncode}, {lines}")
    r = run("export", base, "--score-folds", bad)
    check(r.returncode == 2, f"export --score-folds {bad}: exit {r.returncode}")

sys.exit(1 if failures else 0)
