#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Measures the kerf offset of an export folder's cut loops in pattern.dxf with ezdxf
(python3-ezdxf). Run by tests/export/joints_test.cpp.

usage: check_kerf.py DIR KERF_MM

pattern.json gives each piece's seam (`outline`, sheet mm, y down), the joint holes (centre,
diameter) and, for --joint slots, the tongues and slots (`joint_slots`: tongue, slot loop and
centre). In pattern.dxf (mm, y up), on layer CUT:
  - the closed loops are one per piece plus one per joint hole and slot ("cut loops = pieces +
    holes");
  - every vertex of a piece's outer loop lies KERF/2 outside its seam and tongues (within 0.01 mm:
    round joins are drawn within 5 um);
  - every vertex of a hole's loop lies KERF/2 inside the hole's circle (a slot's: inside its
    rectangle), so that the beam, half a kerf either side of the loop, leaves the hole at its
    designed size (within 0.01 mm).
Prints the largest differences; exit 0 when every check passes, 1 otherwise, 2 without ezdxf.
"""
import json
import math
import os
import sys

try:
    import ezdxf
except ImportError as error:  # fail loudly: scripts/install-deps installs it
    print("check_kerf: python3-ezdxf is missing (%s); run scripts/install-deps" % error)
    sys.exit(2)

TOL = 0.01


def distance_to_loop(loop, q):
    best = math.inf
    for i, a in enumerate(loop):
        b = loop[(i + 1) % len(loop)]
        abx, aby = b[0] - a[0], b[1] - a[1]
        length2 = abx * abx + aby * aby
        t = 0.0 if length2 == 0 else max(0.0, min(1.0, ((q[0] - a[0]) * abx + (q[1] - a[1]) * aby) / length2))
        best = min(best, math.hypot(a[0] + t * abx - q[0], a[1] + t * aby - q[1]))
    return best


def inside(loop, q):
    result = False
    j = len(loop) - 1
    for i, a in enumerate(loop):
        b = loop[j]
        if (a[1] > q[1]) != (b[1] > q[1]) and q[0] < (b[0] - a[0]) * (q[1] - a[1]) / (b[1] - a[1]) + a[0]:
            result = not result
        j = i
    return result


def main():
    folder, kerf = sys.argv[1], float(sys.argv[2])
    pattern = json.load(open(os.path.join(folder, "pattern.json"), encoding="utf-8"))
    height = pattern["sheet"]["height"]
    seams = [piece["outline"] for piece in pattern["pieces"]]
    holes = pattern.get("joint_holes", [])
    slots = pattern.get("joint_slots", [])
    tongues = [slot["tongue"] for slot in slots]
    doc = ezdxf.readfile(os.path.join(folder, "pattern.dxf"))
    loops = [[(x, height - y) for x, y in e.get_points("xy")]
             for e in doc.modelspace().query("LWPOLYLINE") if e.dxf.layer == "CUT" and e.closed]
    problems, worst = [], {"outer": 0.0, "hole": 0.0}
    if len(loops) != len(seams) + len(holes) + len(slots):
        problems.append("%d closed cut loops for %d pieces, %d holes and %d slots" %
                        (len(loops), len(seams), len(holes), len(slots)))
    outer = hole_loops = 0
    for loop in loops:
        cx = sum(p[0] for p in loop) / len(loop)
        cy = sum(p[1] for p in loop) / len(loop)
        near = [h for h in holes if math.hypot(h["centre"][0] - cx, h["centre"][1] - cy) < 1e-2]
        if near:
            hole_loops += 1
            radius = 0.5 * near[0]["diameter_mm"] - 0.5 * kerf
            for q in loop:
                r = math.hypot(q[0] - near[0]["centre"][0], q[1] - near[0]["centre"][1])
                worst["hole"] = max(worst["hole"], abs(r - radius))
            continue
        slot = [s for s in slots if math.hypot(s["slot_centre"][0] - cx, s["slot_centre"][1] - cy) < 1e-2]
        if slot:
            hole_loops += 1
            for q in loop:
                worst["hole"] = max(worst["hole"],
                                    abs(distance_to_loop(slot[0]["slot"], q) - 0.5 * kerf))
                if not inside(slot[0]["slot"], q):
                    problems.append("a slot's cut vertex lies outside the slot")
                    break
            continue
        outer += 1
        seam = min(seams, key=lambda s: distance_to_loop(s, loop[0]))
        for q in loop:
            nearest = min(distance_to_loop(part, q) for part in [seam] + tongues)
            worst["outer"] = max(worst["outer"], abs(nearest - 0.5 * kerf))
            if inside(seam, q) or any(inside(tongue, q) for tongue in tongues):
                problems.append("an outer cut vertex lies inside its seam or a tongue")
                break
    if outer != len(seams) or hole_loops != len(holes) + len(slots):
        problems.append("%d outer loops and %d hole loops, expected %d and %d" %
                        (outer, hole_loops, len(seams), len(holes) + len(slots)))
    for kind, value in worst.items():
        if value > TOL:
            problems.append("%s loop off its kerf offset by %.4f mm" % (kind, value))
    print("check_kerf: %d loops, worst outer %.5f mm, worst hole %.5f mm" %
          (len(loops), worst["outer"], worst["hole"]))
    for problem in problems:
        print("check_kerf: " + problem)
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
