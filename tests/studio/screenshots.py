#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""The screenshots of docs/studio.md, taken from the real page in headless Chromium:

    screenshots.py BUILD/dform SAMPLES_DIR OUT_DIR

studio-forward.png: the shipped ellipse pair, B's start dragged to 0.3 (flipped off), the strip
done, the strain drawn on the shape, the seam point a third of the way round picked, the print
preview open (the design's export settings: the laser profile); studio-inverse.png: the pushed-in
seam curve in the inverse mode, its print preview (what Export would say).
"""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import studio_browser  # noqa: E402


def main():
    dform, samples, out = sys.argv[1], os.path.abspath(sys.argv[2]), sys.argv[3]
    forward = os.path.join(samples, "forward")
    s = studio_browser.Studio(dform, [os.path.join(forward, "ellipses-a.svg"), os.path.join(forward, "ellipses-b.svg")],
                              1500, 900)
    try:
        s.settle()
        s.js("window.studio.setStart(1, 0.3)")
        s.settle()
        s.wait(lambda: s.js("return document.getElementById('strip-cards').getAttribute('data-state')") == "done", 300)
        s.wait(lambda: s.js("var r = window.studio.shown.result; return !!(r.gate && r.overlay)"), 120)
        s.js("var o = document.getElementById('overlay'); o.value = 'strain'; o.dispatchEvent(new Event('change'));"
             "var p = window.studio.picking; p.pick(Math.floor(window.studio.shown.pieces[0].seam.length / 3));")
        s.js("window.studio.preview.schedule(0); document.getElementById('preview').open = true;")
        s.wait(lambda: s.js("var p = window.studio.preview; return p.idle() && !!p.shown"), 300)
        s.js("document.getElementById('preview').scrollIntoView()")
        s.driver.save_screenshot(os.path.join(out, "studio-forward.png"))
        s.driver.find_element("id", "mode-inverse").click()
        s.driver.find_element("id", "curve-file").send_keys(os.path.join(samples, "inverse", "pushed-in.obj"))
        s.wait(lambda: s.js("return window.studio.shown && window.studio.shown.result.mode") == "inverse", 300)
        s.settle(300)
        s.js("var o = document.getElementById('overlay'); o.value = 'none'; o.dispatchEvent(new Event('change'));")
        s.wait(lambda: s.js("var p = window.studio.preview; return p.idle() && !!p.shown && p.shown.seq > 1"), 300)
        s.driver.save_screenshot(os.path.join(out, "studio-inverse.png"))
        errors = s.console_errors()
        if errors:
            print("console errors:", errors)
            return 1
    finally:
        s.close()
    return 0


if __name__ == "__main__":
    sys.exit(main())
