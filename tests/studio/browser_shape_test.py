#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""dform studio's shape as a designer reads it, in headless Chromium with real pointer input.

The overlay: the strain of every edge and the curvature at every vertex coloured from the figures
the server sends (the colour scale is the figure, L_max or the largest angle defect; each edge's
and vertex's colour is the map of its own value over it), a new shape's overlay only with its own
figures, and the gate's failing checks marked where they fail (as many points as the server's
sites; the checks list says so). Linked picking: the pointer over a seam point of piece A's panel
marks that seam point on both panels and in 3D; over the 3D view, the seam point drawn there. The
measure tool: two clicks on the shape give the distance of the two vertices picked, in mm.
The print preview: its page count for a tiled print profile equals the pattern.json page count of
the export made with the same settings, and a sheet too small shows Export's refusal with the
largest scale that fits before Export is clicked. The axes: three, from the shape's lowest corner, labelled at their tips, hidden when unticked.
Snapping to a corner: A's handle dragged to within a few pixels of a hexagon's corner starts the
seam at the corner exactly (the server's corner, solved there); with Alt held it does not snap.
B's handle dragged 5 px past a card of the strip of alternative starts snaps to the card's start;
A's (an ellipse) 5 px past where a mirror axis crosses it, to the crossing.

    browser_shape_test.py DFORM SAMPLES_DIR      (exit 77 when Chromium or Selenium is absent)
"""
import base64
import json
import os
import shutil
import struct
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import studio_browser  # noqa: E402
from studio_browser import check, guarded  # noqa: E402


def doubles(text):
    data = base64.b64decode(text)
    return list(struct.unpack(f"<{len(data) // 8}d", data))


def diverging(t):
    """The page's map, written out again: -1 blue, 0 grey, +1 red."""
    t = max(-1.0, min(1.0, t)) if abs(t) != float("inf") and t == t else 1.0
    mid, end = (0.86, 0.86, 0.86), ((0.15, 0.3, 0.85) if t < 0 else (0.8, 0.05, 0.1))
    return [m + abs(t) * (e - m) for m, e in zip(mid, end)]


def with_overlay(s):
    """Waits for the shown shape's figures and overlay; returns (figures, overlay)."""
    s.settle()
    s.wait(lambda: s.js("var r = window.studio.shown && window.studio.shown.result; return !!(r && r.gate && r.overlay)"),
           120, "the shape's figures and overlay")
    return s.js("var r = window.studio.shown.result; return [r.figures, r.overlay]")


def choose(s, mode):
    from selenium.webdriver.support.ui import Select
    Select(s.driver.find_element("id", "overlay")).select_by_value(mode)


PIXELS = """var c = document.getElementById('view3d'), t = document.createElement('canvas');
    t.width = c.width; t.height = c.height; var g = t.getContext('2d'); g.drawImage(c, 0, 0);
    var d = g.getImageData(0, 0, t.width, t.height).data, h = 0;
    for (var i = 0; i < d.length; i += 4) h = (h * 31 + d[i] * 7 + d[i + 1] * 3 + d[i + 2]) % 1000000007;
    return h;"""


def colours_match(made, expected):
    return len(made) == len(expected) and all(
        all(abs(a - b) < 1e-9 for a, b in zip(m, e)) for m, e in zip(made, expected))


def strain_and_curvature(s):
    figures, overlay = with_overlay(s)
    plain = s.js(PIXELS)
    choose(s, "strain")
    made = s.js("return window.studio.overlay.made")
    strains = [doubles(p["strain"]) for p in overlay["pieces"]]
    largest = max(abs(x) for piece in strains for x in piece)
    check(largest == figures["L_max"], f"the largest |strain| sent is the figure L_max ({largest} vs {figures['L_max']})")
    check(made["mode"] == "strain" and made["scale"] == figures["L_max"], f"the strain scale is L_max ({made['scale']})")
    expected = [diverging(x / figures["L_max"]) for piece in strains for x in piece]
    check(colours_match(made["colours"], expected), f"every edge's colour is its strain over L_max ({len(expected)} edges)")
    check(any(abs(c[0] - 0.8) < 1e-9 or abs(c[2] - 0.85) < 1e-9 for c in made["colours"]),
          "the most strained edge takes the scale's end colour")
    counts = s.js("return window.studio.view3d.overlayCounts()")
    check(counts["lines"] == len(expected), f"the 3D view draws every edge ({counts})")
    legend = s.js("return document.getElementById('overlay-legend').textContent")
    check(f"{100 * figures['L_max']:.3g}" in legend.replace(" %", ""), f"the legend gives the scale ({legend})")
    check(s.js(PIXELS) != plain, "the strain is drawn on the canvas")

    choose(s, "curvature")
    made = s.js("return window.studio.overlay.made")
    curvature = [doubles(p["curvature"]) for p in overlay["pieces"]]
    top = figures["angle_defect_max_rad"]
    check(max(abs(x) for piece in curvature for x in piece) == top,
          f"the largest |angle defect| sent is the figure ({top})")
    expected = [diverging(x / top if top > 0 else 0) for piece in curvature for x in piece]
    check(made["scale"] == top and colours_match(made["colours"], expected),
          f"every vertex's colour is its angle defect over the figure ({len(expected)} vertices)")
    check(s.js("return window.studio.view3d.overlayCounts().tinted") == 2, "both pieces are tinted")

    choose(s, "none")
    check(s.js(PIXELS) == plain, "without the overlay the canvas is as before")

    # A new shape: its overlay only with its own figures.
    choose(s, "strain")
    seq = s.js("return window.studio.shown.seq")
    s.driver.find_element("id", "flip").click()
    s.wait(lambda: s.js("return window.studio.shown && window.studio.shown.seq") > seq, 60, "the flipped shape")
    figures2, _ = with_overlay(s)
    made = s.js("return window.studio.overlay.made")
    check(made["scale"] == figures2["L_max"], f"the new shape's overlay has its own scale ({made['scale']} vs {figures2['L_max']})")
    choose(s, "none")


def pointer_to(s, x, y, click=False):
    """The real pointer moved to viewport point (x, y), and clicked there when asked."""
    from selenium.webdriver.common.action_chains import ActionChains
    from selenium.webdriver.common.actions.action_builder import ActionBuilder
    builder = ActionBuilder(s.driver)
    builder.pointer_action.move_to_location(int(round(x)), int(round(y)))
    if click:
        builder.pointer_action.click()
    builder.perform()
    ActionChains(s.driver).pause(0.05).perform()


SEAM_ON_PANEL = """var v = window.studio.views[arguments[0]], q = v.seamPoint(arguments[1]), p = v.svg.createSVGPoint();
    p.x = q[0]; p.y = -q[1]; var c = p.matrixTransform(v.svg.getScreenCTM()); return [c.x, c.y];"""
MARK_ON_PANEL = """var n = document.querySelector('#svg-' + arguments[0] + '-marks .picked');
    if (!n) return null; var b = n.getBoundingClientRect();
    return [+n.getAttribute('data-seam-point'), b.left + b.width / 2, b.top + b.height / 2];"""
ON_CANVAS = """var b = document.getElementById('view3d').getBoundingClientRect(), q = arguments[0],
    s = window.studio.view3d.project(q[0], q[1], q[2]); return [b.left + s[0], b.top + s[1], s[2]];"""


def seam3d(s, k):
    return s.js("var p = window.studio.shown.pieces[0], v = p.seam[arguments[0]];"
                " return [p.shape[3 * v], p.shape[3 * v + 1], p.shape[3 * v + 2]]", k)


def linked_picking(s):
    s.settle()
    n = s.js("return window.studio.shown.pieces[0].seam.length")
    k = n // 3
    x, y = s.js(SEAM_ON_PANEL, 0, k)
    pointer_to(s, x, y)
    s.wait(lambda: s.js("return window.studio.picking.picked") == k, 10, "the pick")
    on_a, on_b = s.js(MARK_ON_PANEL, "a"), s.js(MARK_ON_PANEL, "b")
    where_b = s.js(SEAM_ON_PANEL, 1, k)
    check(on_a and on_a[0] == k and abs(on_a[1] - x) < 1 and abs(on_a[2] - y) < 1,
          f"seam point {k} under the pointer on A is marked there ({on_a} at {x:.1f}, {y:.1f})")
    check(on_b and on_b[0] == k and abs(on_b[1] - where_b[0]) < 1 and abs(on_b[2] - where_b[1]) < 1,
          f"and its partner on B ({on_b} at {where_b})")
    marks = s.js("return window.studio.view3d.marks('hover')")
    check(len(marks) == 1 and all(abs(a - b) < 1e-9 for a, b in zip(marks[0], seam3d(s, k))),
          f"and in 3D, at A's seam point {k} ({marks})")
    # Over the 3D view: the seam point drawn under the pointer (the nearest on screen).
    j = (2 * n) // 3
    cx, cy, _ = s.js(ON_CANVAS, seam3d(s, j))
    pointer_to(s, cx, cy)
    s.wait(lambda: s.js("return window.studio.picking.picked") is not None
           and s.js("return window.studio.picking.picked") != k, 10, "the pick in 3D")
    got = s.js("return window.studio.picking.picked")
    gx, gy, _ = s.js(ON_CANVAS, seam3d(s, got))
    on_a = s.js(MARK_ON_PANEL, "a")
    check(abs(gx - cx) <= 1.5 and abs(gy - cy) <= 1.5 and on_a and on_a[0] == got,
          f"the seam point drawn under the pointer in 3D ({got}, asked {j}) is marked on the panels")


def measure(s):
    s.settle()
    s.driver.find_element("id", "measure").click()
    # Two seam points of A, as the view draws them; the picks are the front-most vertices there.
    n = s.js("return window.studio.shown.pieces[0].seam.length")
    clicks = []
    for k in (0, n // 2):
        cx, cy, _ = s.js(ON_CANVAS, seam3d(s, k))
        clicks.append((cx, cy))
        pointer_to(s, cx, cy, click=True)
    state = s.js("var m = window.studio.picking; return [m.points, m.distance,"
                 " document.getElementById('measure-readout').textContent]")
    points, distance, readout = state
    check(len(points) == 2, f"two points picked ({points})")
    if len(points) == 2:
        near = all(abs(px - cx) <= 10.5 and abs(py - cy) <= 10.5
                   for (cx, cy), (px, py, _) in zip(clicks, (s.js(ON_CANVAS, p) for p in points)))
        check(near, "each picked point is drawn within 10 px of its click")
        true = sum((a - b) ** 2 for a, b in zip(*points)) ** 0.5
        check(distance is not None and abs(distance - true) < 1e-9 and f"{true:.2f} mm" in readout,
              f"the readout is their distance ({readout}, {true:.4f} mm)")
        check(s.js("return window.studio.view3d.marks('measure').length") == 2, "both points drawn in 3D")
    s.driver.find_element("id", "measure").click()
    check(s.js("return window.studio.view3d.marks('measure').length") == 0, "Measure off clears them")


def drag_to(s, piece, target, alt=False):
    """Drags piece's handle with the real pointer, in ten steps, to viewport point `target`."""
    from selenium.webdriver.common.action_chains import ActionChains
    from selenium.webdriver.common.keys import Keys
    handle = s.driver.find_element("css selector", f"#svg-{piece}-marks circle.handle")
    box = s.js("var b = arguments[0].getBoundingClientRect(); return [b.left + b.width / 2, b.top + b.height / 2]", handle)
    actions = ActionChains(s.driver, duration=10)
    if alt:
        actions.key_down(Keys.ALT)
    actions.click_and_hold(handle)
    last = [0, 0]
    for k in range(1, 11):
        x, y = round((target[0] - box[0]) * k / 10), round((target[1] - box[1]) * k / 10)
        actions.move_by_offset(x - last[0], y - last[1])
        last = [x, y]
    actions.release()
    if alt:
        actions.key_up(Keys.ALT)
    actions.perform()
    s.settle()


def snapping_to_alternatives(s):
    """B's start dragged to 5 px along its outline from a card of the strip snaps to the card's."""
    s.wait(lambda: s.js("return document.getElementById('strip-cards').getAttribute('data-state')") == "done", 300,
           "the strip")
    s.settle()
    current = s.js("return window.studio.shown.settings.start_b")
    flip = s.js("return window.studio.shown.settings.flip")
    # Each card's first start turned over as B is now (a group holds both ways of the same shape).
    groups = s.js("return window.studio.strip.cards.map(function (c) { return [c].concat(c.also).map(function (m) {"
                  " return [m.start_b, m.flip, !!m.error]; }); })")
    starts = [next(m[0] for m in g if m[1] == flip and not m[2]) for g in groups
              if any(m[1] == flip and not m[2] for m in g)]
    card = max(starts, key=lambda f: min(abs(f - current), 1 - abs(f - current)))
    x, y, along = s.js("""var v = window.studio.views[1], m = v.svg.getScreenCTM(), d = 5 / Math.abs(m.a) / v.loop.length;
        var q = v.loop.at(arguments[0] + d), p = v.svg.createSVGPoint(); p.x = q[0]; p.y = -q[1];
        var c = p.matrixTransform(m); return [c.x, c.y, d * v.loop.length];""", card)
    drag_to(s, "b", (x, y))
    got = s.js("return window.studio.shown.settings.start_b")
    label = s.js("return window.studio.views[1].handleLabel.textContent")
    check(got == card and "(alternative" in label,
          f"B dragged {along:.1f} mm past a card's start snaps to it ({got} vs {card}; {label})")
    drag_to(s, "b", (x, y), alt=True)
    length = s.js("return window.studio.views[1].loop.length")
    got = s.js("return window.studio.shown.settings.start_b")
    off = min(abs(got - card), 1 - abs(got - card)) * length
    check(abs(off - along) < 1.5, f"with Alt held it stays where the pointer is ({off:.2f} mm from the card's start)")


def snapping_to_axes(s):
    """A's start (an ellipse: no corners) dragged 5 px along its outline past where a mirror axis
    crosses it snaps to the crossing."""
    s.settle()
    axes = s.js("return window.studio.views[0].axes")
    start = s.js("return window.studio.shown.settings.start_a")
    check(len(axes) == 4, f"the ellipse's two mirror axes cross it four times ({axes})")
    axis = max(axes, key=lambda f: min(abs(f - start), 1 - abs(f - start)))
    x, y = s.js("""var v = window.studio.views[0], m = v.svg.getScreenCTM(), d = 5 / Math.abs(m.a) / v.loop.length;
        var q = v.loop.at(arguments[0] + d), p = v.svg.createSVGPoint(); p.x = q[0]; p.y = -q[1];
        var c = p.matrixTransform(m); return [c.x, c.y];""", axis)
    drag_to(s, "a", (x, y))
    got = s.js("return window.studio.shown.settings.start_a")
    label = s.js("return window.studio.views[0].handleLabel.textContent")
    check(got == axis and "(symmetry axis)" in label, f"A snaps to the axis's crossing ({got} vs {axis}; {label})")


def snapping(s):
    s.js("var k = document.getElementById('kind-a'); k.value = 'polygon'; k.dispatchEvent(new Event('change'))")
    s.wait(lambda: s.js("return window.studio.views[0].corners.length") == 6, 30, "the hexagon")
    s.settle()
    corners = s.js("return window.studio.views[0].corners")
    length = s.js("return window.studio.views[0].loop.length")
    start = s.js("return window.studio.shown.settings.start_a")
    # The corner farthest from A's start, as the panel draws it, and the point 5 px from it
    # towards the hexagon's centre (inside, where the nearest point of the outline is on a side,
    # not the corner): the pointer ends there.
    corner = max(corners, key=lambda c: min(abs(c - start), 1 - abs(c - start)))
    to_screen = ("var v = window.studio.views[0], p = v.svg.createSVGPoint(); p.x = arguments[0]; p.y = -arguments[1];"
                 " var c = p.matrixTransform(v.svg.getScreenCTM()); return [c.x, c.y];")
    x, y = s.js(to_screen, *s.js("return window.studio.views[0].loop.at(arguments[0])", corner))
    cx, cy = s.js(to_screen, 0, 0)
    d = ((cx - x) ** 2 + (cy - y) ** 2) ** 0.5
    x, y = x + 5 * (cx - x) / d, y + 5 * (cy - y) / d
    drag_to(s, "a", (x, y))
    got = s.js("return window.studio.shown.settings.start_a")
    solved = s.js("return window.studio.shown.result.start_a")
    label = s.js("return window.studio.views[0].handleLabel.textContent")
    check(got == corner, f"dragged 5 px off a corner, A starts at the corner ({got} vs {corner})")
    check(abs(solved - corner) < 1e-9, f"the shape is solved from the corner ({solved})")
    check("(corner)" in label, f"the handle says so ({label})")
    drag_to(s, "a", (x, y), alt=True)
    got = s.js("return window.studio.shown.settings.start_a")
    off = min(abs(got - corner), 1 - abs(got - corner)) * length
    check(0.3 < off < 15, f"with Alt held it starts where the pointer is ({off:.2f} mm from the corner)")


def multisampling(s):
    """The harness's WebGL is SwiftShader's, a software rasteriser: the 3D view draws without
    multisampling there (its context's own attributes say so)."""
    renderer = s.js("var gl = document.createElement('canvas').getContext('webgl'),"
                    " e = gl.getExtension('WEBGL_debug_renderer_info'); return gl.getParameter(e.UNMASKED_RENDERER_WEBGL)")
    check("SwiftShader" in renderer, f"the harness's WebGL is SwiftShader ({renderer})")
    attributes = s.js("return document.getElementById('view3d').getContext('webgl').getContextAttributes()")
    check(attributes["antialias"] is False, f"the 3D view draws without multisampling on it ({attributes})")


def preview_settled(s, timeout=180):
    s.wait(lambda: s.js("var p = window.studio.preview; return p.idle() && !!p.shown"), timeout, "the print preview")
    return s.js("return window.studio.preview.shown")


def type_into(s, element_id, text):
    field = s.driver.find_element("id", element_id)
    field.clear()
    if text:
        field.send_keys(text)


def axes(s):
    s.settle()
    a = s.js("return window.studio.view3d.axes()")
    lo = s.js("var lo = [Infinity, Infinity, Infinity]; window.studio.shown.pieces.forEach(function (p) {"
              " for (var v = 0; v < p.shape.length; ++v) lo[v % 3] = Math.min(lo[v % 3], p.shape[v]); }); return lo")
    check(a["on"] and all(abs(x - y) < 1e-3 * max(1, abs(y)) for x, y in zip(a["origin"], lo)) and a["length"] > 0,
          f"the axes start at the shape's lowest corner ({a['origin']} vs {lo})")
    placed = []
    for k, label in enumerate(a["labels"]):
        tip = list(a["origin"])
        tip[k] += a["length"]
        x, y, _ = s.js("var c = document.getElementById('view3d'), q = arguments[0], p = window.studio.view3d.project(q[0], q[1], q[2]);"
                       " return [c.offsetLeft + p[0], c.offsetTop + p[1], 0]", tip)
        placed.append(not label["hidden"] and label["text"].startswith("xyz"[k]) and abs(label["left"] - x) < 0.2
                      and abs(label["top"] - y) < 0.2)
    check(len(placed) == 3 and all(placed) and f"{a['length']:g} mm" in a["labels"][0]["text"],
          f"x, y and z labelled at their tips, x with its length ({a['labels']})")
    s.driver.find_element("id", "axes").click()
    check(all(label["hidden"] for label in s.js("return window.studio.view3d.axes().labels")), "unticked, the axes go")
    s.driver.find_element("id", "axes").click()


def print_preview(s):
    import io
    import zipfile
    from selenium.webdriver.support.ui import Select
    s.settle()
    s.driver.find_element("id", "export").click()
    Select(s.driver.find_element("id", "profile")).select_by_value("print")
    type_into(s, "page", "A4")
    type_into(s, "scale", "1")
    shown = preview_settled(s)
    pages = len(shown.get("pages") or [])
    plan = s.js("return document.querySelectorAll('#preview-pages .plan-page').length")
    said = s.js("return document.getElementById('export-preview').textContent")
    check(pages > 1 and plan == pages and f"{pages} pages" in said,
          f"the preview lays the pieces out on {pages} A4 pages, drawn and said in the dialog ({plan}; {said})")
    sheets = s.js("return document.querySelectorAll('#preview-pages img.preview-sheet').length")
    check(sheets == len(shown["sheets"]) >= 1, f"each sheet is drawn ({sheets})")
    s.js("window.studio.lastDownload = null")
    s.driver.find_element("id", "export-go").click()
    s.wait(lambda: s.js("return !!window.studio.lastDownload"), 300, "the export")
    sidecar = json.loads(zipfile.ZipFile(io.BytesIO(s.download())).read("pattern.json"))
    check(len(sidecar["pages"]) == pages, f"the export's pattern.json has as many pages ({len(sidecar['pages'])})")
    check([p["kind"] for p in sidecar["pages"]] == [p["kind"] for p in shown["pages"]], "the same pages, tiles and maps")
    s.driver.find_element("id", "export").click()
    Select(s.driver.find_element("id", "profile")).select_by_value("laser")
    type_into(s, "page", "")
    type_into(s, "sheet", "100x100mm")
    shown = preview_settled(s)
    said = s.js("return document.getElementById('export-preview').textContent")
    check("largest scale that fits is" in (shown.get("missing") or "") and "largest scale that fits is" in said
          and not shown.get("pages"), f"a sheet too small: Export's refusal and the scale that fits, before Export ({said})")
    type_into(s, "sheet", "")
    s.driver.find_element("id", "export-cancel").click()


def failures_marked(dform, samples):
    """A paper model stopped early fails L_error: its edges over the limit are marked."""
    work = tempfile.mkdtemp(prefix="dform-overlay-")
    s = studio_browser.Studio(dform, [studio_browser.failing_job(samples, work)])
    try:
        s.settle(300)
        figures, overlay = with_overlay(s)
        gate = s.js("return window.studio.shown.result.gate")
        failed = {c["name"]: c for c in gate["checks"] if c["verdict"] == "fail"}
        check("L_error" in failed, f"the design fails L_error ({sorted(failed)})")
        strains = [doubles(p["strain"]) for p in overlay["pieces"]]
        expected = 0
        for name, kind in (("L_error", "edges"), ("L_max", "edges")):
            if name in failed:
                over = sum(1 for piece in strains for x in piece if not abs(x) <= failed[name]["limit"])
                sites = [f for f in overlay["failing"] if f["check"] == name]
                got = len(sites[0]["items"][0]) // 2 + len(sites[0]["items"][1]) // 2 if sites else -1
                check(over > 0 and got == over, f"{name}: the server's sites are the {over} edges over {failed[name]['limit']} ({got})")
                expected += over
        for f in overlay["failing"]:
            if f["check"] not in ("L_error", "L_max"):
                expected += len(f["items"][0]) if f["kind"] == "seam_points" else \
                    (len(f["items"][0]) + len(f["items"][1])) // (2 if f["kind"] == "edges" else 1)
        markers = s.js("return window.studio.view3d.overlayCounts().markers")
        check(markers == expected and expected > 0, f"a point marks each site ({markers} of {expected})")
        listed = s.js("return document.getElementById('checks').textContent")
        check("marked on the shape" in listed, "the checks list says where its failures are marked")
        unlocated = set(overlay["unlocated"])
        check(unlocated == set(failed) - {f["check"] for f in overlay["failing"]},
              f"every other failing check is named as not located ({sorted(unlocated)})")
        s.driver.find_element("id", "mark-failures").click()
        check(s.js("return window.studio.view3d.overlayCounts().markers") == 0, "'mark failures' off takes the points away")
        check(s.console_errors() == [], "no console errors (failing design)")
    finally:
        s.close()
        shutil.rmtree(work, ignore_errors=True)


def main():
    dform, samples = sys.argv[1], os.path.abspath(sys.argv[2])
    if studio_browser.skipped():
        return studio_browser.SKIP
    s = studio_browser.Studio(dform, [])
    try:
        guarded("strain and curvature", strain_and_curvature, s)
        guarded("linked picking", linked_picking, s)
        guarded("measure", measure, s)
        guarded("axes", axes, s)
        guarded("multisampling", multisampling, s)
        guarded("print preview", print_preview, s)
        guarded("snapping to the strip's alternatives", snapping_to_alternatives, s)
        guarded("snapping to a symmetry axis", snapping_to_axes, s)
        guarded("snapping to a corner", snapping, s)
        check(s.console_errors() == [], "no console errors")
    finally:
        s.close()
    guarded("failures marked", failures_marked, dform, samples)
    return studio_browser.verdict()


if __name__ == "__main__":
    sys.exit(main())
