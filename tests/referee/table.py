#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Prints the figures of tests/referee/data/ as the Markdown tables of tests/referee/README.md.

    tests/referee/table.py [--data tests/referee/data]
"""
import argparse
import glob
import json
import math
import os


def sheets_table(data):
    rows = ["| job | start | level | vertices | L_max (start → sheet) | bending: dihedral_hooke / "
            "hinge | seam folds (deg) | hinge folds (deg) | Hessian eigenvalues < 0 (< −1e-9) | "
            "time: wall / CPU s (load) |", "|" + "---|" * 10]
    for path in sorted(glob.glob(os.path.join(data, "*-*k.json"))):
        with open(path, encoding="utf-8") as f:
            d = json.load(f)
        b = d["bending"]
        deg = lambda v: "—" if v is None else f"{math.degrees(v):.0f}"  # noqa: E731
        counts = d["hessian_eigencounts_about_0_and_minus_1e-9"]
        neg = f"{counts[0][0]} ({counts[1][0]})" if len(counts) == 2 else "—"
        rows.append(
            f"| {d['job']} | {d['start']} | {d['level']} | {d['vertices']} | "
            f"{d['start_L_max']:.2e} → {d['L_max']:.2e} | {b['dihedral_hooke']:.4g} / "
            f"{b['hinge']:.4g} | {deg(b['seam_fold_min_rad'])} … {deg(b['seam_fold_max_rad'])} | "
            f"{deg(b['hinge_fold_min_rad'])} … {deg(b['hinge_fold_max_rad'])} | {neg} | "
            f"{d['seconds']:.0f} / {d['cpu_seconds']:.0f} ({d['loadavg_at_start'].split()[0]}) |")
    return "\n".join(rows)


def distances_table(data):
    with open(os.path.join(data, "results.json"), encoding="utf-8") as f:
        results = json.load(f)
    rows = ["| job | comparison | RMS / diagonal | max / diagonal | RMS, reflection allowed |",
            "|---|---|---|---|---|"]
    for job in sorted(results):
        for name in sorted(results[job]):
            r = results[job][name]
            rows.append(f"| {job} | {name} | {r['rms']:.2e} | {r['max']:.2e} | "
                        f"{r['rms_mirror_allowed']:.2e} |")
    return "\n".join(rows)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--data", default=os.path.join(os.path.dirname(__file__), "data"))
    args = parser.parse_args()
    print(sheets_table(args.data))
    print()
    print(distances_table(args.data))


if __name__ == "__main__":
    main()
