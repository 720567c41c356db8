# SPDX-License-Identifier: GPL-3.0-or-later
"""Checks of the referee's definitions on small made-up sheets (python3 -m pytest tests/referee).

The Evolver check runs only where `evolver` is installed (scripts/install-deps --referee)."""
import math
import os
import re
import shutil
import subprocess
import sys

import numpy as np
import pytest

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import referee  # noqa: E402
import sheet as sh  # noqa: E402


def square_pair(fold):
    """Two unit squares (two triangles each) zipped along their boundary: B is A turned over.
    A's diagonal is folded by `fold` rad in 3D, B stays flat (a pillow that stretches)."""
    flat = np.array([[0, 0], [1, 0], [1, 1], [0, 1]], float)
    faces = [[0, 1, 2], [0, 2, 3]]
    h = 0.5 * math.sin(fold)
    shape_a = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]], float)
    shape_a[[1, 3], 2] = h  # lifts the corners off the diagonal 0-2
    a = sh.Piece(flat, shape_a, faces, [0, 1, 2, 3], [], [])
    b = sh.Piece(flat * [1, -1], shape_a.copy(), [[0, 2, 1], [0, 3, 2]], [0, 1, 2, 3], [], [])
    return a, b


def test_sheet_shares_the_seam_and_turns_b():
    a, b = square_pair(0.0)
    s = sh.Sheet(a, b)
    assert len(s.x) == 4  # every vertex is on the seam: B adds none
    assert len(s.faces) == 4
    # A closed pillow: V - E + F = 2, and every edge has two faces (seam edges: one of each piece)
    assert len(s.x) - len(s.edges) + len(s.faces) == 2
    # Each piece's diagonal is its own edge and the only hinge; the four seam edges are not
    assert s.hinge.sum() == 2
    assert sorted(s.edge_owner.tolist()) == [0, 1, 2, 2, 2, 2]
    # Consistent orientation: every edge is run once each way by its two faces
    runs = {}
    for row in s.face_edges:
        for e, sign in row:
            runs.setdefault(e, []).append(sign)
    assert all(sorted(v) == [-1, 1] for v in runs.values())


def test_strain_and_form_factors_follow_the_flat_pieces():
    a, b = square_pair(0.0)
    s = sh.Sheet(a, b)
    assert np.max(np.abs(sh.edge_strains(s, s.x))) < 1e-15
    stretched = s.x * [1.01, 1.0, 1.0]
    assert abs(np.max(np.abs(sh.edge_strains(s, stretched))) - 0.01) < 1e-12
    ff = s.form_factors()
    for f, tri in enumerate(s.faces):  # dot products of the flat sides from the face's first corner
        p = s.face_flat[f]
        assert np.allclose(ff[f], [np.dot(p[1] - p[0], p[1] - p[0]),
                                   np.dot(p[1] - p[0], p[2] - p[0]),
                                   np.dot(p[2] - p[0], p[2] - p[0])])
        assert len(set(tri.tolist())) == 3


def test_subdivide_halves_every_edge_and_keeps_the_seam_shared():
    a, b = square_pair(0.4)
    a2, b2 = sh.subdivide(a), sh.subdivide(b)
    assert len(a2.faces) == 4 * len(a.faces) and len(a2.seam) == 2 * len(a.seam)
    assert np.allclose(a2.shape[a2.seam[1]], 0.5 * (a.shape[0] + a.shape[1]))
    s = sh.Sheet(a2, b2)
    assert len(s.x) - len(s.edges) + len(s.faces) == 2
    # the seam midpoints of B are A's: one vertex each, at the same 3D point
    assert np.allclose(s.seam_points(s.x)[1], 0.5 * (a.shape[0] + a.shape[1]))
    strains = sh.edge_strains(sh.Sheet(a, b), sh.Sheet(a, b).x)
    assert np.max(np.abs(sh.edge_strains(s, s.x))) <= np.max(np.abs(strains)) + 1e-15


def test_hinge_angle_of_a_folded_diagonal():
    fold = 0.3
    a, b = square_pair(fold)
    s = sh.Sheet(a, b)
    angles = {int(e): t for e, t, _ in sh.hinge_angles(s, s.x)}
    diagonal_a = [e for e in range(len(s.edges)) if s.hinge[e] and s.edge_owner[e] == 0][0]
    p = s.x
    n1 = np.cross(p[1] - p[0], p[2] - p[0])
    n2 = np.cross(p[2] - p[0], p[3] - p[0])
    expected = math.acos(np.dot(n1, n2) / np.linalg.norm(n1) / np.linalg.norm(n2))
    assert abs(abs(angles[diagonal_a]) - expected) < 1e-12 and expected > 0.1
    bend = sh.bending(s, s.x)
    # both pieces lie on the same folded surface: two hinges of length sqrt(2) turn by the fold
    assert abs(bend["dihedral_hooke"] - 2 * (1 - math.cos(expected)) * math.sqrt(2)) < 1e-12


def folded_grid(n, fold, margin=0.0):
    """A 100 mm square split into n x n cells (two triangles each), folded by `fold` rad along
    x = 50 (a grid line for even n), zipped to its turned-over copy (as square_pair); `margin`
    grows the flat square by that much on every side (the fold stays at x = 50)."""
    ticks = np.linspace(-margin, 100.0 + margin, n + 1)
    flat = np.array([[x, y] for y in ticks for x in ticks])
    shape = np.zeros((len(flat), 3))
    for i, (x, y) in enumerate(flat):
        t = max(0.0, x - 50.0)
        shape[i] = [min(x, 50.0) + t * math.cos(fold), y, t * math.sin(fold)]
    at = lambda i, j: j * (n + 1) + i  # noqa: E731
    faces = []
    for j in range(n):
        for i in range(n):
            faces += [[at(i, j), at(i + 1, j), at(i + 1, j + 1)], [at(i, j), at(i + 1, j + 1), at(i, j + 1)]]
    loop = ([at(i, 0) for i in range(n)] + [at(n, j) for j in range(n)] +
            [at(i, n) for i in range(n, 0, -1)] + [at(0, j) for j in range(n, 0, -1)])
    a = sh.Piece(flat, shape, faces, loop, [], [])
    b = sh.Piece(flat * [1, -1], shape.copy(), [[f[0], f[2], f[1]] for f in faces], loop, [], [])
    return a, b


def hinge_of(a, b):
    s = sh.Sheet(a, b)
    return sh.bending(s, s.x)["hinge"]


def test_a_fold_counts_the_same_on_one_reference_mesh_whichever_mesh_made_it():
    fold = 0.6
    coarse, fine, reference = folded_grid(8, fold), folded_grid(16, fold), folded_grid(4, 0.0)
    # On its own mesh a fold counts once per edge along it: each of the n fold edges of a piece
    # has |e|^2 / (A1 + A2) = 1, so the hinge energy is 2 n fold^2 and doubles with the mesh.
    assert abs(hinge_of(*coarse) - 2 * 8 * fold ** 2) < 1e-9
    assert abs(hinge_of(*fine) - 2 * 16 * fold ** 2) < 1e-9
    on_reference = [hinge_of(*(sh.resample(p, r) for p, r in zip(model, reference)))
                    for model in (coarse, fine)]
    assert abs(on_reference[0] - 2 * 4 * fold ** 2) < 1e-9
    assert abs(on_reference[1] - on_reference[0]) < 1e-9


def test_resampling_onto_its_own_mesh_gives_its_own_surface():
    a, _ = folded_grid(6, 0.4)
    again = sh.resample(a, a)
    assert np.max(np.abs(again.shape - a.shape)) < 1e-12
    assert again.faces.tolist() == a.faces.tolist() and again.seam == a.seam


def test_a_reference_point_just_outside_takes_the_nearest_point_of_the_surface():
    model, _ = folded_grid(8, 0.4)
    wider, _ = folded_grid(8, 0.0, margin=0.01)
    placed = sh.resample(model, wider)
    # the corner (-0.01, -0.01) lands on the model's corner, (100.01, 50) on its folded edge at y=50
    corner = int(np.argmin(np.linalg.norm(wider.flat - [-0.01, -0.01], axis=1)))
    assert np.allclose(placed.shape[corner], [0, 0, 0], atol=1e-12)
    right = int(np.argmin(np.linalg.norm(wider.flat - [100.01, 50.0], axis=1)))
    assert np.allclose(placed.shape[right], [50 + 50 * math.cos(0.4), 50.0, 50 * math.sin(0.4)], atol=1e-12)


def test_seam_distance_ignores_rigid_motions_not_reflections():
    rng = np.random.default_rng(1)
    p = rng.normal(size=(30, 3))
    c, s_ = math.cos(0.7), math.sin(0.7)
    r = np.array([[c, -s_, 0], [s_, c, 0], [0, 0, 1]])
    q = p @ r.T + [3, -1, 2]
    assert referee.seam_distance(p, q)[1] < 1e-12
    mirrored = p * [1, 1, -1]
    assert referee.seam_distance(p, mirrored)[0] > 0.05
    assert referee.seam_distance(p, mirrored, allow_mirror=True)[1] < 1e-12
    # a seam of twice the points is compared on every other point
    twice = np.repeat(q, 2, axis=0)
    assert referee.seam_distance(p, twice)[1] < 1e-12


@pytest.mark.skipif(shutil.which("evolver") is None, reason="Surface Evolver not installed")
def test_evolver_reads_the_energies_as_defined(tmp_path):
    """The datafile's stretching energy is linear_elastic's formula with the flat form factors, and
    its bending energy is (1 - cos theta) |e| on the hinges only."""
    a, b = square_pair(0.3)
    s = sh.Sheet(a, b)
    x = s.x * [1.02, 0.99, 1.0]
    fe = tmp_path / "t.fe"
    s.write_fe(str(fe), x, ["test"], 1.0, 1.0, 0.3)
    cmd = tmp_path / "t.cmd"
    cmd.write_text('printf "VALUES %.17g %.17g\\n", stretch.value, bend.value\nquit\n')
    out = subprocess.run(["evolver", "-x", "-f", str(cmd), str(fe)], capture_output=True,
                         text=True, stdin=subprocess.DEVNULL, check=False).stdout
    values = re.search(r"^VALUES (\S+) (\S+)$", out, re.M)
    stretch, bend = float(values.group(1)), float(values.group(2))
    p = x[s.faces]
    e1, e2 = p[:, 1] - p[:, 0], p[:, 2] - p[:, 0]
    expected = 0.0
    for f, ff in enumerate(s.form_factors()):
        gram = np.array([[e1[f] @ e1[f], e1[f] @ e2[f]], [e1[f] @ e2[f], e2[f] @ e2[f]]])
        ref = np.array([[ff[0], ff[1]], [ff[1], ff[2]]])
        c = (gram @ np.linalg.inv(ref) - np.eye(2)) / 2
        v = 0.3
        density = (np.trace(c @ c) + v * np.trace(c) ** 2 / (1 - v)) / 2 / (1 + v)
        expected += density * 0.5 * math.sqrt(np.linalg.det(ref))
    assert stretch > 1e-6 and abs(stretch - expected) < 1e-12 * max(1.0, expected)
    assert abs(bend - sh.bending(s, x)["dihedral_hooke"]) < 1e-12
