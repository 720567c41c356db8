#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""dform studio in headless Chromium: the ruled engine's states, the way the strip shows starts.

The anti sample's card sits two ways (docs/ruled.md): the page shows a card for each, least bending
first, with the bending energies `dform run` lists in report.json; clicking the second draws that
state in the 3D view (another shape, without the answer's strain and failure overlay) and says
so; clicking the first brings the answer back with its overlay. A design with one state (the
shipped ellipses, exact) shows no such strip.

    browser_states_test.py DFORM SAMPLES_DIR      (exit 77 when Chromium or Selenium is absent)
"""
import json
import os
import subprocess
import sys
import tempfile
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import studio_browser  # noqa: E402
from studio_browser import check, guarded  # noqa: E402

# The largest distance between the seam points of two states' pieces (mm).
SEAM_APART = """var a = arguments[0], b = arguments[1], worst = 0;
    for (var p = 0; p < 2; ++p) for (var k = 0; k < a[p].seam.length; ++k) {
      var i = 3 * a[p].seam[k], j = 3 * b[p].seam[k];
      worst = Math.max(worst, Math.hypot(a[p].shape[i] - b[p].shape[j], a[p].shape[i + 1] - b[p].shape[j + 1],
                                         a[p].shape[i + 2] - b[p].shape[j + 2]));
    }
    return worst;"""


def anti_states(dform, samples, work):
    job = os.path.join(samples, "forward", "anti.json")
    subprocess.run([dform, "run", job, "--no-export", "-o", os.path.join(work, "anti")], check=True,
                   capture_output=True)
    with open(os.path.join(work, "anti", "report.json")) as f:
        listed = [state["bending_energy"] for state in json.load(f)["model"]["states"]]
    check(len(listed) == 2, f"the CLI lists the anti sample's two states ({listed})")
    s = studio_browser.Studio(dform, [job])
    try:
        s.settle(300)
        s.wait(lambda: s.js("return window.studio.states.list.length") == len(listed), 30, "the states")
        # The cards' pictures are drawn after the answer's frame.
        s.wait(lambda: s.js("return document.querySelectorAll('#state-cards .card img').length") == len(listed), 30,
               "the states' pictures")
        shown = s.js("return [!document.getElementById('states').hidden,"
                     " document.querySelectorAll('#state-cards .card').length,"
                     " window.studio.states.list.map(function (x) { return x.bending; }),"
                     " window.studio.states.list.every(function (x) {"
                     "   return !!x.pieces && /^data:image\\/png;base64,/.test(x.picture) && x.picture.length > 2000; })]")
        check(shown[0] and shown[1] == 2, f"a card for each state ({shown[1]})")
        check(all(abs(a - b) <= 1e-9 * abs(b) for a, b in zip(shown[2], listed)) and shown[2] == sorted(shown[2]),
              f"their bending energies are the report's, least first ({shown[2]} against {listed})")
        check(shown[3], "each state has its shape and its picture")
        # set() makes the cards at once and their pictures after the frame; a newer list drops the
        # pictures due for the one before (two sets, one drawing).
        quick = s.js("""var st = window.studio.states, list = st.list, drawn = 0, pictures = st.pictures;
            st.pictures = function () { ++drawn; return pictures.apply(this, arguments); };
            window.picturesDrawn = function () { return drawn; };
            var again = list.map(function (x) { return { start: x.start, bending_energy: x.bending,
                                                         largest_fold_deg: x.fold, pieces: x.pieces }; });
            st.set(again, list[0].pieces, function (p) { return p; });
            st.set(again, list[0].pieces, function (p) { return p; });
            return [document.querySelectorAll('#state-cards .card').length,
                    document.querySelectorAll('#state-cards .card img').length, drawn];""")
        check(quick == [2, 0, 0], f"the cards come at once, their pictures later ({quick})")
        s.wait(lambda: s.js("return document.querySelectorAll('#state-cards .card img').length") == 2, 30,
               "the pictures again")
        time.sleep(0.2)
        check(s.js("return window.picturesDrawn()") == 1, "drawn once for the newest list")
        s.js("window.studio.overlay.setMode('strain')")
        s.wait(lambda: s.js("return !!window.studio.overlay.data"), 120, "the answer's figures")
        s.driver.find_element("css selector", "#state-cards .card[data-index='1']").click()
        other = s.js("var st = window.studio.states; return [st.shown, window.studio.view3d.model() === st.list[1].pieces,"
                     " window.studio.overlay.data === null, document.getElementById('states-note').textContent,"
                     " document.querySelector('#state-cards .card[data-index=\"1\"]').getAttribute('aria-pressed')]")
        check(other[:3] == [1, True, True] and other[4] == "true",
              f"the second card draws the second state, without the answer's overlay ({other[:3]}, {other[4]})")
        check("another way" in other[3] and "the answer's" in other[3], f"and the page says so ({other[3]!r})")
        apart = s.js("return (function () {" + SEAM_APART + "})(window.studio.states.list[0].pieces,"
                     " window.studio.states.list[1].pieces)")
        check(apart > 1.0, f"a shape of its own (seams up to {apart:.1f} mm apart)")
        s.driver.find_element("css selector", "#state-cards .card[data-index='0']").click()
        back = s.js("var st = window.studio; return [st.states.shown, st.view3d.model() === st.shown.result.decoded,"
                    " !!st.overlay.data]")
        check(back == [0, True, True], f"the first card brings the answer back with its overlay ({back})")
        check(s.console_errors() == [], "no console errors")
    finally:
        s.close()


def one_state(dform, samples):
    s = studio_browser.Studio(dform, [os.path.join(samples, "forward", "ellipses-a.svg"),
                                      os.path.join(samples, "forward", "ellipses-b.svg")])
    try:
        s.settle()
        check(s.js("return document.getElementById('states').hidden && window.studio.states.list.length === 0"),
              "one state (the exact ellipses): no strip of states")
    finally:
        s.close()


def main():
    dform, samples = sys.argv[1], os.path.abspath(sys.argv[2])
    if studio_browser.skipped():
        return studio_browser.SKIP
    work = tempfile.mkdtemp(prefix="dform-studio-states-")
    guarded("states", anti_states, dform, samples, work)
    guarded("one state", one_state, dform, samples)
    return studio_browser.verdict()


if __name__ == "__main__":
    sys.exit(main())
