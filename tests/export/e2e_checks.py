# SPDX-License-Identifier: GPL-3.0-or-later
"""What the end-to-end export tests (score_folds_test.py, hinge_test.py) share: failed checks
collected and printed, and build/dform run with its output captured."""
import subprocess

failures = []


def check(ok, what):
    if not ok:
        failures.append(what)
        print("FAIL:", what)


def runner(dform):
    def run(*args):
        return subprocess.run([dform, *args], capture_output=True, text=True)
    return run
