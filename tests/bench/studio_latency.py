#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""dform studio's live-drag latency in a real browser (docs/benchmarks.md, "Studio"): headless
Chromium drags piece B's start handle (resolution 100) through POSITIONS positions along half its
outline, one real pointer move every PAUSE seconds (1/60: a 60 Hz pointer), once with Chromium's
--disable-gpu and once with its GPU process (WebGL on SwiftShader either way), after the page's
first strip of alternative starts is done. Every move is counted: its latency is the time from
its pointer event (event.timeStamp) to the first animation frame after a shape for it, or for a
newer move, was drawn (a move that never got a frame of its own counts at the next frame's time).
Prints, per flag, the median, the 95th percentile and how many moves got a frame of their own,
each process's CPU time over the drag (Chromium's by kind, the server's) and where a drawn
shape's time went.

    studio_latency.py BUILD/dform SAMPLES_DIR [--pair ellipses|circle-square] [--gpu both|off|on]
                      [--pause 0.016667] [--positions 100] [--instant]

With --instant the page's own part alone: every position is answered at once, in the page, with the
answer to the first one (its seq changed), so the server solves nothing during the drag.

With --paper: the non-convex sample pair (the ruled engine; each position first drawn as a preview
at 36 seam points) dragged for positions x pause seconds; prints how long after letting go (the
pointerup's time) the frames came that drew the last position's preview and its refined shape
(0 where the preview was drawn before the release), and every move's latency to its first shape
(as above) with how many came within 150 ms.
    studio_latency.py BUILD/dform SAMPLES_DIR --paper --positions 50 --pause 0.1
"""
import argparse
import glob
import os
import re
import statistics
import sys
import time

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "studio"))
import studio_browser  # noqa: E402

PAIRS = {"ellipses": ("ellipses-a.svg", "ellipses-b.svg"), "circle-square": ("circle.svg", "square.svg"),
         "paper": ("nonconvex-a.svg", "nonconvex-b.svg")}


def every_move(moves, frames):
    """Per move (seq, time, sent: its position was the one sent, not one the browser coalesced
    into a later pointer event): the time to the first frame of its seq or a newer one, or None
    when no frame came; and whether the move's own shape was drawn."""
    out = []
    for m in moves:
        later = [f for f in frames if f["seq"] >= m["seq"]]
        first = min(later, key=lambda f: f["time"]) if later else None
        out.append((first["time"] - m["time"] if first else None, m["sent"] and any(f["seq"] == m["seq"] for f in frames)))
    return out


def percentile(values, q):
    values = sorted(values)
    return values[min(len(values) - 1, int(round(q * (len(values) - 1))))]


def drag(s, args):
    """Drags B's handle along half its outline; returns the pointer actions, not yet performed."""
    from selenium.webdriver.common.action_chains import ActionChains
    from selenium.webdriver.common.by import By
    n = args.positions
    points = s.js(f"""
        var v = window.studio.views[1], out = [], h = v.handle.getBoundingClientRect(), m = v.svg.getScreenCTM();
        for (var k = 1; k <= {n}; ++k) {{
          var p = v.loop.at(v.fraction + 0.5 * k / {n}), q = v.svg.createSVGPoint();
          q.x = p[0]; q.y = -p[1]; q = q.matrixTransform(m);
          out.push([Math.round(q.x - (h.left + h.width / 2)), Math.round(q.y - (h.top + h.height / 2))]);
        }}
        return out;""")
    actions = ActionChains(s.driver, duration=0).click_and_hold(s.driver.find_element(By.CSS_SELECTOR, "#svg-b-marks circle.handle"))
    last = [0, 0]
    for x, y in points:
        actions.move_by_offset(x - last[0], y - last[1]).pause(args.pause)
        last = [x, y]
    return actions.release()


def cpu_seconds(server_pid):
    """CPU seconds (user + system) so far of each kind of process the drag runs: Chromium's by its
    --type (the browser itself without one), the studio's server, chromedriver."""
    tick = os.sysconf("SC_CLK_TCK")
    out = {}
    for stat in glob.glob("/proc/[0-9]*/stat"):
        try:
            text = open(stat).read()
            command = open(stat[:-4] + "cmdline").read()
        except OSError:
            continue
        name = text[text.index("(") + 1:text.rindex(")")]
        fields = text[text.rindex(")") + 2:].split()
        if int(stat.split("/")[2]) == server_pid:
            kind = "server"
        elif name == "chromium":
            kind = re.search(r"--type=([a-z-]+)", command)
            kind = "Chromium " + (kind.group(1) if kind else "browser")
        elif name == "chromedriver":
            kind = "chromedriver"
        else:
            continue
        out[kind] = out.get(kind, 0.0) + (int(fields[11]) + int(fields[12])) / tick
    return out


def answer_instantly(s):
    """Replaces the page's fetch of /api/solve: the next answer is kept, and every later request is
    answered with it at once (its seq the request's, nothing left to refine)."""
    s.js("""
      var fetchFromServer = window.fetch, kept = null;
      window.fetch = function (path, options) {
        if (path !== "/api/solve") return fetchFromServer.apply(this, arguments);
        var seq = JSON.parse(options.body).seq;
        if (kept) {
          var answer = Object.assign({}, kept.answer, { seq: seq, refining: false });
          return Promise.resolve({ ok: true, status: 200, json: function () { return Promise.resolve(answer); },
                                   headers: { get: function (h) { return h === "Server-Timing" ? kept.timing : null; } } });
        }
        return fetchFromServer.apply(this, arguments).then(function (res) {
          return res.clone().json().then(function (answer) {
            kept = { answer: answer, timing: res.headers.get("Server-Timing") };
            return res;
          });
        });
      };""")
    s.js("window.studio.setStart(1, window.studio.views[1].fraction)")
    s.settle()
    if not s.js("return window.studio.shown && window.studio.shown.result.seq > 0"):
        raise RuntimeError("no answer to keep")


def run(args, pair, gpu):
    forward = os.path.join(args.samples, "forward")
    s = studio_browser.Studio(args.dform, [os.path.join(forward, name) for name in PAIRS[pair]], gpu=gpu)
    flag = "GPU process (SwiftShader)" if gpu else "--disable-gpu"
    try:
        s.settle()
        # The page's first strip of alternative starts is solved in the background: wait for it,
        # so that the drag is measured, not the drag competing with 32 other solves.
        s.wait(lambda: s.js("return document.getElementById('strip-cards').getAttribute('data-state')") == "done", 600)
        if args.instant:
            answer_instantly(s)
        s.js("window.studio.moves = []; window.studio.frames = []; window.studio.breakdown = []")
        actions = drag(s, args)
        if args.paper:
            # Timed in the page's clock, from the pointerup to the frames that drew the last position
            # (studio.frames): polling from here would also count the page's work after the frame.
            s.js("window.releasedAt = null; document.addEventListener('pointerup',"
                 " function (e) { if (window.releasedAt == null) window.releasedAt = e.timeStamp; }, true)")
            actions.perform()
            last = s.js("return window.studio.views[1].fraction")
            showing = "var s = window.studio; return s.frameSeq === s.shown.seq && Math.abs(s.shown.settings.start_b - %r) < 1e-12" % last
            s.wait(lambda: s.js(showing + " && !s.shown.result.preview && !s.shown.result.refining"), 300, "its refined shape")
            seq, released, frames, came, moves = s.js("var s = window.studio; return [s.shown.seq, window.releasedAt,"
                                                      " s.frames, s.shown.result.arrival.parsed, s.moves]")
            drawn = [f for f in frames if f["seq"] == seq]
            preview = max(0.0, (drawn[0]["time"] - released) / 1000)
            refined = next(f for f in drawn if not f["preview"])["time"]
            latencies = [t for t, _ in every_move(moves, frames) if t is not None]
            print(f"{flag}: released after {args.positions} moves x {args.pause} s: the last position's first shape after "
                  f"{preview:.2f} s, refined after {(refined - released) / 1000:.2f} s (its frame "
                  f"{refined - came:.0f} ms after it came); every move's first shape: median "
                  f"{statistics.median(latencies):.0f} ms, p95 {percentile(latencies, 0.95):.0f} ms, max "
                  f"{max(latencies):.0f} ms, {sum(1 for t in latencies if t <= 150)} of {len(moves)} within 150 ms")
            return
        before, began = cpu_seconds(s.process.pid), time.time()
        actions.perform()
        s.settle()
        after, wall = cpu_seconds(s.process.pid), time.time() - began
        moves, frames = s.js("return window.studio.moves"), s.js("return window.studio.frames")
        breakdown = s.js("return window.studio.breakdown")
        errors = s.console_errors()
    finally:
        s.close()
    counted = every_move(moves, frames)
    latencies = [t for t, _ in counted if t is not None]
    own = sum(1 for _, mine in counted if mine)
    if not latencies:
        print(f"{pair}, {flag}: no frame for any of {len(moves)} moves")
        return
    times = sorted(m["time"] for m in moves)
    apart = statistics.median(b - a for a, b in zip(times, times[1:])) if len(times) > 1 else float("nan")
    if args.instant:
        flag += ", every answer at once in the page (--instant)"
    print(f"{pair}, {flag}: {len(moves)} moves at {1 / args.pause:.0f} Hz (as the page got them: {apart:.1f} ms apart, "
          f"median), {own} with a frame of their own, "
          f"{len(moves) - len(latencies)} without any frame; latency of every move median {statistics.median(latencies):.1f} ms, "
          f"p95 {percentile(latencies, 0.95):.1f} ms, min {min(latencies):.1f} ms, max {max(latencies):.1f} ms; "
          f"console errors {len(errors)}")
    used = sorted(((after[k] - before.get(k, 0.0), k) for k in after), reverse=True)
    print(f"  CPU during the drag ({wall:.2f} s, 2 cores = {2 * wall:.2f} s): " +
          ", ".join(f"{k} {seconds:.2f} s" for seconds, k in used if seconds >= 0.01))
    # The median of each part of a drawn shape's frame (ms): queued behind the solve in flight, the
    # request's round trip (the server's time in it, the solve's in that), the answer's body and
    # parsing, showing it, and the wait for the frame.
    parts = [key for key in (breakdown[0] if breakdown else {}) if all(b.get(key) is not None for b in breakdown)]
    if args.instant:  # the server's parts are the kept answer's
        parts = [key for key in parts if key not in ("answer", "made", "server", "server_handle", "solve")]
    print("  breakdown of the drawn shapes (medians, ms): " +
          ", ".join(f"{key} {statistics.median(b[key] for b in breakdown):.1f}" for key in parts))


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("dform")
    parser.add_argument("samples")
    parser.add_argument("--pause", type=float, default=1 / 60)
    parser.add_argument("--positions", type=int, default=100)
    parser.add_argument("--pair", choices=("ellipses", "circle-square"), default="ellipses")
    parser.add_argument("--gpu", choices=("both", "off", "on"), default="both",
                        help="off: --disable-gpu; on: Chromium's GPU process; both: one run each")
    parser.add_argument("--paper", action="store_true")
    parser.add_argument("--instant", action="store_true",
                        help="answer every position in the page with the first answer: the page's own part")
    args = parser.parse_args()
    missing = studio_browser.chromium_missing()
    if missing:
        print("cannot run: " + missing)
        return 1
    print(f"load average {open('/proc/loadavg').read().split()[0:3]}", flush=True)
    for gpu in {"both": (False, True), "off": (False,), "on": (True,)}[args.gpu]:
        run(args, "paper" if args.paper else args.pair, gpu)
    return 0


if __name__ == "__main__":
    sys.exit(main())
