#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""dform studio in headless Chromium: failures shown where the designer looks, and one state.

Export of a design that fails the gate, or whose pattern does not fit the sheet, keeps the dialog
open (its buttons where they were when it opened, whatever the preview then says) and says why
and what to do in the page's words (its fields' labels, no command-line flag, no server path);
the zip without the cutting files is offered as what it is; ticking "export even if the gate
fails" gives the cutting files. A refused outline's message goes with the next change of the
design; a solve that fails takes the last shape, model and figures off the screen, and they come
back when the cause goes (undo); with B flipped the handle and the figures name the same start;
the strip says it is computing and marks its groups provisional until every start is in, and B's
start and flip (its own variables) leave it as it is; the inverse mode shows nothing of the
forward design.

    browser_feedback_test.py DFORM SAMPLES_DIR      (exit 77 when Chromium or Selenium is absent)
"""
import io
import os
import sys
import tempfile
import time
import zipfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import studio_browser  # noqa: E402
from studio_browser import check, guarded  # noqa: E402


def text(s, element_id):
    return s.js("return document.getElementById(arguments[0]).textContent", element_id)


def export_answer(s):
    """Clicks Download zip and waits for the dialog's answer: (message, downloaded)."""
    s.js("window.studio.lastDownload = null")
    s.driver.find_element("id", "export-go").click()
    s.wait(lambda: s.js("return !!window.studio.lastDownload") or
           text(s, "export-state") not in ("", "exporting…"), 300, "the export's answer")
    return text(s, "export-state"), s.js("return !!window.studio.lastDownload")


def button_place(s):
    """Where the export dialog's buttons are on the screen: a click on its way finds its button."""
    return s.js("return ['export-cancel', 'export-go'].map(function (id) {"
                " var r = document.getElementById(id).getBoundingClientRect(); return [r.x, r.y]; })")


def zip_names(s):
    archive = zipfile.ZipFile(io.BytesIO(s.download()))
    return {n: archive.read(n) for n in archive.namelist()}


def words_of_the_page(message):
    return "--" not in message and "/tmp" not in message and "dform export" not in message \
        and "export.sheet" not in message


def failed_export(dform, samples, work):
    """A job whose paper model fails the default gate (studio_browser.failing_job)."""
    s = studio_browser.Studio(dform, [studio_browser.failing_job(samples, work)])
    try:
        s.settle(300)
        s.driver.find_element("id", "export").click()
        opened = button_place(s)
        s.wait(lambda: s.js("var p = window.studio.preview; return p.idle() && !!p.shown"), 300, "the print preview")
        check(button_place(s) == opened and len(text(s, "export-preview")) > 200,
              f"the preview's long answer moves no button of the dialog ({opened}, {button_place(s)})")
        message, downloaded = export_answer(s)
        check(not downloaded and s.js("return document.getElementById('export-dialog').open"),
              "a failed gate's export keeps the dialog open and downloads nothing unasked")
        check("failed the quality gate 'default' (L_error" in message,
              f"it names the gate and the failing check ({message})")
        check('tick "export even if the gate fails"' in message and "no cutting files" in message,
              "it says what the zip lacks and what to do")
        check(words_of_the_page(message), "in the page's words (no flag, no server path)")
        partial = s.driver.find_element("id", "export-partial")
        check(partial.is_displayed() and "without the cutting files" in partial.text,
              "the zip without the cutting files is offered as what it is")
        partial.click()
        s.wait(lambda: s.js("return !!window.studio.lastDownload"), 30, "the partial zip")
        files = zip_names(s)
        check("report.json" in files and "pattern.svg" not in files, "that zip holds the report, no pattern")
        named = [n for n, content in files.items() if b"dform-studio-" in content]
        check(named == [], f"no file of the zip names the server's temporary folder {named}")

        s.driver.find_element("id", "export").click()
        s.js("document.getElementById('sheet').value = '100x100mm';"
             "document.getElementById('export-anyway').checked = true;")
        message, downloaded = export_answer(s)
        check(not downloaded and "does not fit the sheet" in message, f"a sheet too small is said ({message})")
        check('"scale" fit' in message and 'a larger "sheet"' in message and words_of_the_page(message),
              "with what to do, in the dialog's field names")

        s.js("document.getElementById('sheet').value = ''")
        message, downloaded = export_answer(s)
        check(downloaded and not s.js("return document.getElementById('export-dialog').open"),
              "export even if the gate fails downloads at once")
        check("pattern.svg" in zip_names(s), "with the cutting files")
    finally:
        s.close()


# The pieces the 3D view draws (-1: a page without the count).
PARTS = "(window.studio.view3d.partCount ? window.studio.view3d.partCount() : -1)"


def wait_shape(s, seq):
    s.wait(lambda: s.js("return window.studio.frameSeq") > seq, 120, "the next answer")


def one_state(dform, samples, work):
    s = studio_browser.Studio(dform, [])
    try:
        s.settle()
        guarded("refused outline", refused_outline, s, work)
        guarded("flipped start", flipped_start, s)
        guarded("strip", strip_computing, s)
        guarded("exact on a non-convex pair", failed_solve, s, samples)
        guarded("inverse mode", inverse_mode, s)
        errors = [e for e in s.console_errors() if not ("/api/outline" in e["message"] and " 400 " in e["message"])]
        check(errors == [], f"no console errors {errors}")
    finally:
        s.close()


def refused_outline(s, work):
    # A refused outline: its message stands until the design next changes.
    bad = os.path.join(work, "bad.svg")
    with open(bad, "w") as f:
        f.write("<svg xmlns='http://www.w3.org/2000/svg'><path d='M 10 10 L 90 10 L 50'/></svg>")
    s.driver.find_element("id", "file-a").send_keys(bad)
    s.wait(lambda: text(s, "error-a") != "", 30, "the reader's error")
    s.driver.find_element("id", "flip").click()
    s.settle()
    check(text(s, "error-a") == "", "a refused outline's message goes with the next change")


def flipped_start(s):
    # Flipped B: the handle and the figures name one start.
    s.js("window.studio.setStart(1, 0.102)")
    s.settle()
    check(s.js("return window.studio.shown.settings.flip") is True, "B is flipped")
    label = s.js("return window.studio.views[1].handleLabel.textContent")
    figures = text(s, "figures")
    check(label == "B start 0.102" and "B 0.1020" in figures, f"handle '{label}' and figures agree ({figures})")


def strip_computing(s):
    # The strip computing: said, and its groups provisional until every start is in. Every
    # change of the strip is recorded as it happens (a MutationObserver), not sampled.
    s.js("""var c = document.getElementById('strip-cards'), log = window.stripLog = [];
        new MutationObserver(function () {
          log.push([c.getAttribute('data-state'), (document.getElementById('strip-status') || {}).textContent || '',
                    getComputedStyle(c).backgroundImage,
                    Array.from(c.querySelectorAll('.card span')).map(function (e) { return e.textContent; })]);
        }).observe(c, { attributes: true, childList: true, subtree: true });""")
    s.driver.find_element("id", "fit").click()  # the built-in ellipses' perimeters are equal
    s.wait(lambda: s.js("return document.getElementById('strip-cards').getAttribute('data-state')") == "done", 300,
           "the strip")
    seen = {"computing": False, "final_group_early": False, "status": ""}
    for state in s.js("return window.stripLog"):
        if state[0] == "computing" and state[3]:
            seen["computing"] = True
            seen["status"] = state[1]
            seen["style"] = state[2]
            if any("×" in t and "so far" not in t for t in state[3]):
                seen["final_group_early"] = True
    check(seen["computing"] and " of 32" in seen["status"] and seen.get("style", "none") != "none",
          f"the strip says it is computing ({seen['status']})")
    check(seen["computing"] and not seen["final_group_early"], "no group is shown as final while the strip computes")
    final = s.js("return Array.from(document.querySelectorAll('#strip-cards .card span'))"
                 ".map(function (e) { return e.textContent; })")
    check(any("×" in t for t in final) and not any("so far" in t for t in final),
          "the finished strip's groups are final")
    s.driver.find_element("id", "fit").click()  # back on, for the parts after this one
    s.wait(lambda: s.js("return document.getElementById('strip-cards').getAttribute('data-state')") == "done", 300,
           "the strip")
    s.settle()

    # B's start and flip are the strip's own variables: changing them leaves it as it is; A's
    # start makes it anew.
    seq, logged = s.js("return window.studio.strip.seq"), len(s.js("return window.stripLog"))
    s.driver.find_element("id", "flip").click()
    s.settle()
    s.js("window.studio.setStart(1, 0.3)")
    s.settle()
    time.sleep(1.0)  # past the strip's 300 ms debounce
    kept = s.js("return [window.studio.strip.seq, document.getElementById('strip-cards').getAttribute('data-state'),"
                " window.stripLog.length]")
    check(kept == [seq, "done", logged], f"B's flip and start leave the strip as it was ({kept}, {seq}, {logged})")
    s.js("window.studio.setStart(0, 0.1)")
    try:
        s.wait(lambda: s.js("return window.studio.strip.seq") > seq, 30, "A's start's strip")
    except TimeoutError:
        pass  # said by the check below
    renewed = s.js("return [window.studio.strip.seq, window.stripLog.length]")
    check(renewed[0] > seq and renewed[1] > logged, f"A's start makes the strip anew ({renewed}, {seq}, {logged})")
    for _ in range(2):  # A's start and B's as they were (B stays unflipped)
        s.driver.find_element("id", "undo").click()
    s.settle()
    s.wait(lambda: s.js("return document.getElementById('strip-cards').getAttribute('data-state')") == "done", 300,
           "the strip")


def failed_solve(s, samples):
    # Exact forced on a non-convex pair: no stale shape; undo brings the design back.
    seq = s.js("return window.studio.frameSeq")
    s.js("var m = document.getElementById('model-choice'); m.value = 'exact'; m.dispatchEvent(new Event('change'))")
    wait_shape(s, seq)
    seq = s.js("return window.studio.frameSeq")
    s.driver.find_element("id", "file-a").send_keys(os.path.join(samples, "forward", "nonconvex-a.svg"))
    s.wait(lambda: s.js("return document.getElementById('status').className") == "status error", 120, "the error")
    cleared = s.js("return [window.studio.shown, " + PARTS + ","
                   " document.getElementById('figures').rows.length, document.getElementById('model').textContent,"
                   " document.getElementById('status').className, document.querySelectorAll('#svg-a-marks .found-crease').length]")
    check(cleared[4] == "status error", f"the failed solve is said ({text(s, 'status')})")
    check(cleared[0] is None and cleared[1] == 0 and cleared[2] == 0 and cleared[3] == "",
          f"its design shows no old shape, model or figures {cleared}")
    s.driver.find_element("id", "undo").click()
    s.settle()
    check(s.js("return document.getElementById('status').className") != "status error" and
          s.js("return " + PARTS) == 2,
          "undo brings back a shape and clears the error")


def inverse_mode(s):
    # The inverse mode shows nothing of the forward design.
    s.js("var k = document.getElementById('kind-a'); k.value = 'polygon'; k.dispatchEvent(new Event('change'))")
    s.wait(lambda: s.js("return document.querySelectorAll('#sliders-a input').length") > 0, 30, "the sliders")
    s.settle()
    s.driver.find_element("id", "mode-inverse").click()
    state = s.js("return [getComputedStyle(document.getElementById('sliders-a')).display,"
                 " " + PARTS + ", document.querySelectorAll('#svg-a-marks .handle, #svg-a .cut').length,"
                 " document.getElementById('figures').rows.length, !!window.studio.shown]")
    check(state == ["none", 0, 0, 0, False], f"inverse mode: no sliders, shape, pieces or figures of the forward design {state}")
    s.driver.find_element("id", "mode-forward").click()
    s.settle()
    check(s.js("return " + PARTS) == 2 and
          s.js("return document.querySelectorAll('#svg-a-marks .handle').length") == 1, "back in forward, its design again")


def main():
    dform, samples = sys.argv[1], os.path.abspath(sys.argv[2])
    if studio_browser.skipped():
        return studio_browser.SKIP
    work = tempfile.mkdtemp(prefix="dform-studio-feedback-")
    guarded("export", failed_export, dform, samples, work)
    one_state(dform, samples, work)
    return studio_browser.verdict()


if __name__ == "__main__":
    sys.exit(main())
