#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Ctrl-C ends a run at resolution 1500 within a second, forward and inverse, wherever it lands.

Each run (the shipped ellipse pair with the paper model; the shipped saddle) writes into a folder
that holds an earlier result. SIGINT is sent when the run reaches the stage it is meant to land in,
as the run reports it on its terminal (stderr is a pseudo-terminal, so the progress line is
shown): at once when the finest level is meshed, in the set-up of its solve (the terms, their Gram
matrices, the relaxation's system and its analysis), and at the finest level's first iterations,
where the long factorisations are. Each stop must end the process with exit 130 and one
`interrupted` error line within STOP_BOUND of the signal, and leave the folder byte for byte as
it was, with nothing beside it.

    stop_latency_test.py BUILD/dform SAMPLES_DIR
"""
import os
import pty
import re
import signal
import subprocess
import sys
import tempfile
import threading
import time

# The bar: a person pressing Ctrl-C sees the prompt again within a second.
STOP_BOUND = 1.0
# The stages a stop is sent in, each by what the run prints when it gets there: the finest level's
# "meshed piece A" line (its solve's set-up follows), and the finest level's first progress line
# ("level 3/3: relaxing 1/40 steps": its iterations and their factorisations).
STAGES = (("set-up", re.compile(rb"meshed piece A with")),
          ("iterations", re.compile(rb"level (\d+)/\1: (relaxing|solving) ")))
# No run takes this long to reach a stage (about 30 s to the finest level on a loaded 2-core
# machine).
STAGE_LIMIT = 600.0
ANSI = re.compile(rb"\x1b\[[0-9;]*[A-Za-z]")


def folder_contents(folder):
    contents = {}
    for root, _, files in os.walk(folder):
        for name in files:
            path = os.path.join(root, name)
            with open(path, "rb") as f:
                contents[os.path.relpath(path, folder)] = f.read()
    return contents


def stop_once(command, out, stage):
    """Sends SIGINT once the run prints `stage`'s mark; the latency, exit code, stderr's text."""
    leader, follower = pty.openpty()
    process = subprocess.Popen(command + ["-o", out], stdout=subprocess.DEVNULL, stderr=follower)
    os.close(follower)
    seen = bytearray()

    def drain():  # the terminal must be read, or the run blocks on its progress line
        while True:
            try:
                chunk = os.read(leader, 4096)
            except OSError:
                return
            if not chunk:
                return
            seen.extend(chunk)

    reader = threading.Thread(target=drain)
    reader.start()
    started = time.monotonic()
    name, mark = stage
    while not mark.search(bytes(seen)):
        if process.poll() is not None or time.monotonic() - started > STAGE_LIMIT:
            process.kill()
            process.wait()
            reader.join()
            os.close(leader)
            raise AssertionError(f"{command}: never reached the {name} stage: {bytes(seen)[-300:]!r}")
        time.sleep(0.01)
    if process.poll() is not None:
        raise AssertionError(f"{command}: finished as it reached the {name} stage")
    sent = time.monotonic()
    process.send_signal(signal.SIGINT)
    code = process.wait()
    latency = time.monotonic() - sent
    reader.join()
    os.close(leader)
    text = ANSI.sub(b"", bytes(seen)).replace(b"\r", b"\n").decode(errors="replace")
    return latency, code, text


def main():
    dform, samples = sys.argv[1], sys.argv[2]
    forward = ["forward", os.path.join(samples, "forward", "ellipses-a.svg"),
               os.path.join(samples, "forward", "ellipses-b.svg"), "--model", "paper"]
    inverse = ["inverse", os.path.join(samples, "inverse", "saddle.obj")]
    failures = []
    with tempfile.TemporaryDirectory() as work:
        for name, args in (("forward", forward), ("inverse", inverse)):
            parent = os.path.join(work, name)
            os.mkdir(parent)
            out = os.path.join(parent, "out")
            # The earlier result an interrupted run must leave as it is.
            subprocess.run([dform] + args + ["--resolution", "30", "--no-export", "-q", "-o", out],
                           stdout=subprocess.DEVNULL, check=True)
            before = folder_contents(out)
            assert before, f"{name}: the earlier run wrote nothing"
            for stage in STAGES:
                latency, code, err = stop_once([dform] + args + ["--resolution", "1500", "--no-export"], out,
                                               stage)
                errors = [line for line in err.splitlines() if line.startswith("dform: error:")]
                where = f"{name}, {stage[0]}"
                print(f"{where}: exit {code} in {1000 * latency:.0f} ms: "
                      f"{errors[-1] if errors else err.strip()[-200:]}")
                if code != 130:
                    failures.append(f"{where}: exit {code}, not 130")
                if len(errors) != 1 or "interrupted" not in errors[0]:
                    failures.append(f"{where}: error lines {errors}, not one `interrupted` line")
                if not latency <= STOP_BOUND:
                    failures.append(f"{where}: stopped in {latency:.2f} s, more than {STOP_BOUND} s")
                if folder_contents(out) != before:
                    failures.append(f"{where}: the output folder changed")
                if sorted(os.listdir(parent)) != ["out"]:
                    failures.append(f"{where}: left beside the folder: {os.listdir(parent)}")
    print(f"load average {os.getloadavg()[0]:.1f} on {os.cpu_count()} cores")
    for failure in failures:
        print("FAILED:", failure)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
