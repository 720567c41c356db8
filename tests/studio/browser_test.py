#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""dform studio in a real browser (headless Chromium): the page loads without console errors;
dragging a start handle changes the shape, and the shape is the command line's for that start;
a raw pointer update during a drag moves the handle and is solved at once, and the release
settles the last position (refined without waiting for a pause);
dragging B's start round a square at 60 Hz is answered by the exact model at every position;
flip and the alternative-starts strip work; a bad SVG shows its error and the next good one
solves; Save job + `dform run` reproduces the figures; Export's pattern.svg is the CLI's, byte
for byte; the export dialog's material, numbers and hinge lists are the settings table's and reach
the export and the saved job; requests without the token or from a foreign origin get 403.

    browser_test.py DFORM SAMPLES_DIR      (exit 77 when Chromium, its driver or Selenium is absent)
"""
import json
import math
import os
import subprocess
import sys
import tempfile
import urllib.error
import urllib.request

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import studio_browser  # noqa: E402
from studio_browser import check  # noqa: E402


def http_status(url, headers):
    try:
        return urllib.request.urlopen(urllib.request.Request(url, headers=headers), timeout=10).status
    except urllib.error.HTTPError as e:
        return e.code


def obj_vertices(path):
    with open(path) as f:
        return [[float(x) for x in line.split()[1:4]] for line in f if line.startswith("v ")]


def downloaded_json(s, button, folder, name):
    """Clicks `button`, unzips the download into `folder` and reads its JSON file `name`."""
    s.js("window.studio.lastDownload = null")
    s.driver.find_element("id", button).click()
    s.wait(lambda: s.js("return !!window.studio.lastDownload"), 120, "the download of " + button)
    studio_browser.unzip(s.download(), folder)
    with open(os.path.join(folder, name)) as f:
        return json.load(f)


def drag_handle(s, piece, steps):
    """Drags piece's start handle along its outline with real pointer input (a quarter turn)."""
    from selenium.webdriver.common.action_chains import ActionChains
    from selenium.webdriver.common.by import By
    handle = s.driver.find_element(By.CSS_SELECTOR, f"#svg-{piece}-marks circle.handle")
    svg = s.driver.find_element(By.ID, f"svg-{piece}")
    before = s.js(f"return window.studio.shown.settings.start_{piece}")
    actions = ActionChains(s.driver, duration=10).click_and_hold(handle)
    # Points of the outline a quarter turn on, in screen offsets from the handle.
    points = s.js(f"""
        var v = window.studio.views[{'ab'.index(piece)}], out = [], h = v.handle.getBoundingClientRect();
        var m = v.svg.getScreenCTM();
        for (var k = 1; k <= {steps}; ++k) {{
          var p = v.loop.at(v.fraction + 0.25 * k / {steps}), q = v.svg.createSVGPoint();
          q.x = p[0]; q.y = -p[1]; q = q.matrixTransform(m);
          out.push([q.x - (h.left + h.width / 2), q.y - (h.top + h.height / 2)]);
        }}
        return out;""")
    last = [0, 0]
    for x, y in points:
        actions.move_by_offset(round(x - last[0]), round(y - last[1]))
        last = [round(x), round(y)]
    actions.release().perform()
    s.settle()
    return before


def drag_round(s, piece, moves, pause):
    """Drags piece's start handle once round its outline, one real pointer move every `pause`
    seconds (1/60: a 60 Hz pointer)."""
    from selenium.webdriver.common.action_chains import ActionChains
    from selenium.webdriver.common.by import By
    points = s.js(f"""
        var v = window.studio.views[{'ab'.index(piece)}], out = [], h = v.handle.getBoundingClientRect();
        var m = v.svg.getScreenCTM();
        for (var k = 1; k <= {moves}; ++k) {{
          var p = v.loop.at(v.fraction + k / {moves}), q = v.svg.createSVGPoint();
          q.x = p[0]; q.y = -p[1]; q = q.matrixTransform(m);
          out.push([Math.round(q.x - (h.left + h.width / 2)), Math.round(q.y - (h.top + h.height / 2))]);
        }}
        return out;""")
    actions = ActionChains(s.driver, duration=0).click_and_hold(
        s.driver.find_element(By.CSS_SELECTOR, f"#svg-{piece}-marks circle.handle"))
    last = [0, 0]
    for x, y in points:
        actions.move_by_offset(x - last[0], y - last[1]).pause(pause)
        last = [x, y]
    actions.release().perform()
    s.settle()


def main():
    dform, samples = sys.argv[1], sys.argv[2]
    if studio_browser.skipped():
        return studio_browser.SKIP
    a, b = os.path.join(samples, "forward", "ellipses-a.svg"), os.path.join(samples, "forward", "ellipses-b.svg")
    work = tempfile.mkdtemp(prefix="dform-studio-browser-")
    s = studio_browser.Studio(dform, [a, b])
    try:
        s.settle()
        errors = s.console_errors()
        check(errors == [], f"the page loads without console errors {errors}")
        check(s.js("return document.getElementById('model').textContent") == "exact", "the exact model is shown")

        first = s.js("return Array.from(window.studio.shown.pieces[0].shape)")
        # What B's drag leaves as it was is not drawn again: A's ticks and handle, the model's name.
        s.js("window.redrawn = 0; ['#svg-a-marks .ticks', '#svg-a-marks .handle', '#svg-a-marks .handle-label', '#model']"
             " .forEach(function (css) { new MutationObserver(function (m) { window.redrawn += m.length; })"
             " .observe(document.querySelector(css), { subtree: true, childList: true, attributes: true, characterData: true }); });")
        answers_before = len(s.js("return window.studio.answers"))
        before = drag_handle(s, "b", 12)
        redrawn, answers = s.js("return window.redrawn"), len(s.js("return window.studio.answers")) - answers_before
        check(answers >= 2 and redrawn == 0,
              f"B's drag ({answers} answers) redraws neither A's ticks and handle nor the model's name ({redrawn} changes)")
        after = s.js("return window.studio.shown.settings")
        shape = s.js("return Array.from(window.studio.shown.pieces[0].shape)")
        check(abs(after["start_b"] - before) > 0.05, f"dragging B's handle moved its start ({before} -> {after['start_b']})")
        check(shape != first, "the shape changed with the start")

        # The command line's shape for the same start.
        out = os.path.join(work, "cli-drag")
        subprocess.run([dform, "forward", a, b, "--start-a", repr(after["start_a"]), "--start-b", repr(after["start_b"]),
                        "--fit-perimeter", "--no-export", "--gate", "none", "-q", "-o", out], check=True)
        cli = obj_vertices(os.path.join(out, "piece-a-3d.obj"))
        seam = s.js("return window.studio.shown.result.pieces[0].seam")
        lo = [min(v[k] for v in cli) for k in range(3)]
        hi = [max(v[k] for v in cli) for k in range(3)]
        diagonal = math.dist(lo, hi)
        worst = max(math.dist(cli[i], shape[3 * i:3 * i + 3]) for i in seam) if len(cli) * 3 == len(shape) else math.inf
        check(worst <= 1e-9 * diagonal, f"seam vertices equal the CLI's for the same start (largest distance {worst:.3g} mm)")

        # A drag takes each move as the browser gets it (pointerrawupdate), not once a frame: a raw
        # update moves the handle and asks for its shape at once; the frame's pointermove after it
        # asks nothing more. (Alt held: no snapping, so the handle goes where the pointer is.)
        from selenium.webdriver.common.action_chains import ActionChains
        from selenium.webdriver.common.by import By
        s.js("""window.settles = []; var fetched = window.fetch;
                window.fetch = function (path, init) {
                  if (path === "/api/settle") window.settles.push(JSON.parse(init.body).seq);
                  return fetched.apply(this, arguments);
                };""")
        ActionChains(s.driver, duration=0).click_and_hold(
            s.driver.find_element(By.CSS_SELECTOR, "#svg-b-marks circle.handle")).perform()
        raw = s.js("""
            var v = window.studio.views[1], m = v.svg.getScreenCTM(), moves = window.studio.moves.length;
            function send(type, f) {
              var p = v.loop.at(f), q = v.svg.createSVGPoint();
              q.x = p[0]; q.y = -p[1]; q = q.matrixTransform(m);
              v.svg.dispatchEvent(new PointerEvent(type, { clientX: q.x, clientY: q.y, pointerId: 1,
                                                           isPrimary: true, altKey: true, bubbles: true }));
              return [window.studio.moves.length - moves, v.fraction];
            }
            var target = (v.fraction + 0.1) % 1;
            return { target: target, raw: send("pointerrawupdate", target),
                     move: send("pointermove", (v.fraction + 0.2) % 1) };""")
        ActionChains(s.driver, duration=0).release().perform()
        s.settle()
        check(raw["raw"][0] == 1 and abs(raw["raw"][1] - raw["target"]) < 1e-3,
              f"a raw pointer update during a drag moves B's handle and asks for its shape ({raw})")
        check(raw["move"] == raw["raw"], f"the frame's pointermove after it changes nothing ({raw})")
        shown = s.js("return window.studio.shown.settings.start_b")
        check(abs(shown - raw["raw"][1]) < 1e-12, f"the raw update's start is the one solved ({shown})")
        # The release tells the server the drag's last position is final (refined without a pause).
        settles, last = s.js("return [window.settles, window.studio.moves[window.studio.moves.length - 1].seq]")
        check(settles == [last], f"the release settles the drag's last position ({settles}, last asked {last})")

        flat_before = s.js("return window.studio.shown.result.pieces[1].flat")
        s.driver.find_element("id", "flip").click()
        s.settle()
        check(s.js("return window.studio.shown.settings.flip") is True, "flip is on")
        check(s.js("return window.studio.shown.result.pieces[1].flat") != flat_before, "flipping B changes piece B")

        s.wait(lambda: s.js("return document.getElementById('strip-cards').getAttribute('data-state')") == "done", 180,
               "the strip")
        cards = s.driver.find_elements("css selector", "#strip-cards .card")
        grouped = s.js("return document.querySelectorAll('#strip-cards .card').length")
        check(0 < grouped < 32, f"the strip shows {grouped} cards for 32 starts (symmetric duplicates grouped)")
        target = cards[min(1, len(cards) - 1)]
        want_b, want_flip = float(target.get_attribute("data-start-b")), target.get_attribute("data-flip") == "true"
        target.click()
        s.settle()
        got = s.js("return window.studio.shown.settings")
        check(abs(got["start_b"] - want_b) < 1e-12 and got["flip"] == want_flip, "clicking a card jumps to its start")

        # A setting change schedules a new run; the old run's end, arriving in the debounce, must not
        # mark the strip done while its cards are about to be replaced.
        old_seq = s.js("return window.studio.strip.seq")
        state = s.js("document.getElementById('fit').click(); window.studio.strip.done({seq: arguments[0]});"
                     " return document.getElementById('strip-cards').getAttribute('data-state')", old_seq)
        check(state == "scheduled", f"the finished run's end leaves the newly scheduled strip alone ({state})")
        s.driver.find_element("id", "fit").click()
        s.settle()

        bad = os.path.join(work, "bad.svg")
        with open(bad, "w") as f:
            f.write("<svg xmlns='http://www.w3.org/2000/svg' width='100mm' height='100mm'><path d='M 10 10 L 90 10 L 50'/></svg>")
        s.driver.find_element("id", "file-a").send_keys(bad)
        s.wait(lambda: s.js("return document.getElementById('error-a').textContent") != "", 30, "the reader's error")
        error = s.js("return document.getElementById('error-a').textContent")
        check("bad.svg" in error, f"a bad SVG shows the reader's error ({error})")
        seq = s.js("return window.studio.frameSeq")
        s.driver.find_element("id", "file-a").send_keys(os.path.join(samples, "forward", "circle.svg"))
        s.wait(lambda: s.js("return window.studio.frameSeq") > seq, 60, "the next good outline's shape")
        s.settle()
        check(s.js("return document.getElementById('error-a').textContent") == "", "the good outline clears the error")
        check("circle.svg" in s.js("return document.getElementById('name-a').textContent"), "the good outline solved")

        # Circle + square, B's start dragged round the whole square at 60 Hz: across its four
        # corners every position is answered by the exact model at the page's resolution (no
        # preview), and every verdict shown passes.
        seq = s.js("return window.studio.frameSeq")
        s.driver.find_element("id", "file-b").send_keys(os.path.join(samples, "forward", "square.svg"))
        s.wait(lambda: s.js("return window.studio.frameSeq") > seq, 60, "the square's shape")
        s.settle()
        first = s.js("return [window.studio.answers.length, window.studio.verdicts.length]")
        resolution = s.js("return window.studio.shown.settings.resolution")
        drag_round(s, "b", 480, 1 / 60)
        s.wait(lambda: s.js("return !!window.studio.shown.result.gate"), 120, "the last position's verdict")
        answers = s.js("return window.studio.answers")[first[0]:]
        verdicts = s.js("return window.studio.verdicts")[first[1]:]
        waiting = s.js("return window.studio.inputsWaiting()")
        check(waiting == 0, f"the page keeps no input time of a position the drag moved past ({waiting} kept)")
        starts = sorted(a["start_b"] % 1.0 for a in answers)
        gap = max([b - a for a, b in zip(starts, starts[1:])] + [starts[0] + 1.0 - starts[-1]]) if starts else 1.0
        not_exact = [a for a in answers if a["model"] != "exact" or a["preview"] or a["seam"] != resolution]
        check(len(answers) >= 8 and gap < 0.1,
              f"the drag round the square was answered all along it ({len(answers)} positions, largest gap {gap:.3f})")
        check(not not_exact, f"every position the exact model's at {resolution} seam points, none a preview {not_exact[:3]}")
        check(verdicts and all(v["passed"] for v in verdicts),
              f"every verdict shown passed ({sum(not v['passed'] for v in verdicts)} of {len(verdicts)} failed)")

        s.driver.find_element("id", "save-job").click()
        s.wait(lambda: s.js("return !!window.studio.lastDownload"), 30, "the saved job")
        job_dir = os.path.join(work, "job")
        studio_browser.unzip(s.download(), job_dir)
        cli_dir = os.path.join(work, "cli-job")
        subprocess.run([dform, "run", os.path.join(job_dir, "job.json"), "-o", cli_dir, "-q"], check=True)
        with open(os.path.join(cli_dir, "report.json")) as f:
            report = json.load(f)
        # The figures follow the shape with the gate's verdict, into the panel.
        s.wait(lambda: s.js("return !!window.studio.shown.result.figures"), 60, "the shown shape's figures")
        figures = s.js("return window.studio.shown.result.figures")
        check("%.3f %%" % (100 * figures["L_error"]) in s.js("return document.getElementById('figures').textContent"),
              "the shape's figures are in the panel")
        same = all(report["metrics"][k] == figures[k] for k in ("L_error", "L_max", "B_error", "angle_defect_max_rad"))
        check(same, "Save job + dform run reproduces the figures")

        s.js("window.studio.lastDownload = null")
        s.driver.find_element("id", "export").click()
        s.driver.find_element("id", "export-go").click()
        s.wait(lambda: s.js("return !!window.studio.lastDownload"), 120, "the export")
        export_dir = os.path.join(work, "export")
        studio_browser.unzip(s.download(), export_dir)
        with open(os.path.join(export_dir, "pattern.svg"), "rb") as f1, open(os.path.join(cli_dir, "pattern.svg"), "rb") as f2:
            check(f1.read() == f2.read(), "Export's pattern.svg is byte-identical to the CLI's")

        # The dialog's lists are the settings table's; what they are set to reaches the export and
        # the saved job.
        s.driver.find_element("id", "export").click()
        lists = s.js("return ['material', 'numbers', 'hinge'].map(function (k) {"
                     " return Array.from(document.getElementById(k).options).map(function (o) { return o.value; }); })")
        check(lists[1] == ["", '"face"', '"tabs"', '"both"'] and lists[2] == ["", "true", "false"] and
              '"plywood"' in lists[0], f"the export dialog lists material, numbers and hinge ({lists})")
        s.js("document.getElementById('numbers').value = '\"both\"';"
             " document.getElementById('hinge').value = 'false'")
        listed = downloaded_json(s, "export-go", os.path.join(work, "export-lists"),
                                 "report.json")["job"]["export"]
        check(listed.get("numbers") == "both" and listed.get("hinge") is False,
              f"the dialog's numbers and hinge reach the export ({listed})")
        saved = downloaded_json(s, "save-job", os.path.join(work, "job-lists"), "job.json")["export"]
        check(saved.get("numbers") == "both" and saved.get("hinge") is False,
              f"Save job keeps the dialog's numbers and hinge ({saved})")

        # A pair whose glued metric is not convex: a preview at once, then the refined shape (the
        # ruled engine's: the paper model's shape made exact) streamed, with the seam point that
        # breaks convexity marked on the pieces.
        seq = s.js("return window.studio.frameSeq")
        s.driver.find_element("id", "file-a").send_keys(os.path.join(samples, "forward", "nonconvex-a.svg"))
        s.wait(lambda: s.js("return window.studio.frameSeq") > seq, 60, "the first non-convex shape")
        seq = s.js("return window.studio.frameSeq")
        s.driver.find_element("id", "file-b").send_keys(os.path.join(samples, "forward", "nonconvex-b.svg"))
        s.wait(lambda: s.js("return window.studio.frameSeq") > seq, 60, "the non-convex pair's shape")
        preview = s.js("return window.studio.shown.result.preview")
        s.settle(300)
        result = s.js("return window.studio.shown.result")
        check(preview and not result["preview"] and result["model"]["name"] == "ruled",
              f"a non-convex pair shows a preview, then the refined ruled shape ({result['model']['name']})")
        check(len(result["pieces"][0]["seam"]) == 100, "the refined shape has the page's resolution")
        check("seam point" in result["model"]["reason"] and
              len(s.driver.find_elements("css selector", "#svg-a-marks circle.break-point")) == 1,
              "the seam point that breaks convexity is named and marked")

        base = f"http://127.0.0.1:{s.port}"
        check(http_status(base + "/", {}) == 403, "a request without the token gets 403")
        check(http_status(base + "/api/session", {"X-Dform-Token": s.token, "Origin": "http://evil.example"}) == 403,
              "a request with a foreign Origin gets 403")
        check(http_status(base + "/?token=" + s.token, {"Host": "evil.example:%d" % s.port}) == 403,
              "a request with a foreign Host gets 403")
        # The bad SVG's upload was answered 400, which the browser logs; nothing else may be.
        errors = [e for e in s.console_errors() if not ("/api/outline" in e["message"] and " 400 " in e["message"])]
        check(errors == [], f"no other console errors {errors}")
    finally:
        s.close()
    code = s.process.returncode
    check(code == 143, f"SIGTERM stops the studio with exit 143 (got {code})")
    return studio_browser.verdict()


if __name__ == "__main__":
    sys.exit(main())
