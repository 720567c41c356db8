# SPDX-License-Identifier: GPL-3.0-or-later
"""dform studio in headless Chromium, for the browser tests, the latency benchmark and the
screenshots of docs/studio.md: starts `dform studio --no-browser` on a free port, opens its page
with Debian's chromium-driver through python3-selenium, and stops both.

SKIP (77) is what a test exits with when Chromium, its driver or Selenium is genuinely absent.
"""
import base64
import io
import os
import re
import shutil
import signal
import subprocess
import sys
import tempfile
import time
import zipfile

SKIP = 77

failures = []


def check(condition, message):
    """One check of a browser test: printed, and remembered when it fails."""
    print(("ok   " if condition else "FAIL ") + message, flush=True)
    if not condition:
        failures.append(message)


def guarded(what, part, *args):
    """Runs one part of a test; an exception (a timeout: what it waited for never came, an element
    the page lacks) is that part's failure, and the next part runs."""
    try:
        part(*args)
    except Exception as e:  # noqa: BLE001
        check(False, f"{what}: {type(e).__name__}: {str(e).splitlines()[0] if str(e) else ''}")


def verdict():
    """The test's exit code after its checks: 1 when any failed."""
    print(f"{len(failures)} failure(s)")
    return 1 if failures else 0


def chromium_missing():
    """Why headless Chromium cannot run here, or None."""
    for tool in ("chromium", "chromedriver"):
        if not shutil.which(tool):
            return f"{tool} is not installed (apt-get install chromium chromium-driver)"
    try:
        import selenium  # noqa: F401
    except ImportError:
        return "python3-selenium is not installed"
    return None


def skipped():
    """True, with the reason printed, when headless Chromium cannot run here."""
    missing = chromium_missing()
    if missing:
        print("SKIP: " + missing)
    return missing is not None


class Studio:
    """`dform studio ARGS --no-browser --port 0` and a Chromium window on its page."""

    def __init__(self, dform, args, width=1500, height=950, gpu=False):
        """gpu: run Chromium's GPU process (WebGL on SwiftShader there) instead of --disable-gpu."""
        from selenium import webdriver
        from selenium.webdriver.chrome.service import Service
        self.dform = dform
        self.process = subprocess.Popen([dform, "studio", *args, "--no-browser"], stdout=subprocess.PIPE,
                                        stderr=subprocess.PIPE, text=True)
        line = self.process.stdout.readline()
        match = re.search(r"(http://127\.0\.0\.1:(\d+)/\?token=([0-9a-f]+))", line)
        if not match:
            self.process.kill()
            raise RuntimeError("dform studio printed no address: " + line + self.process.stderr.read())
        self.url, self.port, self.token = match.group(1), int(match.group(2)), match.group(3)
        self.profile = tempfile.mkdtemp(prefix="dform-studio-chromium-")
        options = webdriver.ChromeOptions()
        options.binary_location = shutil.which("chromium")
        for flag in ("--headless=new", "--no-sandbox", *(() if gpu else ("--disable-gpu",)), "--use-angle=swiftshader",
                     "--enable-unsafe-swiftshader", "--disable-quic", "--no-first-run",
                     "--disable-background-networking", "--disable-component-update", "--disable-sync",
                     f"--window-size={width},{height}", f"--user-data-dir={self.profile}"):
            options.add_argument(flag)
        options.set_capability("goog:loggingPrefs", {"browser": "ALL"})
        self.driver = webdriver.Chrome(service=Service(shutil.which("chromedriver")), options=options)
        self.driver.set_script_timeout(120)
        self.driver.get(self.url)
        self.wait(lambda: self.js("return window.studio && window.studio.frameSeq || 0") >= 1, 60)

    def js(self, script, *args):
        return self.driver.execute_script(script, *args)

    def wait(self, condition, timeout=60, what="the page"):
        end = time.time() + timeout
        while time.time() < end:
            if condition():
                return
            time.sleep(0.02)
        raise TimeoutError(f"timed out waiting for {what}")

    def settle(self, timeout=120):
        """Waits until the newest input's full (not preview) result is on screen."""
        self.wait(lambda: self.js(
            "var s = window.studio; return s.shown && s.frameSeq === s.shown.seq && !s.shown.result.refining"
            " && s.idle();"), timeout, "the newest shape")

    def console_errors(self):
        """The console's errors since the last call (reading the log empties it)."""
        return [e for e in self.driver.get_log("browser") if e["level"] == "SEVERE"]

    def download(self):
        """The last download (Save job, Export) as bytes."""
        data = self.driver.execute_async_script(
            "var done = arguments[0], r = new FileReader();"
            "r.onload = function () { done(r.result.split(',')[1]); };"
            "r.readAsDataURL(window.studio.lastDownload);")
        return base64.b64decode(data)

    def close(self):
        try:
            self.driver.quit()
        finally:
            self.process.send_signal(signal.SIGTERM)
            try:
                self.process.wait(20)
            except subprocess.TimeoutExpired:
                self.process.kill()
            shutil.rmtree(self.profile, ignore_errors=True)


def failing_job(samples, work):
    """A job file in `work` whose paper model (isometry weighted 0.001, three iterations) fails the
    default gate (L_error among its checks); its path."""
    import json
    job = os.path.join(work, "failing.json")
    with open(job, "w") as f:
        json.dump({"mode": "forward", "piece_a": os.path.join(samples, "forward", "ellipses-a.svg"),
                   "piece_b": os.path.join(samples, "forward", "ellipses-b.svg"),
                   "fit_perimeter": True, "model": "paper", "resolution": 40,
                   "weights": {"isometry": 0.001}, "solver": {"max_iterations": 3}}, f)
    return job


def unzip(data, folder):
    zipfile.ZipFile(io.BytesIO(data)).extractall(folder)
