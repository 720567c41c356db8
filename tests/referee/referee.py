#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""The referee: a near-inextensible elastic sheet computed by Surface Evolver from a dform result.

    referee.py solve DIR -o OUT [--subdivide K] [--mirror] [--schedule NAME]
    referee.py compare SEAM1.json SEAM2.json [--mirror]
    referee.py bending DIR... --on REF

`solve` reads the four piece OBJs of dform result folder DIR (made by `dform forward ... --model
paper|general|exact`), glues the pieces into one sheet (sheet.py), optionally splits every
triangle into four K times, and writes OUT/sheet.fe: a linear-elastic stretching energy of each
triangle against its flat triangle plus a dihedral bending energy on the interior edges of each
piece (seam and free boundaries are free hinges). It runs Surface Evolver (`evolver`) on it with
the schedule's stages (stretching stiffness up, bending down; gradient steps, then Newton steps
until the energy stops falling), and writes OUT/piece-*.obj (dform's format, the solved 3D shape),
OUT/seam.json (the 3D seam points in seam order, mm) and OUT/summary.json (L_max, bending, energies,
the Hessian's negative eigenvalue count, time), then prints the summary.

`compare` prints the distance between two seams of the same sampling after the best rigid motion
(Kabsch; with --mirror the best motion or motion plus reflection), over the first one's bounding box
diagonal: RMS and max.

`bending` prints each result folder's hinge energy (sheet.bending) on its own mesh and on the
pieces' meshes of result folder REF, its surface resampled onto them (sheet.resample): results of
different models, meshed differently, compared on one mesh.
"""
import argparse
import json
import os
import platform
import re
import resource
import shutil
import subprocess
import sys
import time

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import sheet as sh  # noqa: E402

# A schedule: its stages (bending modulus, gradient steps, Newton step cap) and the eigenvalue
# below which a Newton step is followed by a saddle step. The stretching modulus is 1 (energy
# density (1/2/(1+v))(tr C^2 + v (tr C)^2/(1-v)) per mm^2 of sheet), the bending modulus in mm.
# "finish" (a converged sheet split into four) takes saddle steps only below -1e-9: the rigid
# motions' eigenvalues sit between that and 0 through rounding, and at 4k vertices each saddle
# step costs about ten Newton steps.
SCHEDULES = {
    "default": ([(1e1, 200, 40), (1.0, 200, 40), (1e-1, 200, 40), (1e-2, 200, 60),
                 (1e-3, 200, 80), (1e-4, 200, 100), (1e-5, 2000, 200)], 0.0),
    "quick": ([(1e1, 50, 20), (1e-1, 50, 20), (1e-3, 200, 60)], 0.0),
    "finish": ([(1e-4, 200, 100), (1e-5, 2000, 200)], -1e-9),
}
POISSON = 0.3
NEWTON_TOL = 1e-13  # relative energy drop below which a Newton loop ends


def command_file(schedule, saddle_below):
    """Evolver commands: each stage sets the bending modulus, takes gradient steps, then Newton
    (hessian_seek) steps, each followed by a saddle step (a line search along the lowest
    eigenvector) while the Hessian has an eigenvalue below saddle_below, until the energy falls by
    less than NEWTON_TOL relative or the cap; at the end the energies, the Hessian's eigenvalue
    counts about 0 and -1e-9, and every vertex position."""
    saddle = "if eigenneg > 0 then { saddle; saddle_steps += 1 }"
    if saddle_below != 0:  # count again below the threshold first
        saddle = f"if eigenneg > 0 then {{ eigenprobe {saddle_below!r}; {saddle} }}"
    lines = ["hessian_normal off", "quiet on", "newton_steps := 0", "gradient_steps := 0",
             "saddle_steps := 0"]
    for k, (kbend, gsteps, cap) in enumerate(schedule):
        lines += [
            f"kbend := {kbend!r}",
            "bend.modulus := kbend",
            f"printf \"STAGE {k} kbend %g start %.17g\\n\", kbend, total_energy",
            f"g {gsteps}",
            f"gradient_steps += {gsteps}",
            "newton_count := 0",
            "do { e_old := total_energy; hessian_seek; newton_count += 1; " + saddle + "; "
            f"}} while (e_old - total_energy > {NEWTON_TOL!r} * abs(e_old) && newton_count < {cap})",
            "newton_steps += newton_count",
            f"printf \"STAGE {k} kbend %g end %.17g newton %d\\n\", kbend, total_energy, "
            "newton_count",
        ]
    lines += [
        "printf \"ENERGY %.17g %.17g %.17g\\n\", stretch.value, bend.value, total_energy",
        "printf \"STEPS %d %d %d\\n\", gradient_steps, newton_steps, saddle_steps",
        "quiet off",
        "eigenprobe 0",
        "eigenprobe -1e-9",
        "foreach vertex vv do printf \"P %d %.17g %.17g %.17g\\n\", vv.id, vv.x, vv.y, vv.z",
        "quit",
    ]
    return "\n".join(lines) + "\n"


def run_evolver(fe, commands, log_path):
    """Runs `evolver -x -f commands fe`, keeps its output in log_path; returns (text, wall seconds,
    CPU seconds)."""
    evolver = shutil.which("evolver")
    if not evolver:
        raise SystemExit("referee: `evolver` not found (Debian package evolver-nox)")
    start = time.monotonic()
    cpu = resource.getrusage(resource.RUSAGE_CHILDREN)
    with open(log_path, "w", encoding="utf-8") as log:
        proc = subprocess.run([evolver, "-x", "-f", commands, fe], stdin=subprocess.DEVNULL,
                              stdout=log, stderr=subprocess.STDOUT, check=False)
    seconds = time.monotonic() - start
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu_seconds = (after.ru_utime - cpu.ru_utime) + (after.ru_stime - cpu.ru_stime)
    with open(log_path, encoding="utf-8", errors="replace") as log:
        text = log.read()
    if proc.returncode != 0 or "ENERGY" not in text:
        raise SystemExit(f"referee: evolver failed (exit {proc.returncode}); see {log_path}")
    return text, seconds, cpu_seconds


def parse_log(text, n):
    """(positions n x 3, energies dict, stages list, eigen counts or None) from Evolver's output."""
    x = np.full((n, 3), np.nan)
    for m in re.finditer(r"^P (\d+) (\S+) (\S+) (\S+)$", text, re.M):
        x[int(m.group(1)) - 1] = [float(m.group(k)) for k in (2, 3, 4)]
    if np.isnan(x).any():
        raise SystemExit("referee: evolver's output lacks some vertex positions")
    stretch, bend, total = (float(t) for t in re.search(r"^ENERGY (\S+) (\S+) (\S+)$", text,
                                                        re.M).groups())
    gsteps, nsteps, ssteps = (int(t) for t in
                              re.search(r"^STEPS (\d+) (\d+) (\d+)$", text, re.M).groups())
    stages = [{"kbend": float(m.group(2)), "energy": float(m.group(3)),
               "newton_steps": int(m.group(4))}
              for m in re.finditer(r"^STAGE (\d+) kbend (\S+) end (\S+) newton (\d+)$", text, re.M)]
    counts = [[int(t) for t in m.groups()] for m in
              re.finditer(r"Eigencounts:\s+(\d+)\s*<,\s*(\d+)\s*==,\s*(\d+)\s*>", text)]
    return x, {"stretch": stretch, "bend": bend, "total": total, "gradient_steps": gsteps,
               "newton_steps": nsteps, "saddle_steps": ssteps}, stages, counts


def solve(args):
    a, b = sh.read_piece(args.folder, "a"), sh.read_piece(args.folder, "b")
    for _ in range(args.subdivide):
        a, b = sh.subdivide(a), sh.subdivide(b)
    sheet = sh.Sheet(a, b)
    start = sheet.x.copy()
    if args.mirror:
        start[:, 2] = -start[:, 2]
    os.makedirs(args.output, exist_ok=True)
    schedule, saddle_below = SCHEDULES[args.schedule]
    fe = os.path.join(args.output, "sheet.fe")
    cmd = os.path.join(args.output, "schedule.cmd")
    command = " ".join(["tests/referee/referee.py"] + sys.argv[1:])
    sheet.write_fe(fe, start, [f"dform referee sheet of {args.folder}", command],
                   1.0, schedule[0][0], POISSON)
    with open(cmd, "w", encoding="utf-8") as f:
        f.write(command_file(schedule, saddle_below))
    load = open("/proc/loadavg", encoding="utf-8").read().split()[:3]
    text, seconds, cpu_seconds = run_evolver(fe, cmd, os.path.join(args.output, "evolver.log"))
    x, energies, stages, counts = parse_log(text, len(sheet.x))
    strain = sh.edge_strains(sheet, x)
    summary = {
        "source": os.path.abspath(args.folder),
        "command": command,
        "subdivide": args.subdivide,
        "mirror": args.mirror,
        "schedule": args.schedule,
        "vertices": len(sheet.x),
        "faces": len(sheet.faces),
        "seam_points": len(sheet.seam),
        "start_L_max": float(np.max(np.abs(sh.edge_strains(sheet, start)))),
        "L_max": float(np.max(np.abs(strain))),
        "L_rms": float(np.sqrt(np.mean(strain ** 2))),
        "bending": sh.bending(sheet, x),
        "evolver_energy": energies,
        "final_kbend": schedule[-1][0],
        "stages": stages,
        "hessian_eigencounts_about_0_and_minus_1e-9": counts,
        "seconds": round(seconds, 2),
        "cpu_seconds": round(cpu_seconds, 2),
        "loadavg_at_start": " ".join(load),
        "machine": platform.machine(),
        "evolver": "Surface Evolver 2.70a (Debian evolver-nox)",
    }
    sh.write_model(args.output, sheet, x)
    if args.dform:
        summary["dform_validate"] = dform_validate(args.dform, args.folder, args.output)
    sh.write_json(os.path.join(args.output, "seam.json"),
                  {"source": summary["source"], "command": command, "units": "mm",
                   "points": [[float(c) for c in p] for p in sheet.seam_points(x)]})
    sh.write_json(os.path.join(args.output, "summary.json"), summary)
    print(json.dumps({k: summary[k] for k in ("vertices", "L_max", "bending", "seconds",
                                              "hessian_eigencounts_about_0_and_minus_1e-9",
                                              "cpu_seconds")}))


def dform_validate(dform, source, folder):
    """`dform validate --gate none --json` on the solved sheet: the start's report.json is copied
    in (validate needs one), so validate exits 7 listing how the start's figures differ from the
    sheet's; the figures it measures on the sheet's meshes are what is kept here."""
    shutil.copyfile(os.path.join(source, "report.json"), os.path.join(folder, "report.json"))
    proc = subprocess.run([dform, "validate", folder, "--gate", "none", "--json"],
                          stdin=subprocess.DEVNULL, capture_output=True, text=True, check=False)
    try:
        out = json.loads(proc.stdout)
    except json.JSONDecodeError:
        return {"exit_code": proc.returncode, "error": proc.stderr.strip()}
    return {"exit_code": proc.returncode,
            "checks": {c["name"]: c["value"] for c in out["gate"]["checks"]},
            "note": "report.json is the start's: exit 7 lists the start's figures that differ"}


def kabsch(p, q, allow_mirror=False):
    """q moved by the rotation (and, with allow_mirror, reflection) and translation that bring it
    closest to p in the least-squares sense."""
    pc, qc = p.mean(0), q.mean(0)
    u, _, vt = np.linalg.svd((q - qc).T @ (p - pc))
    d = np.sign(np.linalg.det(u @ vt))
    if allow_mirror:
        d = 1.0
    r = u @ np.diag([1.0, 1.0, d]) @ vt
    return (q - qc) @ r + pc


def seam_distance(p, q, allow_mirror=False):
    """(RMS, max) distance of seam q from seam p after alignment, over p's bbox diagonal."""
    p, q = np.asarray(p, float), np.asarray(q, float)
    if len(p) != len(q):
        if len(q) % len(p) == 0:
            q = q[:: len(q) // len(p)]
        elif len(p) % len(q) == 0:
            p = p[:: len(p) // len(q)]
        else:
            raise SystemExit("referee: the seams' point counts do not divide each other")
    moved = kabsch(p, q, allow_mirror)
    d = np.linalg.norm(moved - p, axis=1)
    diag = float(np.linalg.norm(p.max(0) - p.min(0)))
    return float(np.sqrt(np.mean(d ** 2)) / diag), float(d.max() / diag)


def seam_of(args):
    """The 3D seam of a dform result folder as a seam.json."""
    a = sh.read_piece(args.folder, "a")
    sh.write_json(args.output, {"source": os.path.abspath(args.folder),
                                "command": " ".join(["tests/referee/referee.py"] + sys.argv[1:]),
                                "units": "mm",
                                "points": [[float(c) for c in a.shape[i]] for i in a.seam]})


def compare(args):
    load = [json.load(open(path, encoding="utf-8"))["points"] for path in (args.first, args.second)]
    rms, worst = seam_distance(load[0], load[1], args.mirror)
    print(json.dumps({"rms_over_diagonal": rms, "max_over_diagonal": worst}))


def bending_on(args):
    """Each result folder's hinge energy on its own mesh and resampled onto the reference's."""
    reference = [sh.read_piece(args.on, p) for p in "ab"]
    for folder in args.folders:
        pieces = [sh.read_piece(folder, p) for p in "ab"]
        own = sh.Sheet(*pieces)
        common = sh.Sheet(*(sh.resample(piece, ref) for piece, ref in zip(pieces, reference)))
        print(json.dumps({"folder": folder, "reference": args.on,
                          "reference_vertices": len(common.x),
                          "hinge_own_mesh": sh.bending(own, own.x)["hinge"],
                          "hinge_on_reference": sh.bending(common, common.x)["hinge"]}))


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    sub = parser.add_subparsers(dest="command", required=True)
    s = sub.add_parser("solve", help="an Evolver sheet from a dform result folder")
    s.add_argument("folder")
    s.add_argument("-o", "--output", required=True)
    s.add_argument("--subdivide", type=int, default=0, choices=[0, 1, 2])
    s.add_argument("--mirror", action="store_true", help="start from the mirror image (z -> -z)")
    s.add_argument("--schedule", default="default", choices=sorted(SCHEDULES))
    s.add_argument("--dform", help="a dform binary: measure the sheet with `dform validate` too")
    s.set_defaults(run=solve)
    t = sub.add_parser("seam", help="the 3D seam of a dform result folder as a seam.json")
    t.add_argument("folder")
    t.add_argument("-o", "--output", required=True)
    t.set_defaults(run=seam_of)
    c = sub.add_parser("compare", help="distance between two seam.json files")
    c.add_argument("first")
    c.add_argument("second")
    c.add_argument("--mirror", action="store_true")
    c.set_defaults(run=compare)
    b = sub.add_parser("bending", help="hinge energies of result folders on one reference mesh")
    b.add_argument("folders", nargs="+")
    b.add_argument("--on", required=True, help="a result folder whose pieces' meshes are the reference")
    b.set_defaults(run=bending_on)
    args = parser.parse_args()
    args.run(args)


if __name__ == "__main__":
    main()
