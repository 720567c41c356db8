#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""The CLI's tables of docs/benchmarks.md: runs `dform` as a user does and prints each table in
Markdown, figures from the runs' report.json, times as stated in each table's heading.

    cli_tables.py BUILD/dform SAMPLES_DIR [--repeats 3]
                  [--only exact,samples,inverse,sweep,general,ruled,isometric,export]

Every run writes into a temporary folder that is removed at the end. A table's times are the
median of --repeats runs where its heading says so, else one run's.
"""
import argparse
import json
import os
import re
import statistics
import subprocess
import sys
import tempfile
import time


class Runner:
    def __init__(self, dform, samples, work):
        self.dform, self.samples, self.work, self.count = dform, samples, work, 0

    def sample(self, *parts):
        return os.path.join(self.samples, *parts)

    def run(self, args):
        """Runs dform ARGS -q -o FOLDER: (report or None, exit code, wall s, peak RSS MB)."""
        self.count += 1
        out = os.path.join(self.work, f"run{self.count}")
        report, code, wall, rss = self.timed([*args, "-q", "-o", out])
        report_path = os.path.join(out, "report.json")
        report = json.load(open(report_path)) if os.path.exists(report_path) else None
        return report, code, wall, rss

    def timed(self, args):
        """Runs dform ARGS as it is: (None, exit code, wall s, peak RSS MB)."""
        begun = time.perf_counter()
        process = subprocess.Popen([self.dform, *args], stdout=subprocess.DEVNULL,
                                   stderr=subprocess.DEVNULL)
        _, status, usage = os.wait4(process.pid, 0)
        wall = time.perf_counter() - begun
        return None, os.waitstatus_to_exitcode(status), wall, usage.ru_maxrss / 1024.0


def job_with_model(r, job, model):
    """A copy of samples/forward/JOB.json that runs MODEL, its outline paths made absolute."""
    source = r.sample("forward", job + ".json")
    settings = json.load(open(source))
    for key in ("piece_a", "piece_b"):
        settings[key] = os.path.join(os.path.dirname(source), settings[key])
    settings["model"] = model
    path = os.path.join(r.work, f"{job}-{model}.json")
    with open(path, "w") as f:
        json.dump(settings, f)
    return path


def ellipses(r):
    return [r.sample("forward", "ellipses-a.svg"), r.sample("forward", "ellipses-b.svg")]


def circle_square(r):
    return [r.sample("forward", "circle.svg"), r.sample("forward", "square.svg")]


def vertices(report):
    mesh = report["mesh"]
    return mesh["vertices_a"] + mesh["vertices_b"]


def general_figures(report):
    """(Newton steps, stationarity) from the general model's message, or blanks."""
    for message in report["messages"]:
        found = re.search(r"general model: (\d+) Newton steps, stationarity ([0-9.e+-]+)",
                          message["text"])
        if found:
            return found.group(1), found.group(2)
    return "", ""


def percent(value):
    return f"{100 * value:.4g}"


def row(*cells):
    print("| " + " | ".join(str(c) for c in cells) + " |")


def exact_tables(r, repeats):
    print("\n### exact: solve time (report.json timings.solve, median of %d)\n" % (repeats * 2))
    row("N", "solve s, median", "min")
    row(*["---"] * 3)
    for n in (100, 200):
        times = [r.run(["forward", *ellipses(r), "--resolution", str(n), "--model", "exact",
                        "--no-export", "--gate", "none"])[0]["timings"]["solve"]
                 for _ in range(repeats * 2)]
        row(n, f"{statistics.median(times):.3f}", f"{min(times):.3f}")
    print("\n### exact: figures under the strict gate (one run each)\n")
    row("case", "N", "L_max", "angle_defect_max_rad", "exact_distance_max_rel", "run s", "gate")
    row(*["---"] * 7)
    cases = [("ellipses", ["forward", *ellipses(r)], n)
             for n in (50, 100, 200, 400, 450, 500, 800, 1000)]
    cases.append(("circle + square", ["forward", *circle_square(r)], 100))
    for name, args, n in cases:
        report, code, _, _ = r.run([*args, "--resolution", str(n), "--model", "exact",
                                    "--gate", "strict", "--no-export"])
        m = report["metrics"]
        row(name, n, f"{m['L_max']:.2g}", f"{m['angle_defect_max_rad']:.2g}",
            f"{m['exact_distance_max_rel']:.2g}", f"{report['timings']['run']:.3f}",
            "passes strict" if report["gate"]["passed"] else f"fails (exit {code})")
    for curve in ("three-lobed.obj", "tennis-ball.obj", "saddle.obj"):
        report, code, _, _ = r.run(["inverse", r.sample("inverse", curve), "--gate", "strict",
                                    "--no-export"])
        m = report["metrics"]
        row(curve + " (inverse)", report["mesh"]["seam_vertices"], f"{m['L_max']:.2g}",
            f"{m['angle_defect_max_rad']:.2g}", f"{m.get('roundtrip_max_rel', float('nan')):.2g} (round trip)",
            f"{report['timings']['run']:.3f}",
            "passes strict" if report["gate"]["passed"] else f"fails (exit {code})")


def samples_table(r, repeats):
    print("\n### shipped forward samples, paper model (solve s: median of %d)\n" % repeats)
    row("sample", "vertices", "relaxation steps", "LM iters", "factorisations", "L_error %",
        "L_max %", "cost", "flipped 3D", "solve s")
    row(*["---"] * 10)
    for job in ("ellipse-twin", "ellipses-quarter-turn", "circle-square-mid-side",
                "nonconvex-shifted", "squaricle", "demi", "anti"):
        runs = [r.run(["run", job_with_model(r, job, "paper"), "--no-export"])
                for _ in range(repeats)]
        report = runs[0][0]
        if report is None:
            row(job, *[""] * 8, f"exit {runs[0][1]}")
            continue
        s, m = report["solver"], report["metrics"]
        row(job, vertices(report), s["local_global"]["iterations"], len(s.get("iterations", [])),
            s["factorisations"], percent(m["L_error"]), percent(m["L_max"]),
            f"{s['final_cost']:.5f}", m["flipped_3d"],
            f"{statistics.median(run[0]['timings']['solve'] for run in runs):.2f}")


def inverse_table(r, repeats):
    print("\n### inverse samples as a fresh CLI process (gate, export, report; median of %d)\n"
          % repeats)
    row("curve", "model", "seam n", "vertices", "L_max %", "round trip RMS", "CLI wall s",
        "peak RSS MB", "exit")
    row(*["---"] * 9)
    for curve in ("tennis-ball.obj", "saddle.obj", "three-lobed.obj", "pushed-in.obj",
                  "rotated.json"):
        runs = [r.run(["inverse", r.sample("inverse", curve)]) for _ in range(repeats)]
        report, code = runs[0][0], runs[0][1]
        m = report["metrics"]
        row(curve, report["model"]["name"], report["mesh"]["seam_vertices"], vertices(report),
            percent(m["L_max"]), f"{m.get('roundtrip_rms_rel', float('nan')):.2g}",
            f"{statistics.median(run[2] for run in runs):.2f}",
            f"{statistics.median(run[3] for run in runs):.0f}", code)


def sweep_table(r, repeats):
    print("\n### sweep of 64 starts (ellipses, exact, every start exported; median of %d)\n"
          % repeats)
    walls = [r.run(["sweep", *ellipses(r), "--starts", "64"])[2] for _ in range(repeats)]
    print(f"wall s: {', '.join(f'{w:.2f}' for w in walls)}; median {statistics.median(walls):.2f}")


def general_tables(r):
    print("\n### general engine (one run each; default gate)\n")
    row("case", "n", "model", "vertices", "L_error %", "L_max %", "exact distance RMS (max)",
        "stationarity", "Newton steps", "gate", "solve s")
    row(*["---"] * 11)
    cases = [("ellipses", ["forward", *ellipses(r)], n, model)
             for n, model in ((40, "paper"), (40, "general"), (100, "exact"), (100, "paper"),
                              (100, "general"), (200, "general"))]
    cases += [("circle + square", ["forward", *circle_square(r)], 100, model)
              for model in ("exact", "general")]
    cases += [("non-convex", ["forward", r.sample("forward", "nonconvex-a.svg"),
                              r.sample("forward", "nonconvex-b.svg")], n, "general")
              for n in (100, 200)]
    cases += [(job + " (sample)", ["run", job_with_model(r, job, "general")], None, None)
              for job in ("ellipse-twin", "ellipses-quarter-turn", "circle-square-mid-side",
                          "nonconvex-shifted", "squaricle", "demi", "anti")]
    for name, args, n, model in cases:
        extra = ["--resolution", str(n), "--model", model] if n else []
        report, code, _, _ = r.run([*args, *extra, "--no-export"])
        model = report["model"]["name"] if report else model
        if report is None:
            row(name, n or "", model or "", "", "", "", "", "", "", f"exit {code}", "")
            continue
        m = report["metrics"]
        steps, stationarity = general_figures(report)
        distance = (f"{m['exact_distance_rms_rel']:.2g} ({m['exact_distance_max_rel']:.2g})"
                    if m.get("exact_note", "") == "" and "exact_distance_rms_rel" in m
                    else "(" + (m.get("exact_note") or "none") + ")")
        row(name, n or report["mesh"]["seam_vertices"], model, vertices(report),
            percent(m["L_error"]), percent(m["L_max"]), distance, stationarity, steps,
            "passed" if report["gate"]["passed"] else "failed", f"{report['timings']['solve']:.2f}")


def ruled_table(r, repeats):
    print(f"\n### ruled engine (resolution 100; times the median of {repeats} runs)\n")
    row("case", "L_max", "bending energy", "flips", "states", "exact distance max", "gate",
        "run s", "peak MB")
    row(*["---"] * 9)
    cases = [("ellipses", ["forward", *ellipses(r), "--resolution", "100", "--model", "ruled"]),
             ("circle + square",
              ["forward", *circle_square(r), "--resolution", "100", "--model", "ruled"])]
    cases += [(job + " (sample)", ["run", job_with_model(r, job, "ruled")])
              for job in ("ellipse-twin", "circle-square-mid-side", "squaricle", "anti",
                          "nonconvex-shifted", "demi")]
    for name, args in cases:
        runs = [r.run([*args, "--no-export"]) for _ in range(repeats)]
        report, code = runs[0][0], runs[0][1]
        wall = statistics.median(run[2] for run in runs)
        rss = statistics.median(run[3] for run in runs)
        if report is None:
            row(name, "", "", "", "", "", f"exit {code}", f"{wall:.2f}", f"{rss:.0f}")
            continue
        model, m = report["model"], report["metrics"]
        distance = (f"{m['exact_distance_max_rel']:.2g}" if not m.get("exact_note")
                    and m.get("exact_distance_max_rel") is not None else "n/a")
        row(name, f"{m['L_max']:.2g}", f"{model.get('bending_energy', 0):.4g}",
            model.get("flips", ""), len(model.get("states", [])), distance,
            "passed" if report["gate"]["passed"] else "failed", f"{wall:.2f}", f"{rss:.0f}")


def isometric_table(r, repeats):
    """The states with vertices inside the pieces (auto) against resolution: the non-convex and
    demi samples at n = 100, 200, 400 and the non-convex at 150, a resolution that is not a
    doubling of 100 (times the median of REPEATS runs), and the non-convex at 800 and 1000 (one
    run each)."""
    print(f"\n### states with vertices inside the pieces (auto; times the median of {repeats} "
          "runs, n = 800 and 1000 one run)\n")
    row("case", "n", "L_max", "states: ranking energy", "answer's bending energy", "gate", "run s",
        "solve s", "peak MB")
    row(*["---"] * 9)
    nonconvex = [r.sample("forward", "nonconvex-a.svg"), r.sample("forward", "nonconvex-b.svg"),
                 "--start-b", "0.3"]
    demi = [r.sample("forward", "demi-disc.svg"), r.sample("forward", "demi-ring.svg"),
            "--join", "outer,inner", "--start-a", "0.003", "--start-b", "0.003"]
    cases = [("non-convex", nonconvex, n, repeats) for n in (100, 150, 200, 400)]
    cases += [("non-convex", nonconvex, n, 1) for n in (800, 1000)]
    cases += [("demi", demi, n, repeats) for n in (100, 200, 400)]
    for name, pair, n, times in cases:
        runs = [r.run(["forward", *pair, "--resolution", str(n), "--no-export"])
                for _ in range(times)]
        report, code = runs[0][0], runs[0][1]
        wall = statistics.median(run[2] for run in runs)
        rss = statistics.median(run[3] for run in runs)
        if report is None:
            row(name, n, "", "", "", f"exit {code}", f"{wall:.2f}", "", f"{rss:.0f}")
            continue
        model, m = report["model"], report["metrics"]
        solve = statistics.median(run[0]["timings"]["solve"] for run in runs if run[0])
        ranking = ", ".join(f"{s['ranking_energy']:.4g}" for s in model.get("states", []))
        row(name, n, f"{m['L_max']:.2g}", ranking, f"{model.get('bending_energy', 0):.4g}",
            "passed" if report["gate"]["passed"] else "failed", f"{wall:.2f}", f"{solve:.2f}",
            f"{rss:.0f}")


def saved_export_table(r, repeats):
    """`dform export DIR -o OUT` of a saved ellipses result at resolution 1000 (laser profile):
    its gate reused from report.json (the meshes unchanged), and measured again (--regate)."""
    solved = os.path.join(r.work, "ellipses-1000")
    subprocess.run([r.dform, "forward", *ellipses(r), "--resolution", "1000", "--no-export", "-q",
                    "-o", solved], check=True)
    print(f"\n`dform export` of a saved ellipses result, n = 1000, median of {repeats}\n")
    row("gate", "wall s, median", "min", "max", "peak RSS MB")
    row(*["---"] * 5)
    cases = (("reused from report.json, -o OUT", ["export", solved]),
             ("measured again (--regate), -o OUT", ["export", solved, "--regate"]),
             ("reused, into DIR (report.html redrawn)", ["export", solved]))
    for label, args in cases:
        walls, rss = [], []
        for _ in range(repeats):
            if "DIR" in label:
                _, code, wall, peak = r.timed([*args, "-q"])
            else:
                _, code, wall, peak = r.run(args)
            if code != 0:
                raise SystemExit(f"dform {' '.join(args)} exited {code}")
            walls.append(wall)
            rss.append(peak)
        row(label, f"{statistics.median(walls):.2f}", f"{min(walls):.2f}", f"{max(walls):.2f}",
            f"{statistics.median(rss):.0f}")


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("dform")
    parser.add_argument("samples")
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--only",
                        default="exact,samples,inverse,sweep,general,ruled,isometric,export")
    args = parser.parse_args()
    tables = {"exact": lambda r: exact_tables(r, args.repeats),
              "samples": lambda r: samples_table(r, args.repeats),
              "inverse": lambda r: inverse_table(r, args.repeats),
              "sweep": lambda r: sweep_table(r, args.repeats),
              "general": general_tables,
              "ruled": lambda r: ruled_table(r, args.repeats),
              "isometric": lambda r: isometric_table(r, args.repeats),
              "export": lambda r: saved_export_table(r, args.repeats)}
    with tempfile.TemporaryDirectory() as work:
        runner = Runner(os.path.abspath(args.dform), os.path.abspath(args.samples), work)
        for name in args.only.split(","):
            print(f"\nload average before {name}: {os.getloadavg()[0]:.1f}")
            tables[name](runner)
            sys.stdout.flush()
    return 0


if __name__ == "__main__":
    sys.exit(main())
