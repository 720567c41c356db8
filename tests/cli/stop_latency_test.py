#!/usr/bin/env python3
"""Ctrl-C ends a run at resolution 1500 within a second, forward and inverse, wherever it lands.

Each run (the shipped ellipse pair with the paper model; the shipped saddle) writes into a folder
that holds an earlier result. SIGINT is sent a few moments after the finest level is meshed, so
that it lands in the set-up of the finest level's solve (the terms, their Gram matrices, the
relaxation's system and its analysis) or in its first iterations, where the long steps are. Each
stop must end the process with exit 130 and one `interrupted` error line within STOP_BOUND of the
signal, and leave the folder byte for byte as it was, with nothing beside it.

    stop_latency_test.py BUILD/dform SAMPLES_DIR
"""
import os
import signal
import subprocess
import sys
import tempfile
import time

# The bar: a person pressing Ctrl-C sees the prompt again within a second.
STOP_BOUND = 1.0
# Seconds from the finest level's "meshed piece A" line to the signal: at once (the terms), and
# well into the set-up of its solve (the relaxation's system, its analysis and factorisations).
OFFSETS = {"forward": (3.0, 30.0), "inverse": (12.0, 30.0)}
# No run takes this long to reach its finest level (about 30 s on a loaded 2-core machine).
MESHING_LIMIT = 600.0


def folder_contents(folder):
    contents = {}
    for root, _, files in os.walk(folder):
        for name in files:
            path = os.path.join(root, name)
            with open(path, "rb") as f:
                contents[os.path.relpath(path, folder)] = f.read()
    return contents


def stop_once(command, out, offset, log):
    """Sends SIGINT `offset` s after the finest level is meshed; the latency, exit code, stderr."""
    with open(log, "wb") as err:
        process = subprocess.Popen(command + ["-o", out], stdout=subprocess.DEVNULL, stderr=err)
    started = time.monotonic()
    while b"meshed piece A with" not in open(log, "rb").read():
        if process.poll() is not None or time.monotonic() - started > MESHING_LIMIT:
            process.kill()
            process.wait()
            raise AssertionError(f"{command}: no finest level meshed: {open(log, 'rb').read()!r}")
        time.sleep(0.05)
    time.sleep(offset)
    if process.poll() is not None:
        raise AssertionError(f"{command}: finished {offset} s after meshing, before the signal")
    sent = time.monotonic()
    process.send_signal(signal.SIGINT)
    code = process.wait()
    latency = time.monotonic() - sent
    return latency, code, open(log, "rb").read().decode(errors="replace")


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
            for offset in OFFSETS[name]:
                latency, code, err = stop_once([dform] + args + ["--resolution", "1500", "--no-export"], out,
                                               offset, os.path.join(work, "err.txt"))
                errors = [line for line in err.splitlines() if line.startswith("dform: error:")]
                print(f"{name} +{offset:.0f} s after meshing: exit {code} in {1000 * latency:.0f} ms: "
                      f"{errors[-1] if errors else err.strip()[-200:]}")
                if code != 130:
                    failures.append(f"{name} +{offset} s: exit {code}, not 130")
                if len(errors) != 1 or "interrupted" not in errors[0]:
                    failures.append(f"{name} +{offset} s: error lines {errors}, not one `interrupted` line")
                if not latency <= STOP_BOUND:
                    failures.append(f"{name} +{offset} s: stopped in {latency:.2f} s, more than {STOP_BOUND} s")
                if folder_contents(out) != before:
                    failures.append(f"{name} +{offset} s: the output folder changed")
                if sorted(os.listdir(parent)) != ["out"]:
                    failures.append(f"{name} +{offset} s: left beside the folder: {os.listdir(parent)}")
    print(f"load average {os.getloadavg()[0]:.1f} on {os.cpu_count()} cores")
    for failure in failures:
        print("FAILED:", failure)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
