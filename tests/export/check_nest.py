#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Measures how far apart a nest's pieces are cut, with ezdxf (python3-ezdxf), in its sheets' DXF
files. Run by tests/export/nest_test.cpp.

usage: check_nest.py GAP_MM SHEET.dxf [SHEET.dxf ...]

In each file, the closed LWPOLYLINEs of layer CUT are loops; a loop inside no other is a piece's
outer cut, a loop inside one is a hole of it. Every two outer cuts of a file must lie GAP_MM apart
or more: no vertex of one inside the other, and the least distance from a vertex of either to a
segment of the other at least GAP_MM (two polygonal loops that do not cross are nearest at a
vertex of one). Prints the pieces and the least distance per file and over all; exit 0 when every
file passes, 1 otherwise, 2 without ezdxf.
"""
import sys

try:
    import ezdxf
    import numpy as np
except ImportError as error:  # fail loudly: scripts/install-deps installs them
    print("check_nest: python3-ezdxf or python3-numpy is missing (%s)" % error)
    sys.exit(2)


def loops_of(path):
    doc = ezdxf.readfile(path)
    loops = []
    for e in doc.modelspace().query("LWPOLYLINE"):
        if e.dxf.layer == "CUT" and e.closed:
            loops.append(np.array([(p[0], p[1]) for p in e.get_points("xy")], dtype=float))
    return loops


def inside(loop, points):
    """Which of `points` lie inside the closed polygon `loop` (even-odd ray casting)."""
    x, y = points[:, 0][:, None], points[:, 1][:, None]
    ax, ay = loop[:, 0][None, :], loop[:, 1][None, :]
    bx, by = np.roll(loop[:, 0], -1)[None, :], np.roll(loop[:, 1], -1)[None, :]
    crosses = ((ay > y) != (by > y)) & (x < (bx - ax) * (y - ay) / np.where(by != ay, by - ay, 1) + ax)
    return np.count_nonzero(crosses, axis=1) % 2 == 1


def vertex_segment_distance(points, loop):
    """The least distance from any of `points` to a segment of the closed `loop`."""
    a = loop
    b = np.roll(loop, -1, axis=0)
    best = np.inf
    for start in range(0, len(points), 256):
        p = points[start:start + 256][:, None, :]
        ab = (b - a)[None, :, :]
        t = np.clip(np.sum((p - a[None]) * ab, axis=2) / np.maximum(np.sum(ab * ab, axis=2), 1e-300),
                    0.0, 1.0)
        d = np.linalg.norm(p - (a[None] + t[:, :, None] * ab), axis=2)
        best = min(best, float(d.min()))
    return best


def boxes_near(a, b, gap):
    return not (a[:, 0].max() + gap < b[:, 0].min() or b[:, 0].max() + gap < a[:, 0].min() or
                a[:, 1].max() + gap < b[:, 1].min() or b[:, 1].max() + gap < a[:, 1].min())


def main():
    gap = float(sys.argv[1])
    failed = False
    overall, pieces = np.inf, 0
    for path in sys.argv[2:]:
        loops = loops_of(path)
        outer = [i for i, loop in enumerate(loops)
                 if not any(j != i and inside(other, loop[:1])[0] for j, other in enumerate(loops))]
        least = np.inf
        for n, i in enumerate(outer):
            for j in outer[n + 1:]:
                a, b = loops[i], loops[j]
                if not boxes_near(a, b, 2 * gap):
                    continue
                if inside(a, b).any() or inside(b, a).any():
                    least = 0.0
                    continue
                least = min(least, vertex_segment_distance(a, b), vertex_segment_distance(b, a))
        pieces += len(outer)
        overall = min(overall, least)
        print("check_nest: %s: %d pieces, least distance %s mm" %
              (path, len(outer), "n/a" if least == np.inf else "%.4f" % least))
        failed = failed or least < gap - 1e-6
    print("check_nest: %d pieces, least distance between two %s mm (at least %.4f asked)" %
          (pieces, "n/a" if overall == np.inf else "%.4f" % overall, gap))
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
