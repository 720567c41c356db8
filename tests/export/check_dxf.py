#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Reads an export folder's DXF files back with ezdxf (python3-ezdxf) and checks them against the
SVG beside each and pattern.json. Run by tests/export/dxf_test.cpp.

usage: check_dxf.py DIR [--seam A_MM B_MM]

For pattern.dxf (against pattern.svg) and, with several sheets, each pattern-sheet-k.dxf (against
pattern-sheet-k.svg):
  - $INSUNITS is 4 (mm); the layers CUT, SCORE and ENGRAVE exist;
  - every drawn SVG polyline (but the printed tint of layer Bleed, which is no machine's work) is
    one LWPOLYLINE, in order, on the DXF layer of its SVG layer (a FAILED GATE stamp's on
    FAILED-GATE), with
    the SVG's closed flag, its vertices at (x, H - y) (y up, H the sheet height) within the SVG's
    rounding (1.1e-4 mm per coordinate);
  - every cut outline (A-cut, B-cut, holes) is closed and its perimeter is the SVG's within 0.1 mm;
  - $LIMMIN/$LIMMAX are the SVG sheet (0, 0)-(W, H); the entities' extents (ezdxf.bbox) are the
    SVG paths' box flipped, and $EXTMIN/$EXTMAX say the same;
  - tick 0 of pattern.json (y down, canvas mm) lies on a polyline of A-tick-00's layer (SCORE; a
    print-and-cut sheet prints its ticks: ENGRAVE) at (x, H - y);
  - with --seam: each piece's closed seam cut (A-cut, or A-cut-hole-1 when the seam is a hole; a
    pattern without tabs or kerf) and pattern.json's perimeter_mm (the seam as drawn, already
    scaled) are the given seam lengths (the solved seam times the scale) within 0.1 mm.
Prints the largest differences; exit 0 when every check passes, 1 otherwise, 2 without ezdxf.
"""
import json
import math
import os
import re
import sys

try:
    import ezdxf
    from ezdxf import bbox
except ImportError as error:  # fail loudly: scripts/install-deps installs it
    print("check_dxf: python3-ezdxf is missing (%s); run scripts/install-deps" % error)
    sys.exit(2)

MM_TOL = 0.1     # the bar for cut dimensions
# Per coordinate: the SVG writes 4 decimals (its points and its height each off by up to 5e-5 mm),
# the DXF 9.
SVG_TOL = 1.1e-4

# (A RIP profile's cut layer is named after its spot colour, CutContour.)
LAYER_OF = {"Cut": "CUT", "CutContour": "CUT", "Score": "SCORE", "Fold": "SCORE",
            "Regmarks": "REGMARKS", "FailedGate": "FAILED-GATE"}

problems = []
worst = {"perimeter_vs_svg": 0.0, "perimeter_vs_seam": 0.0, "vertex": 0.0}


def fail(message):
    problems.append(message)


def read_svg(path):
    text = open(path, encoding="utf-8").read()
    root = re.search(r'<svg[^>]*\swidth="([0-9.]+)mm"\s+height="([0-9.]+)mm"', text)
    width, height = float(root.group(1)), float(root.group(2))
    paths, layer = [], None
    for m in re.finditer(r'<g inkscape:groupmode="layer" inkscape:label="([^"]*)"|'
                         r'<path id="([^"]*)"[^>]*\sd="([^"]*)"', text):
        if m.group(1) is not None:
            layer = m.group(1)
            continue
        parts, closed, tokens = [], False, m.group(3).split()
        i = 0
        while i < len(tokens):
            t = tokens[i]
            if t == "M":
                parts.append([(float(tokens[i + 1]), float(tokens[i + 2]))])
                i += 3
            elif t == "L":
                parts[-1].append((float(tokens[i + 1]), float(tokens[i + 2])))
                i += 3
            elif t == "Z":
                closed = True
                i += 1
            else:
                fail("%s: unknown path command %r in %s" % (path, t, m.group(2)))
                i += 1
        if layer != "Bleed":  # printed only: the DXF leaves it out
            paths.append({"id": m.group(2), "layer": layer, "parts": parts, "closed": closed})
    return width, height, paths


def perimeter(points, closed):
    n = len(points)
    total = sum(math.dist(points[i], points[i + 1]) for i in range(n - 1))
    return total + (math.dist(points[-1], points[0]) if closed and n > 1 else 0.0)


def segment_distance(p, a, b):
    ax, ay = b[0] - a[0], b[1] - a[1]
    length2 = ax * ax + ay * ay
    t = 0.0 if length2 == 0 else max(0.0, min(1.0, ((p[0] - a[0]) * ax + (p[1] - a[1]) * ay) / length2))
    return math.dist(p, (a[0] + t * ax, a[1] + t * ay))


def check_pair(svg_path, dxf_path, sidecar, sheet_index, seams):
    name = os.path.basename(dxf_path)
    if not os.path.exists(dxf_path):
        fail("%s: missing" % name)
        return
    width, height, svg = read_svg(svg_path)
    doc = ezdxf.readfile(dxf_path)
    if doc.header.get("$INSUNITS") != 4:
        fail("%s: $INSUNITS is %r, not 4 (mm)" % (name, doc.header.get("$INSUNITS")))
    layers = {layer.dxf.name for layer in doc.layers}
    for needed in ("CUT", "SCORE", "ENGRAVE"):
        if needed not in layers:
            fail("%s: no layer %s (has %s)" % (name, needed, sorted(layers)))
    msp = doc.modelspace()
    entities = list(msp)
    others = [e.dxftype() for e in entities if e.dxftype() != "LWPOLYLINE"]
    if others:
        fail("%s: entities other than LWPOLYLINE: %s" % (name, sorted(set(others))))

    def up(q):
        return (q[0], height - q[1])

    # Every SVG polyline, in order, against the DXF's.
    drawn = [(path, part) for path in svg for part in path["parts"] if len(part) >= 2]
    if len(drawn) != len(entities):
        fail("%s: %d LWPOLYLINEs for the SVG's %d polylines" % (name, len(entities), len(drawn)))
    cut_perimeters = {}
    for (path, part), entity in zip(drawn, entities):
        if entity.dxftype() != "LWPOLYLINE":
            continue
        where = "%s: %s" % (name, path["id"])
        expected_layer = LAYER_OF.get(path["layer"], "ENGRAVE")
        if entity.dxf.layer != expected_layer:
            fail("%s on layer %s, not %s" % (where, entity.dxf.layer, expected_layer))
        if bool(entity.closed) != path["closed"]:
            fail("%s: closed flag %s, the SVG's %s" % (where, entity.closed, path["closed"]))
        points = [(x, y) for x, y, *_ in entity.get_points("xy")]
        svg_points = list(part)
        if path["closed"] and len(svg_points) > 2 and svg_points[0] == svg_points[-1]:
            svg_points.pop()
        if len(points) != len(svg_points):
            fail("%s: %d vertices, the SVG's %d" % (where, len(points), len(svg_points)))
            continue
        for q, s in zip(points, svg_points):
            d = max(abs(a - b) for a, b in zip(q, up(s)))
            worst["vertex"] = max(worst["vertex"], d)
            if d > SVG_TOL:
                fail("%s: vertex %s, expected %s (SVG %s flipped)" % (where, q, up(s), s))
                break
        if path["layer"] == "Cut" and path["closed"]:
            dxf_length = perimeter(points, bool(entity.closed))
            svg_length = perimeter(svg_points, True)
            worst["perimeter_vs_svg"] = max(worst["perimeter_vs_svg"], abs(dxf_length - svg_length))
            if abs(dxf_length - svg_length) > MM_TOL:
                fail("%s: cut perimeter %.4f mm, the SVG's %.4f" % (where, dxf_length, svg_length))
            cut_perimeters[path["id"]] = dxf_length
    for path in svg:
        if path["layer"] == "Cut" and re.match(r"^[AB]-cut(-hole-\d+)?$", path["id"]):
            if not path["closed"]:
                fail("%s: the SVG's %s is not closed" % (name, path["id"]))

    # The sheet and what is drawn on it.
    # The SVG writes the sheet's size to 4 decimals too: a tiled piece's sheet is not a whole size.
    lim_min, lim_max = doc.header.get("$LIMMIN"), doc.header.get("$LIMMAX")
    if lim_min is None or lim_max is None or math.dist(lim_min[:2], (0, 0)) > 1e-9 or \
            max(abs(lim_max[0] - width), abs(lim_max[1] - height)) > SVG_TOL:
        fail("%s: limits %s-%s, the SVG sheet is (0, 0)-(%g, %g)" % (name, lim_min, lim_max, width, height))
    xs = [q[0] for _, part in drawn for q in part]
    ys = [q[1] for _, part in drawn for q in part]
    if xs:
        expected = (min(xs), height - max(ys), max(xs), height - min(ys))
        box = bbox.extents(msp)
        got = (box.extmin.x, box.extmin.y, box.extmax.x, box.extmax.y)
        if max(abs(a - b) for a, b in zip(got, expected)) > SVG_TOL:
            fail("%s: extents %s, the SVG's box flipped is %s" % (name, got, expected))
        header = doc.header.get("$EXTMIN")[:2] + doc.header.get("$EXTMAX")[:2]
        if max(abs(a - b) for a, b in zip(header, got)) > 1e-6:
            fail("%s: $EXTMIN/$EXTMAX %s, the entities' %s" % (name, header, got))
        if min(got) < -1e-9 or got[2] > width + 1e-9 or got[3] > height + 1e-9:
            fail("%s: drawing %s off the %g x %g sheet" % (name, got, width, height))

    # A labelled point: tick 0 on piece A, from pattern.json's canvas (y down) to this sheet.
    sheet = sidecar["sheets"][sheet_index] if sheet_index is not None else None
    origin = sheet["origin"] if sheet else [0.0, 0.0]
    piece_a = sidecar["pieces"][0]
    if sidecar["ticks"] and (sheet is None or piece_a["sheet"] == sheet_index):
        tick = sidecar["ticks"][0]["a"]
        target = (tick[0] - origin[0], height - (tick[1] - origin[1]))
        tick_layer = next((LAYER_OF.get(p["layer"], "ENGRAVE") for p in svg if p["id"] == "A-tick-00"),
                          "SCORE")
        nearest = min((segment_distance(target, pts[i], pts[i + 1])
                       for e in entities if e.dxftype() == "LWPOLYLINE" and e.dxf.layer == tick_layer
                       for pts in [[(x, y) for x, y, *_ in e.get_points("xy")]]
                       for i in range(len(pts) - 1)), default=math.inf)
        if nearest > 1e-3:
            fail("%s: tick 0 of A at %s (pattern.json %s, y flipped) is %.4f mm from every %s line"
                 % (name, target, tick, nearest, tick_layer))

    # The seam lengths the test computed from the solved pieces, times the scale.
    if seams:
        for piece, seam in zip(sidecar["pieces"], seams):
            if abs(piece["perimeter_mm"] - seam) > MM_TOL:
                fail("pattern.json: %s perimeter_mm %.4f, the seam is %.4f" %
                     (piece["name"], piece["perimeter_mm"], seam))
            # A seam that is a hole's loop (anti and demi D-Forms) is cut as the piece's hole.
            cut_id = piece["name"] + ("-cut-hole-1" if piece.get("seam_is_hole") else "-cut")
            cut = cut_perimeters.get(cut_id)
            if cut is None:
                if sheet is None or piece["sheet"] == sheet_index:
                    fail("%s: no %s" % (name, cut_id))
                continue
            worst["perimeter_vs_seam"] = max(worst["perimeter_vs_seam"], abs(cut - seam))
            if abs(cut - seam) > MM_TOL:
                fail("%s: %s perimeter %.4f mm, the seam x scale is %.4f" % (name, cut_id, cut, seam))


def main(argv):
    if len(argv) < 2:
        print(__doc__)
        return 1
    folder = argv[1]
    seams = None
    if "--seam" in argv:
        at = argv.index("--seam")
        seams = [float(argv[at + 1]), float(argv[at + 2])]
    sidecar = json.load(open(os.path.join(folder, "pattern.json"), encoding="utf-8"))
    check_pair(os.path.join(folder, "pattern.svg"), os.path.join(folder, "pattern.dxf"), sidecar,
               None if len(sidecar["sheets"]) > 1 else 0, seams)
    if len(sidecar["sheets"]) > 1:
        for k, sheet in enumerate(sidecar["sheets"]):
            check_pair(os.path.join(folder, sheet["file"]), os.path.join(folder, sheet["dxf"]),
                       sidecar, k, seams)
    for message in problems:
        print("check_dxf: " + message)
    print("check_dxf: %d problem(s); max |cut perimeter DXF - SVG| %.2e mm, max |seam cut perimeter "
          "DXF - solved seam x scale| %s, max vertex offset from the flipped SVG %.2e mm (per "
          "coordinate)" % (len(problems), worst["perimeter_vs_svg"],
                           "%.2e mm" % worst["perimeter_vs_seam"] if seams else "not asked",
                           worst["vertex"]))
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
