#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""How long a run takes to stop after Ctrl-C (docs/benchmarks.md, "Stopping a run"): starts a
forward run (the shipped ellipse pair, paper model) and an inverse run (the shipped saddle) at
resolution 1500, sends SIGINT after each delay, and measures the time from the signal to the
process's exit. Checks that each ends with exit 130 and one `interrupted` error line, and prints
the stage its message names, the latency of each delay, and the median and largest per run kind.

    stop_latency.py BUILD/dform SAMPLES_DIR [--delays 2,5,10,20,40,60,80] [--resolution 1500]
"""
import argparse
import os
import shutil
import signal
import statistics
import subprocess
import sys
import tempfile
import time


def runs(dform, samples, resolution):
    forward = [dform, "forward", os.path.join(samples, "forward", "ellipses-a.svg"),
               os.path.join(samples, "forward", "ellipses-b.svg"), "--model", "paper"]
    inverse = [dform, "inverse", os.path.join(samples, "inverse", "saddle.obj")]
    return {name: command + ["--resolution", str(resolution), "--no-export"]
            for name, command in (("forward", forward), ("inverse", inverse))}


def stop_after(command, delay, out):
    """The seconds from SIGINT to exit, the exit code and the last line of stderr."""
    shutil.rmtree(out, ignore_errors=True)
    with tempfile.TemporaryFile() as err:
        process = subprocess.Popen(command + ["-o", out], stdout=subprocess.DEVNULL, stderr=err)
        time.sleep(delay)
        if process.poll() is not None:
            return None, process.returncode, "finished before the signal"
        sent = time.monotonic()
        process.send_signal(signal.SIGINT)
        process.wait()
        latency = time.monotonic() - sent
        err.seek(0)
        lines = err.read().decode(errors="replace").strip().splitlines()
        return latency, process.returncode, lines[-1] if lines else ""


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("dform")
    parser.add_argument("samples")
    parser.add_argument("--delays", default="2,5,10,20,40,60,80")
    parser.add_argument("--resolution", type=int, default=1500)
    args = parser.parse_args()
    delays = [float(d) for d in args.delays.split(",")]
    load = os.getloadavg()[0]
    print(f"load average {load:.1f} on {os.cpu_count()} cores; resolution {args.resolution}")
    failed = False
    with tempfile.TemporaryDirectory() as work:
        for name, command in runs(args.dform, args.samples, args.resolution).items():
            latencies = []
            for delay in delays:
                latency, code, line = stop_after(command, delay, os.path.join(work, "out"))
                if latency is None:
                    print(f"{name:8} after {delay:5.1f} s: {line}")
                    continue
                stage = line.split("interrupted", 1)[-1].split(";")[0].strip() if "interrupted" in line else line
                ok = code == 130 and "interrupted" in line
                failed = failed or not ok
                latencies.append(latency)
                print(f"{name:8} after {delay:5.1f} s: stopped in {1000 * latency:7.0f} ms, exit {code}, {stage}")
            if latencies:
                print(f"{name:8} median {1000 * statistics.median(latencies):.0f} ms, "
                      f"largest {1000 * max(latencies):.0f} ms over {len(latencies)} stops")
    print(f"load average {os.getloadavg()[0]:.1f} at the end")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
