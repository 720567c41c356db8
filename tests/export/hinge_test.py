#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Kerf-bending hinges end to end: the ellipses and circle + square in plywood (exact model,
resolution 100) and the shipped squaricle job (the ruled engine's creases), where the hinge is on
by default. Against report.json's model.folds (the body's fold lines, in each piece's flat mm)
and pattern.json's hinges:

- every fold above 2 degrees belongs to a hinge of its piece, drawn at its true length, and (the
  ellipses and circle + square) is flanked by slits parallel to it within 2 degrees (unless the
  whole fold lies in the seam margin);
- no slit comes within the solid margin of the seam (hole edge + half a hole + the thickness) or
  of a joint hole, and slits are straight, apart from each other and from every cut loop, so each
  piece stays one part (one outer cut loop);
- each row with slits allows a radius of its pitch over the plywood's row angle, a row without
  none (null); each fold's allowed radius is the loosest of the rows with slits across its band,
  and it is met (radius_met) exactly where some row there has slits and the material bends as
  tightly as the fold needs: every fold the plywood can follow is met; every fold it cannot
  (circle + square's and the squaricle's creases, a 4.7 mm radius against plywood's 46.9 mm) is
  not, and a warning (stderr and pattern.json) names its hinge and the fold by its index;
- each fold's stretches within the seam margin (in_seam_margin, in_seam_margin_mm) are the
  stretches of its line that the test finds within the margin of the outline, and no slit beside
  the fold reaches along them; a fold's bend_deg (its share of the rows with slits across its
  band) is at most its rows' and adds up to the hinge's bend_deg within one row angle;
- where no message says otherwise, the rows with slits bend at least as far as the hinge's folds;
- the DXF (ezdxf) has one open CUT polyline per slit; `dform export` of the saved result draws
  the same hinges; --scale 50% draws the folds at half length; --no-hinge draws none;
- --hinge on card, slots in plywood: exit 2 naming the setting; a paper-model result warns.

usage: hinge_test.py DFORM SAMPLES_DIR WORK_DIR
"""
import json
import math
import os
import re
import shutil
import sys

import ezdxf

from e2e_checks import check, failures, runner

DFORM, SAMPLES, WORK = sys.argv[1:4]
F = os.path.join(SAMPLES, "forward")
PAIRS = {"ellipses": (os.path.join(F, "ellipses-a.svg"), os.path.join(F, "ellipses-b.svg")),
         "circle-square": (os.path.join(F, "circle.svg"), os.path.join(F, "square.svg"))}
ROW_DEG = 90.0 / 23  # plywood's row angle (profile.cpp's preset)
ROW_MM = 3.2
TIGHTEST = ROW_MM / math.radians(ROW_DEG)  # 46.9 mm: the tightest radius plywood bends to
MARGIN = 6.0 + 0.5 * 4.0 + 3.0  # plywood: hole edge 6, hole 4 mm, 3 mm thick
run = runner(DFORM)


def forward(name, out, *extra):
    shutil.rmtree(out, ignore_errors=True)
    if name == "squaricle":  # the shipped job: its creases run in the ruled engine
        r = run("run", os.path.join(F, "squaricle.json"), "-o", out, "-q", *extra)
        check(r.returncode == 0, f"{name} {extra}: exit {r.returncode}: {r.stderr.strip()}")
        return r
    a, b = PAIRS[name]
    r = run("forward", a, b, "--model", "exact", "--resolution", "100", "-o", out, "-q", *extra)
    check(r.returncode == 0, f"{name} {extra}: exit {r.returncode}: {r.stderr.strip()}")
    return r


def dist_point_segment(q, a, b):
    ax, ay = a
    bx, by = b
    dx, dy = bx - ax, by - ay
    n2 = dx * dx + dy * dy
    t = 0.0 if n2 == 0 else max(0.0, min(1.0, ((q[0] - ax) * dx + (q[1] - ay) * dy) / n2))
    return math.hypot(ax + t * dx - q[0], ay + t * dy - q[1])


def segments_cross(a, b, c, d):
    def orient(p, q, r):
        return (q[0] - p[0]) * (r[1] - p[1]) - (q[1] - p[1]) * (r[0] - p[0])
    return (orient(a, b, c) * orient(a, b, d) < 0) and (orient(c, d, a) * orient(c, d, b) < 0)


def dist_segments(a, b, c, d):
    if segments_cross(a, b, c, d):
        return 0.0
    return min(dist_point_segment(a, c, d), dist_point_segment(b, c, d),
               dist_point_segment(c, a, b), dist_point_segment(d, a, b))


def dist_to_loop(a, b, loop):
    return min(dist_segments(a, b, p, q) for p, q in zip(loop, loop[1:] + loop[:1]))


def angle_between(u, v):  # of two undirected lines, degrees
    cross = abs(u[0] * v[1] - u[1] * v[0])
    dot = abs(u[0] * v[0] + u[1] * v[1])
    return math.degrees(math.atan2(cross, dot))


def direction(line):
    return (line[-1][0] - line[0][0], line[-1][1] - line[0][1])


def hinges_of(out):
    pattern = json.load(open(os.path.join(out, "pattern.json")))
    return pattern, {p["name"]: p.get("hinges", []) for p in pattern["pieces"]}


def overlap(a0, a1, b0, b1):
    return min(a1, b1) - max(a0, b0)


def on_line(q, a, b):
    return dist_point_segment(q, a, b) < 1e-6


def check_margin(name, hid, f, outline):
    """The fold's stretches within the seam margin are where its line is within MARGIN of the
    outline: their middles inside, their ends inside the fold at the margin's edge, and their
    length that of the line's samples within the margin."""
    fa, fb = f["line"]
    parts = f["in_seam_margin"]
    total = sum(math.dist(*part) for part in parts)
    check(abs(total - f["in_seam_margin_mm"]) < 1e-9, f"{name}: {hid}: in_seam_margin_mm")
    for part in parts:
        check(all(on_line(q, fa, fb) for q in part), f"{name}: {hid}: a margin part off its fold")
        mid = ((part[0][0] + part[1][0]) / 2, (part[0][1] + part[1][1]) / 2)
        check(dist_to_loop(mid, mid, outline) < MARGIN, f"{name}: {hid}: a margin part outside it")
        for q in part:
            if min(math.dist(q, fa), math.dist(q, fb)) > 1e-6:
                g = dist_to_loop(q, q, outline)
                check(abs(g - MARGIN) < 0.02, f"{name}: {hid}: a margin part ends {g:.3f} mm in")
    length = math.dist(fa, fb)
    steps = max(1, int(length / 2.0))
    sampled = sum(length / steps for k in range(steps)
                  if dist_to_loop(*(2 * [(fa[0] + (k + 0.5) / steps * (fb[0] - fa[0]),
                                          fa[1] + (k + 0.5) / steps * (fb[1] - fa[1]))]),
                                  outline) < MARGIN)
    check(abs(sampled - total) <= (length / steps) * (2 * len(parts) + 1),
          f"{name}: {hid}: fold {f['fold']}: {total:.2f} mm in the margin, {sampled:.2f} sampled")
    for end in (fa, fb):  # a fold ending on the seam has its end in the margin
        if dist_to_loop(end, end, outline) < MARGIN - 0.02:
            check(any(on_line(end, *part) for part in parts),
                  f"{name}: {hid}: fold {f['fold']}'s end in the margin is not in in_seam_margin")


def check_bands(name, hinge, outline):
    """The hinge's folds and rows across it: the bands and the rows' cells tile it; each radius is
    what they say; a fold is met exactly where rows with slits bend there as tightly as it needs,
    and always where the plywood can bend that tightly and a row there has slits. Returns the
    (hinge id, fold) pairs plywood cannot follow."""
    hid = hinge["id"]
    folds, rows = hinge["folds"], hinge["rows"]
    at = 0.0
    for f in folds:
        lo, hi = f["band_mm"]
        check(abs(lo - at) < 1e-9, f"{name}: {hid}: fold {f['fold']}'s band at {lo}, not {at}")
        want = (hi - lo) / math.radians(f["angle_deg"])
        check(abs(f["radius_needed_mm"] - want) <= 1e-9 * want, f"{name}: {hid}: band radius")
        at = hi
    end, at = at, 0.0
    for r in rows:
        check(abs(r["from_mm"] - at) < 1e-9, f"{name}: {hid}: a row at {r['from_mm']}, not {at}")
        at = r["from_mm"] + r["pitch_mm"]
        cell = (r["from_mm"], min(at, end))
        loose = [f["radius_needed_mm"] for f in folds if overlap(*cell, *f["band_mm"]) > 1e-9]
        tight = [f["radius_needed_mm"] for f in folds if overlap(*cell, *f["band_mm"]) > -1e-9]
        need = r["radius_needed_mm"]
        check(loose and min(tight) <= need <= min(loose), f"{name}: {hid}: a row's needed radius")
        if r["cuts"]:  # as tight as the cell needs, or as tight as plywood bends
            check(r["radius_allowed_mm"] <= need * (1 + 1e-9) or
                  (abs(r["pitch_mm"] - ROW_MM) < 1e-9 and need < TIGHTEST),
                  f"{name}: {hid}: a row allows {r['radius_allowed_mm']:.2f} mm, needs {need:.2f}")
    check(rows and at >= end - 1e-9 and rows[-1]["from_mm"] < end, f"{name}: {hid}: rows' span")
    flagged = []
    for f in folds:
        band = f["band_mm"]
        cut = [r for r in rows if r["cuts"]]
        loose = [r["radius_allowed_mm"] for r in cut
                 if overlap(r["from_mm"], r["from_mm"] + r["pitch_mm"], *band) > 1e-9]
        tight = [r["radius_allowed_mm"] for r in cut
                 if overlap(r["from_mm"], r["from_mm"] + r["pitch_mm"], *band) > -1e-9]
        allowed = f["radius_allowed_mm"]
        if allowed is None:
            check(not loose, f"{name}: {hid}: fold {f['fold']} has rows with slits, no radius")
        else:
            check(loose and max(loose) <= allowed <= max(tight),
                  f"{name}: {hid}: fold {f['fold']} allows {allowed}, its rows {tight}")
        bend = sum(ROW_DEG * max(0.0, overlap(r["from_mm"], r["from_mm"] + r["pitch_mm"], *band)) /
                   r["pitch_mm"] for r in cut)
        check(abs(f["bend_deg"] - bend) < 1e-6, f"{name}: {hid}: fold {f['fold']} bend_deg")
        need = f["radius_needed_mm"]
        met = allowed is not None and allowed <= need * (1 + 1e-9)
        check(f["radius_met"] == met, f"{name}: {hid}: fold {f['fold']} radius_met")
        if need >= TIGHTEST * (1 + 1e-9) and allowed is not None:
            check(met, f"{name}: {hid}: fold {f['fold']} needs {need:.2f} mm, gets {allowed:.2f}")
        if need < TIGHTEST * (1 - 1e-9):
            check(not met, f"{name}: {hid}: fold {f['fold']} needs {need:.2f} mm, met")
            flagged.append((hid, f["fold"]))
        check_margin(name, hid, f, outline)
    total = sum(f["bend_deg"] for f in folds)
    check(total <= hinge["bend_deg"] + 1e-6 and total >= hinge["bend_deg"] - ROW_DEG - 1e-6,
          f"{name}: {hid}: its folds bend {total:.3f} of its rows' {hinge['bend_deg']:.3f} degrees")
    return flagged


def check_warnings(name, warnings, stderr, flagged):
    """A warning per hinge with folds plywood cannot follow, naming exactly those folds, in
    pattern.json and on stderr; none for the others."""
    named = {}
    for w in warnings:
        hid, _, rest = w.partition(": ")
        check("bends to a radius of 46.9 mm" in rest and "needs less at fold" in rest,
              f"{name}: warning {w}")
        listed = rest.split("needs less at ")[-1].split(" of report.json")[0]
        named[hid] = {int(k) for k in re.findall(r"(\d+) \(\d+\.\d mm\)", listed)}
        check(f"warning: export: {w}" in stderr, f"{name}: warning not on stderr: {w}")
    want = {}
    for hid, fold in flagged:
        want.setdefault(hid, set()).add(fold)
    check(named == want, f"{name}: warnings name {named}, folds plywood cannot follow {want}")
    return want


def check_pair(name, out):
    stderr = forward(name, out, "--material", "plywood").stderr
    folds = json.load(open(os.path.join(out, "report.json")))["model"]["folds"]
    pattern, hinges = hinges_of(out)
    messages = pattern["messages"]
    pieces = {p["name"]: p for p in pattern["pieces"]}
    check(set(pieces) == {"A", "B"}, f"{name}: pieces {sorted(pieces)}")
    holes = {n: [h for h in pattern["joint_holes"] if h["piece"] == n] for n in pieces}
    steep = [i for i, f in enumerate(folds) if f["angle_deg"] > 2]
    check(len(steep) > 10, f"{name}: {len(steep)} folds above 2 degrees")
    flanked = 0
    for i in steep:
        f = folds[i]
        piece = pieces[f["piece"]]
        owners = [h for h in hinges[f["piece"]] if any(hf["fold"] == i for hf in h["folds"])]
        check(len(owners) == 1, f"{name}: fold {i} in {len(owners)} hinges")
        if len(owners) != 1:
            continue
        hinge = owners[0]
        entry = next(hf for hf in hinge["folds"] if hf["fold"] == i)
        flat_len = math.dist(f["from_mm"], f["to_mm"])
        check(abs(math.dist(*entry["line"]) - flat_len) < 1e-6,
              f"{name}: fold {i} drawn {math.dist(*entry['line']):.4f} mm long, {flat_len:.4f} flat")
        check(abs(entry["angle_deg"] - f["angle_deg"]) < 1e-9, f"{name}: fold {i} angle")
        fa, fb = entry["line"]
        check(angle_between(direction(entry["line"]), hinge["direction"]) <= 2.0,
              f"{name}: fold {i} not parallel to {hinge['id']}")
        # Flanked: a slit parallel within 2 degrees, within half its row's pitch of the fold line
        # and beside it along the fold.
        d = direction(entry["line"])
        length = math.hypot(*d)
        u = (d[0] / length, d[1] / length)
        found = False
        for row in hinge["rows"]:
            for cut in row["cuts"]:
                mid = ((cut[0][0] + cut[-1][0]) / 2, (cut[0][1] + cut[-1][1]) / 2)
                across = abs((mid[0] - fa[0]) * u[1] - (mid[1] - fa[1]) * u[0])
                along = [(q[0] - fa[0]) * u[0] + (q[1] - fa[1]) * u[1] for q in cut]
                if (angle_between(direction(cut), d) <= 2.0 and
                        across <= 0.5 * row["pitch_mm"] + 1e-6 and
                        max(along) > 0 and min(along) < length):
                    found = True
        # A slit needs 8 mm of the fold's line outside the margin: 2 mm and a 3 mm bridge at
        # either end.
        steps = max(1, int(length / 0.25))
        room = 0.0 if found else sum(
            length / steps for k in range(steps)
            if dist_to_loop(*(2 * [(fa[0] + (k + 0.5) / steps * d[0],
                                    fa[1] + (k + 0.5) / steps * d[1])]),
                            piece["outline"]) >= MARGIN)
        if name in PAIRS:  # the bar: the ellipses and circle + square
            check(found or room < 8.0,
                  f"{name}: fold {i} ({f['angle_deg']:.2f} deg, {room:.1f} mm clear) has no slits")
        flanked += found
    if name in PAIRS:
        check(flanked > len(steep) // 2, f"{name}: {flanked} of {len(steep)} folds flanked")

    slits = []
    bent = [0]  # hinges that bend all their folds turn, as tightly as they turn
    flagged = []  # (hinge id, fold index) the plywood cannot follow
    for n, piece in pieces.items():
        check(len(piece["cut"]) == 1, f"{name}: piece {n} is cut as {len(piece['cut'])} loops")
        for hinge in hinges[n]:
            check(hinge["id"].startswith(n + "-hinge-"), f"{name}: hinge id {hinge['id']}")
            capacity = 0.0
            for row in hinge["rows"]:
                check(row["pitch_mm"] >= ROW_MM - 1e-9, f"{name}: {hinge['id']} pitch")
                if row["cuts"]:
                    capacity += math.radians(ROW_DEG)
                    check(row["radius_allowed_mm"] is not None and
                          abs(row["radius_allowed_mm"] - row["pitch_mm"] / math.radians(ROW_DEG))
                          < 1e-9, f"{name}: {hinge['id']}: allowed radius is not pitch / row angle")
                else:
                    check(row["radius_allowed_mm"] is None,
                          f"{name}: {hinge['id']}: a row without slits claims a radius")
                for cut in row["cuts"]:
                    check(len(cut) == 2, f"{name}: a slit of {len(cut)} points")
                    check(angle_between(direction(cut), hinge["direction"]) < 1e-6,
                          f"{name}: {hinge['id']}: a slit off the hinge's direction")
                    m = dist_to_loop(cut[0], cut[-1], piece["outline"])
                    check(m >= MARGIN - 1e-6, f"{name}: {hinge['id']}: a slit {m:.3f} mm from the seam")
                    for h in holes[n]:
                        g = dist_point_segment(h["centre"], cut[0], cut[-1]) - 0.5 * h["diameter_mm"]
                        check(g >= 1.0, f"{name}: a slit {g:.3f} mm from joint hole {h['index']}")
                    slits.append((n, cut))
            flagged += check_bands(name, hinge, piece["outline"])
            bend = sum(math.radians(f["angle_deg"]) for f in hinge["folds"])
            said = [m for m in messages if m.startswith(hinge["id"] + ":")]
            check(abs(hinge["turn_deg"] - math.degrees(bend)) < 1e-9, f"{name}: turn_deg")
            check(abs(hinge["bend_deg"] - math.degrees(capacity)) < 1e-6, f"{name}: bend_deg")
            short = capacity < bend * (1 - 1e-9)
            check(short == any("rows of slits bend" in m for m in said),
                  f"{name}: {hinge['id']} bends {math.degrees(capacity):.2f} of "
                  f"{math.degrees(bend):.2f} degrees, messages {said}")
            if not short and all(f["radius_met"] for f in hinge["folds"]):
                bent[0] += 1
    flagged = check_warnings(name, pattern.get("warnings", []), stderr, flagged)
    if name != "ellipses":  # creases: a radius of a few millimetres
        check(flagged, f"{name}: no fold too tight for plywood")
    check(len(slits) > 30, f"{name}: {len(slits)} slits")
    if name == "ellipses":  # circle + square's hinges all reach into the seam margin
        check(bent[0] > 0, f"{name}: no hinge bends as far and as tightly as its folds")
    for k, (n, (a, b)) in enumerate(slits):
        for m, (c, d) in slits[k + 1:]:
            if n == m and max(a[0], b[0]) + 3 > min(c[0], d[0]) and \
                    max(c[0], d[0]) + 3 > min(a[0], b[0]):
                g = dist_segments(a, b, c, d)
                check(g >= 1.0, f"{name}: slits {g:.3f} mm apart on {n}")
    # The DXF: the slits are the open polylines of the CUT layer.
    doc = ezdxf.readfile(os.path.join(out, "pattern.dxf"))
    open_cuts = sum(1 for e in doc.modelspace().query("LWPOLYLINE")
                    if e.dxf.layer == "CUT" and not e.closed)
    check(open_cuts == len(slits), f"{name}: {open_cuts} open CUT polylines, {len(slits)} slits")
    return folds, hinges


for pair in list(PAIRS) + ["squaricle"]:
    out = os.path.join(WORK, pair)
    folds, hinges = check_pair(pair, out)
    r = run("export", out, "--material", "plywood", "-q")
    check(r.returncode == 0, f"{pair}: export exit {r.returncode}: {r.stderr.strip()}")
    check(hinges_of(out)[1] == hinges, f"{pair}: dform export draws other hinges than the run")

out = os.path.join(WORK, "half")
forward("ellipses", out, "--material", "plywood", "--scale", "50%")
report = json.load(open(os.path.join(out, "report.json")))["model"]["folds"]
drawn = [(hf["fold"], math.dist(*hf["line"])) for hs in hinges_of(out)[1].values() for h in hs
         for hf in h["folds"]]
check(drawn != [], "--scale 50%: no hinges")
for i, length in drawn:
    want = 0.5 * math.dist(report[i]["from_mm"], report[i]["to_mm"])
    check(abs(length - want) < 1e-6, f"--scale 50%: fold {i} drawn {length:.4f} mm, {want:.4f} wanted")

out = os.path.join(WORK, "none")
forward("ellipses", out, "--material", "plywood", "--no-hinge")
check(all(h == [] for h in hinges_of(out)[1].values()), "--no-hinge drew hinges")

for extra, mentions in [(["--material", "card", "--hinge"], "hinge"),
                        (["--hinge"], "hinge"),
                        (["--material", "plywood", "--joint", "slots"], "slots")]:
    r = run("forward", *PAIRS["ellipses"], "-o", os.path.join(WORK, "bad"), *extra)
    lines = r.stderr.strip().splitlines()
    check(r.returncode == 2 and len(lines) == 1 and mentions in lines[0],
          f"{extra}: exit {r.returncode}, {lines}")

paper = os.path.join(WORK, "paper")
shutil.rmtree(paper, ignore_errors=True)
r = run("forward", *PAIRS["circle-square"], "--model", "paper", "--resolution", "30", "--gate",
        "none", "--material", "plywood", "-o", paper)
check(r.returncode == 0 and "no folds known" in r.stderr,
      f"paper model in plywood: exit {r.returncode}, no warning: {r.stderr.strip()}")
check(all(h == [] for h in hinges_of(paper)[1].values()), "paper model: hinges")

sys.exit(1 if failures else 0)
