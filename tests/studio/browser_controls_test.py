#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""dform studio's controls in headless Chromium, with real keys: Ctrl+Shift+Z redoes; Ctrl+Z in a
number box is the box's own (the design stays); counts move in whole steps (Reuleaux sides in odd
steps); every slider shows its unit and has a number box; the starts are typed in mm and nudged
with the arrow keys (Shift: ten times as far); a handle's label stays inside its panel; '?' opens
the list of shortcuts; Reset view; a fixed scale (ground grid, scale bar in mm) shows a change of
size; docs/studio.md lists the outlines the page offers.

    browser_controls_test.py DFORM SOURCE_DIR      (exit 77 when Chromium or Selenium is absent)
"""
import os
import re
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import studio_browser  # noqa: E402
from studio_browser import check, guarded  # noqa: E402


def keys(s, *sequence):
    """Real key presses: strings are typed, tuples are chords (modifiers held)."""
    from selenium.webdriver.common.action_chains import ActionChains
    actions = ActionChains(s.driver)
    for item in sequence:
        if isinstance(item, tuple):
            *modifiers, key = item
            for m in modifiers:
                actions.key_down(m)
            actions.send_keys(key)
            for m in reversed(modifiers):
                actions.key_up(m)
        else:
            actions.send_keys(item)
    actions.perform()


def flip(s):
    return s.js("return document.getElementById('flip').checked")


def solved_after(s, action):
    """Does `action` (which changes an outline: its new shape comes after a request for the
    outline) and waits for the shape it makes."""
    seq = s.js("return window.studio.frameSeq")
    action()
    s.wait(lambda: s.js("return window.studio.frameSeq") > seq, 60, "the outline's shape")
    s.settle()


def choose_kind(s, piece, kind):
    """A built-in outline for `piece`, its shape solved."""
    solved_after(s, lambda: s.js(f"var k = document.getElementById('kind-{piece}'); k.value = '{kind}';"
                                 " k.dispatchEvent(new Event('change'))"))


COLOURED = """var c = document.getElementById('view3d'), t = document.createElement('canvas');
    t.width = c.width; t.height = c.height; var g = t.getContext('2d'); g.drawImage(c, 0, 0);
    var d = g.getImageData(0, 0, t.width, t.height).data, n = 0;
    for (var i = 0; i < d.length; i += 4)
      if (Math.max(d[i], d[i + 1], d[i + 2]) - Math.min(d[i], d[i + 1], d[i + 2]) > 40) ++n;
    return n;"""


def view(s):
    """Reset view; fixed scale with its grid and scale bar shows a change of size."""
    from selenium.webdriver.common.action_chains import ActionChains
    from selenium.webdriver.common.keys import Keys
    canvas = s.driver.find_element("id", "view3d")
    ActionChains(s.driver).move_to_element(canvas).click_and_hold().move_by_offset(80, 40).release().perform()
    turned = s.js("return Object.assign({}, window.studio.view3d.camera)")
    s.driver.find_element("id", "reset-view").click()
    home = s.js("return Object.assign({}, window.studio.view3d.camera)")
    check(turned != home and home == {"azimuth": 30, "elevation": 25, "zoom": 1}, f"Reset view turns {turned} back to {home}")

    choose_kind(s, "a", "ellipse")
    choose_kind(s, "b", "ellipse")
    s.driver.find_element("id", "fixed-scale").click()
    before = s.js("return [window.studio.view3d.pixelsPerMm(), document.getElementById('scale-bar-text').textContent,"
                  " document.getElementById('scale-bar-line').style.width, window.studio.view3d.gridLines()]")
    pixels = s.js(COLOURED)
    # A at half its size: B, scaled to A's perimeter, halves too, so the shape is the same at half
    # the size: a quarter of the pixels at a fixed scale, twice the pixels per mm when refitted.
    for name, value in (("a", "60"), ("b", "35")):
        size = s.driver.find_element("id", "value-a-" + name)
        size.clear()
        solved_after(s, lambda: size.send_keys(value, Keys.ENTER))
    after = s.js("return [window.studio.view3d.pixelsPerMm(), document.getElementById('scale-bar-text').textContent,"
                 " document.getElementById('scale-bar-line').style.width, window.studio.view3d.gridLines()]")
    smaller = s.js(COLOURED)
    check(before[3] > 4 and after == before and before[1].endswith(" mm"),
          f"fixed scale: the scale, the bar and the ground grid stay ({before} -> {after})")
    check(0.18 < smaller / pixels < 0.32, f"fixed scale shows the shape at half its size ({pixels} -> {smaller} pixels)")
    s.driver.find_element("id", "fixed-scale").click()
    refit = s.js("return [window.studio.view3d.pixelsPerMm(), document.getElementById('scale-bar-text').textContent]")
    check(abs(refit[0] / before[0] - 2) < 0.01, f"without it the view fits the smaller shape again ({refit})")


def undo_keys(s):
    from selenium.webdriver.common.keys import Keys
    s.driver.find_element("id", "flip").click()
    s.settle()
    s.driver.find_element("tag name", "body").click()
    keys(s, (Keys.CONTROL, "z"))
    s.wait(lambda: not flip(s), 10, "undo")
    keys(s, (Keys.CONTROL, Keys.SHIFT, "z"))
    s.wait(lambda: flip(s), 10, "redo")
    check(flip(s), "Ctrl+Z undoes and Ctrl+Shift+Z redoes")
    s.settle()


def box_undo(s):
    """Ctrl+Z in a number box undoes the typing, not the design."""
    from selenium.webdriver.common.keys import Keys
    was = flip(s)
    s.driver.find_element("id", "flip").click()
    s.settle()
    s.driver.find_element("id", "resolution").click()
    keys(s, "4", (Keys.CONTROL, "z"))
    check(flip(s) != was, "Ctrl+Z in the resolution box leaves the design alone")
    keys(s, (Keys.CONTROL, "a"), "100", Keys.TAB)  # the box as it was, whatever the undo left
    s.settle()
    check(s.js("return window.studio.shown.settings.resolution") == 100, "the resolution is 100 again")


def counts(s):
    """Counts move in whole steps; Reuleaux sides in odd ones."""
    from selenium.webdriver.common.keys import Keys
    choose_kind(s, "a", "polygon")
    slider = s.driver.find_element("css selector", "#sliders-a input[type=range]")
    check(slider.get_attribute("step") == "1", f"the sides slider steps by 1 ({slider.get_attribute('step')})")
    sides = s.driver.find_element("id", "value-a-sides")
    sides.clear()
    solved_after(s, lambda: sides.send_keys("3.5", Keys.ENTER))
    check(slider.get_attribute("value") == "4", "3.5 sides typed is 4 sides")


def reuleaux_sides(s):
    from selenium.webdriver.common.keys import Keys
    choose_kind(s, "b", "reuleaux")
    reuleaux = s.driver.find_element("css selector", "#sliders-b input[type=range]")
    s.js("arguments[0].value = 3; arguments[0].focus()", reuleaux)
    keys(s, Keys.ARROW_RIGHT)
    s.wait(lambda: reuleaux.get_attribute("value") != "3", 10, "the slider's step")
    s.settle()
    value = reuleaux.get_attribute("value")
    check(value == "5", f"one step up from a Reuleaux triangle is a pentagon ({value})")


def units(s):
    labels = s.js("return Array.from(document.querySelectorAll('.sliders label')).map(function (l) {"
                  " var u = l.querySelector('.unit'); return [u ? u.textContent : '', !!l.querySelector('input[type=number]')]; })")
    check(labels and all(u and box for u, box in labels), f"every slider shows its unit and a number box {labels}")


def starts_in_mm(s):
    """Starts typed in mm, nudged by 1 mm, by 10 mm with Shift."""
    from selenium.webdriver.common.keys import Keys
    field = s.driver.find_element("id", "start-mm-a")
    length = s.js("return window.studio.views[0].loop.length")
    field.click()
    field.clear()
    field.send_keys("100", Keys.ENTER)
    s.settle()
    got = s.js("return window.studio.shown.settings.start_a") * length
    check(abs(got - 100) < 1e-6, f"A's start typed as 100 mm ({got:.6f} mm)")
    keys(s, Keys.ARROW_UP, (Keys.SHIFT, Keys.ARROW_UP))
    s.settle()
    got = s.js("return window.studio.shown.settings.start_a") * length
    check(abs(got - 111) < 1e-6, f"up nudges 1 mm, Shift+up 10 mm ({got:.6f} mm)")
    s.driver.find_element("tag name", "body").click()


def labels_inside(s):
    """The handle's label inside its panel, at the outline's right- and top-most points."""
    for which in ("right", "top"):
        s.js(f"""var v = window.studio.views[1], p = v.loop.points, best = 0;
            for (var k = 0; k < v.loop.n; ++k) if ({'p[2*k] > p[2*best]' if which == 'right' else 'p[2*k+1] > p[2*best+1]'}) best = k;
            window.studio.setStart(1, v.loop.cumulative[best] / v.loop.length);""")
        s.settle()
        inside = s.js("var l = window.studio.views[1].handleLabel.getBoundingClientRect(),"
                      " b = document.getElementById('svg-b').getBoundingClientRect();"
                      " return [l.left >= b.left, l.right <= b.right, l.top >= b.top, l.bottom <= b.bottom]")
        check(all(inside), f"the handle's label is inside the panel at the {which}most point {inside}")


def help_list(s):
    """'?' lists the shortcuts; Escape closes the list."""
    from selenium.webdriver.common.keys import Keys
    s.driver.find_element("tag name", "body").click()
    keys(s, "?")
    s.wait(lambda: s.js("return document.getElementById('help').open"), 10, "the help")
    listed = s.js("return document.getElementById('help').textContent")
    check(all(k in listed for k in ("Ctrl", "Shift", "Z", "Esc", "?")), "'?' lists the shortcuts")
    keys(s, Keys.ESCAPE)
    check(not s.js("return document.getElementById('help').open"), "Escape closes the list")


def documented_outlines(s, source):
    """docs/studio.md names the page's outlines, no more and no fewer."""
    with open(os.path.join(source, "docs", "studio.md")) as f:
        docs = f.read()
    line = re.search(r"built-in parametric outlines with sliders \(([^)]*)\)", docs.replace("\n  ", " "))
    documented = sorted(x.strip().lower() for x in re.split(r",|\band\b", line.group(1)) if x.strip()) if line else []
    offered = sorted(k["label"].lower() for k in s.js("return window.studio.kinds || []"))
    check(documented and documented == offered, f"docs/studio.md lists the page's outlines ({documented} vs {offered})")


def main():
    dform, source = sys.argv[1], sys.argv[2]
    if studio_browser.skipped():
        return studio_browser.SKIP
    s = studio_browser.Studio(dform, [])
    try:
        s.settle()
        guarded("undo keys", undo_keys, s)
        guarded("Ctrl+Z in a box", box_undo, s)
        guarded("counts", counts, s)
        guarded("Reuleaux sides", reuleaux_sides, s)
        guarded("units", units, s)
        guarded("starts in mm", starts_in_mm, s)
        guarded("handle labels", labels_inside, s)
        guarded("help", help_list, s)
        guarded("the 3D view's tools", view, s)
        guarded("docs", documented_outlines, s, source)
        check(s.console_errors() == [], "no console errors")
    finally:
        s.close()
    return studio_browser.verdict()


if __name__ == "__main__":
    sys.exit(main())
