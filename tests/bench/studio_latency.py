#!/usr/bin/env python3
"""dform studio's live-drag latency in a real browser (docs/benchmarks.md, "Studio"): headless
Chromium drags piece B's start handle of the shipped ellipse pair (resolution 100) through 100
positions along its outline, one real pointer move every PAUSE seconds, and the page records,
for every shape it shows, the time from the pointer event (event.timeStamp) to the animation
frame after the new shape was drawn (a shape that answers several moves counts from the newest
it answers). The drag starts once the page's first strip of alternative starts is done. Prints
the median, the 95th percentile and how many of the positions got a frame of their own.

    studio_latency.py BUILD/dform SAMPLES_DIR [--pause 0.15] [--positions 100]

With --paper: the non-convex sample pair (the paper model) dragged for positions x pause seconds;
prints how long after letting go the page showed the last position's preview and its refined
shape.
    studio_latency.py BUILD/dform SAMPLES_DIR --paper --positions 50 --pause 0.1
"""
import time
import argparse
import os
import statistics
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "studio"))
import studio_browser  # noqa: E402


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("dform")
    parser.add_argument("samples")
    parser.add_argument("--pause", type=float, default=0.15)
    parser.add_argument("--positions", type=int, default=100)
    parser.add_argument("--paper", action="store_true")
    args = parser.parse_args()
    missing = studio_browser.chromium_missing()
    if missing:
        print("cannot run: " + missing)
        return 1
    from selenium.webdriver.common.action_chains import ActionChains
    from selenium.webdriver.common.by import By
    forward = os.path.join(args.samples, "forward")
    pair = ("nonconvex-a.svg", "nonconvex-b.svg") if args.paper else ("ellipses-a.svg", "ellipses-b.svg")
    s = studio_browser.Studio(args.dform, [os.path.join(forward, name) for name in pair])
    try:
        s.settle()
        # The page's first strip of alternative starts is solved in the background: wait for it,
        # so that the drag is measured, not the drag competing with 32 other solves.
        s.wait(lambda: s.js("return document.getElementById('strip-cards').getAttribute('data-state')") == "done", 600)
        s.js("window.studio.latencies = []; window.studio.breakdown = []")
        n = args.positions
        points = s.js(f"""
            var v = window.studio.views[1], out = [], h = v.handle.getBoundingClientRect(), m = v.svg.getScreenCTM();
            for (var k = 1; k <= {n}; ++k) {{
              var p = v.loop.at(v.fraction + 0.5 * k / {n}), q = v.svg.createSVGPoint();
              q.x = p[0]; q.y = -p[1]; q = q.matrixTransform(m);
              out.push([Math.round(q.x - (h.left + h.width / 2)), Math.round(q.y - (h.top + h.height / 2))]);
            }}
            return out;""")
        actions = ActionChains(s.driver, duration=0).click_and_hold(s.driver.find_element(By.CSS_SELECTOR, "#svg-b circle.handle"))
        last = [0, 0]
        for x, y in points:
            actions.move_by_offset(x - last[0], y - last[1]).pause(args.pause)
            last = [x, y]
        actions.release()
        if args.paper:
            actions.perform()
            released = time.time()
            last = s.js("return window.studio.views[1].fraction")
            showing = "var s = window.studio; return s.frameSeq === s.shown.seq && Math.abs(s.shown.settings.start_b - %r) < 1e-12" % last
            s.wait(lambda: s.js(showing), 300, "the last position")
            preview = time.time() - released
            s.wait(lambda: s.js(showing + " && !s.shown.result.preview && !s.shown.result.refining"), 300, "its refined shape")
            print(f"released after {args.positions} moves x {args.pause} s: the last position's first shape after {preview:.2f} s, "
                  f"refined after {time.time() - released:.2f} s")
            return 0
        actions.perform()
        s.settle()
        latencies = s.js("return window.studio.latencies")
        breakdown = s.js("return window.studio.breakdown")
        errors = s.console_errors()
    finally:
        s.close()
    latencies.sort()
    p95 = latencies[min(len(latencies) - 1, int(round(0.95 * (len(latencies) - 1))))]
    print(f"frames {len(latencies)} of {args.positions} positions; latency median {statistics.median(latencies):.1f} ms, "
          f"p95 {p95:.1f} ms, min {latencies[0]:.1f} ms, max {latencies[-1]:.1f} ms; console errors {len(errors)}")
    # The median of each part of a frame (ms): queued behind the solve in flight, the request's
    # round trip (the server's time in it, the solve's in that), the answer's body and parsing,
    # showing it, and the wait for the frame.
    parts = [key for key in (breakdown[0] if breakdown else {}) if all(b.get(key) is not None for b in breakdown)]
    print("breakdown (medians, ms): " + ", ".join(f"{key} {statistics.median(b[key] for b in breakdown):.1f}" for key in parts))
    return 0


if __name__ == "__main__":
    sys.exit(main())
