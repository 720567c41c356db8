#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Makes every referee sheet of tests/referee/README.md and the files under tests/referee/data/.

    tests/referee/run_all.py [--dform build/dform] [--work out/referee] [--only JOB ...]
                             [--levels 0 1] [--data tests/referee/data]

Run from the repository root after building dform. For each job it makes the start results with
`dform forward` (paper and general models; the exact one for convex pairs), then one referee
sheet (referee.py solve) per start, mirror and level (0: dform's mesh, about 1k vertices, from
dform's result; 1: the converged level-0 sheet with every triangle split into four, about 4k,
finished with the last two stages). A run whose summary.json exists is not run again (delete the
folder to redo it). Then it writes data/<job>-<start>-<level>.json (the converged seam, the
commands, the figures) and data/results.json (the comparisons: against the exact seam, 1k against
4k, between the states a pair converged to).
"""
import argparse
import json
import os
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import referee  # noqa: E402

S = "samples/forward/"
COMMON = ["--no-export", "--quiet", "--gate", "none"]
ZIP = ["--start-a", "0.003", "--start-b", "0.003"]
# name: (dform forward arguments, interior edge for about 1k vertices, convex, starts)
JOBS = {
    "ellipses": ([S + "ellipses-a.svg", S + "ellipses-b.svg"], "1.3", True, ["paper", "exact"]),
    "circle-square": ([S + "circle.svg", S + "square.svg"], "1.3", True, ["paper", "exact"]),
    "nonconvex-shifted": ([S + "nonconvex-a.svg", S + "nonconvex-b.svg", "--start-b", "0.3"],
                          "1.3", False, ["paper", "general"]),
    "nonconvex": ([S + "nonconvex-a.svg", S + "nonconvex-b.svg"], "1.3", False,
                  ["paper", "general"]),
    "anti": ([S + "anti-a.svg", S + "anti-b.svg", "--join", "inner,inner"] + ZIP, "2.6", False,
             ["paper", "general", "paper-mirror", "general-mirror", "paper-r50", "general-r50",
              "paper-r50-stiff"]),
    "demi": ([S + "demi-disc.svg", S + "demi-ring.svg", "--join", "outer,inner"] + ZIP, "2.0",
             False, ["paper-r50", "general-r50", "paper-r50-mirror", "general-r50-mirror",
                     "paper-r50-stiff"]),
}
LEVEL_NAME = {0: "1k", 1: "4k"}


def run(cmd):
    print("+", " ".join(cmd), flush=True)
    subprocess.run(cmd, check=True)


def make_input(args, job, start):
    """dform's result for the job and start (its model; `-r50`: resolution 50 with dform's own
    interior edge, about 1.6k vertices, instead of resolution 100 with a coarser interior);
    returns (folder, command)."""
    files, ie, _, _ = JOBS[job]
    model = start.split("-")[0]
    name = model + ("-r50" if "-r50" in start else "")
    folder = os.path.join(args.work, "inputs", f"{job}-{name}")
    mesh = ["--resolution", "50"] if "-r50" in start else ["--resolution", "100",
                                                           "--interior-edge", ie]
    cmd = [args.dform, "forward"] + files + ["--model", model] + mesh + COMMON + ["-o", folder]
    if not os.path.exists(os.path.join(folder, "report.json")) and not args.collect:
        run(cmd)
    return folder, " ".join(cmd)


def run_folder(args, job, start, level):
    return os.path.join(args.work, "runs", f"{job}-{start}-{LEVEL_NAME[level]}")


def solve(args, job, start, level, source):
    """Level 0 starts from dform's result (mirrored for a -mirror start) with the default
    schedule (a -stiff start: the last two stages only); level 1 from the level-0 sheet split
    into four, with the last two stages."""
    folder = run_folder(args, job, start, level)
    cmd = [sys.executable, "tests/referee/referee.py", "solve", source, "-o", folder,
           "--dform", args.dform]
    if level == 0 and start.endswith("-mirror"):
        cmd.append("--mirror")
    if level == 0 and "-stiff" in start:  # stiff from the first step: does the start's state hold?
        cmd += ["--schedule", "finish"]
    if level == 1:
        cmd[3] = run_folder(args, job, start, 0)
        cmd += ["--subdivide", "1", "--schedule", "finish"]
    if not os.path.exists(os.path.join(folder, "summary.json")):
        if args.collect:
            return None, None
        run(cmd)
    with open(os.path.join(folder, "summary.json"), encoding="utf-8") as f:
        summary = json.load(f)
    with open(os.path.join(folder, "seam.json"), encoding="utf-8") as f:
        points = json.load(f)["points"]
    return summary, points


def record(args, job, start, level, input_cmd, summary, points):
    """data/<job>-<start>-<level>.json: the seam and how it was made; the bending figures are
    measured again on the run's OBJs (sheet.bending, today's definition)."""
    folder = run_folder(args, job, start, level)
    solved = referee.sh.Sheet(referee.sh.read_piece(folder, "a"), referee.sh.read_piece(folder, "b"))
    summary = dict(summary, bending=referee.sh.bending(solved, solved.x))
    keep = ["vertices", "faces", "seam_points", "start_L_max", "L_max", "L_rms", "bending",
            "evolver_energy", "final_kbend", "hessian_eigencounts_about_0_and_minus_1e-9",
            "seconds", "cpu_seconds", "loadavg_at_start", "evolver"]
    data = {"job": job, "start": start, "level": LEVEL_NAME[level],
            "dform_command": input_cmd,
            "referee_command": summary["command"].replace(os.path.abspath(".") + "/", ""),
            "units": "mm", "seam_order": "piece A's seam from its first vertex",
            **{k: summary[k] for k in keep},
            "dform_validate": summary.get("dform_validate", {}).get("checks"),
            "points": [[round(c, 9) for c in p] for p in points]}
    path = os.path.join(args.data, f"{job}-{start}-{LEVEL_NAME[level]}.json")
    with open(path, "w", encoding="utf-8") as f:
        json.dump(data, f, indent=1)
        f.write("\n")


def distances(p, q):
    rms, worst = referee.seam_distance(p, q)
    rms_m, worst_m = referee.seam_distance(p, q, allow_mirror=True)
    return {"rms": rms, "max": worst, "rms_mirror_allowed": rms_m, "max_mirror_allowed": worst_m}


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--dform", default="build/dform")
    parser.add_argument("--work", default="out/referee")
    parser.add_argument("--data", default="tests/referee/data")
    parser.add_argument("--only", nargs="*", default=list(JOBS))
    parser.add_argument("--levels", nargs="*", type=int, default=[0, 1])
    parser.add_argument("--starts", nargs="*", help="only these starts (paper, general-mirror...)")
    parser.add_argument("--collect", action="store_true",
                        help="run nothing: write data/ from the runs that have finished")
    args = parser.parse_args()
    os.makedirs(args.data, exist_ok=True)
    results_path = os.path.join(args.data, "results.json")
    for job in args.only:
        _, _, convex, starts = JOBS[job]
        if args.starts:
            starts = [s for s in starts if s in args.starts]
        seams, out = {}, {}
        for start in starts:
            source, input_cmd = make_input(args, job, start)
            for level in args.levels:
                summary, points = solve(args, job, start, level, source)
                if summary is None:
                    continue
                record(args, job, start, level, input_cmd, summary, points)
                seams[(start, level)] = points
        if convex and seams:
            folder, _ = make_input(args, job, "exact")
            exact = referee.sh.read_piece(folder, "a")
            exact_seam = [list(exact.shape[i]) for i in exact.seam]
            for (start, level), points in seams.items():
                out[f"vs_exact_{start}_{LEVEL_NAME[level]}"] = distances(exact_seam, points)
        for name in ("paper", "general", "paper-r50", "general-r50", "paper-default"):
            # dform's results of the job against each sheet (-default: resolution 100 with
            # dform's own interior edge, the CLI's result; made by hand where it is listed)
            folder = os.path.join(args.work, "inputs", f"{job}-{name}")
            if not os.path.exists(os.path.join(folder, "report.json")):
                continue
            piece = referee.sh.read_piece(folder, "a")
            dform_seam = [list(piece.shape[i]) for i in piece.seam]
            for (start, level), points in seams.items():
                out[f"dform_{name}_vs_sheet_{start}_{LEVEL_NAME[level]}"] = distances(
                    points, dform_seam)
        for start in starts:
            if (start, 0) in seams and (start, 1) in seams:
                out[f"1k_vs_4k_{start}"] = distances(seams[(start, 1)], seams[(start, 0)])
        for level in args.levels:
            done = [s for s in starts if (s, level) in seams]
            for i, s in enumerate(done):
                for t in done[i + 1:]:
                    out[f"{s}_vs_{t}_{LEVEL_NAME[level]}"] = distances(seams[(s, level)],
                                                                       seams[(t, level)])
        results = {}
        if os.path.exists(results_path):  # read again: another run may have written meanwhile
            with open(results_path, encoding="utf-8") as f:
                results = json.load(f)
        results.setdefault(job, {}).update(out)
        with open(results_path, "w", encoding="utf-8") as f:
            json.dump(results, f, indent=1, sort_keys=True)
            f.write("\n")


if __name__ == "__main__":
    main()
