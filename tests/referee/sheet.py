# SPDX-License-Identifier: GPL-3.0-or-later
"""The referee's sheet: two dform pieces read from a result folder, glued into one surface.

A dform result folder holds piece-a-flat.obj / piece-a-3d.obj and piece-b-flat.obj / piece-b-3d.obj
(src/io/model_files.cpp): the same vertices and faces in both files of a piece, the flat layout
with z = 0, and polylines grouped as `seam` (one closed loop), `boundary` (free boundary loops) and
`crease`. Seam vertex i of A is zipped to seam vertex i of B, and the two share their 3D position.

The glued sheet keeps A's vertices, then B's vertices off the seam; B's seam vertex i becomes A's.
Every triangle keeps its own flat (reference) triangle, so each piece stretches against its own
pattern. An edge is a hinge with bending stiffness when two triangles of the same piece share it
and it is not a drawn crease; the seam, the free boundaries and the creases are free hinges.
"""
import json
import math

import numpy as np


class Piece:
    """One piece as dform writes it: flat (n x 2), shape (n x 3), faces (m x 3, 0-based), the seam
    loop, the free boundary loops and the creases (lists of 0-based vertex indices)."""

    def __init__(self, flat, shape, faces, seam, boundaries, creases):
        self.flat = np.asarray(flat, dtype=float)
        self.shape = np.asarray(shape, dtype=float)
        self.faces = np.asarray(faces, dtype=int)
        self.seam = list(seam)
        self.boundaries = [list(b) for b in boundaries]
        self.creases = [list(c) for c in creases]


def read_obj(path):
    """(vertices, faces, {group: [polyline, ...]}) of a dform piece OBJ, 0-based indices. A closed
    loop that repeats its first index at the end loses the repeat (model_files.cpp does the same)."""
    vertices, faces, lines = [], [], {}
    group = "seam"
    with open(path, encoding="utf-8") as f:
        for number, raw in enumerate(f, 1):
            parts = raw.split()
            if not parts or parts[0].startswith("#"):
                continue
            if parts[0] == "v":
                vertices.append([float(t) for t in parts[1:4]])
            elif parts[0] == "f":
                if len(parts) != 4:
                    raise ValueError(f"{path}:{number}: a face that is not a triangle")
                faces.append([int(t.split("/")[0]) - 1 for t in parts[1:4]])
            elif parts[0] == "g":
                group = parts[1] if len(parts) > 1 else "seam"
            elif parts[0] == "l":
                line = [int(t) - 1 for t in parts[1:]]
                if group != "crease" and len(line) > 1 and line[0] == line[-1]:
                    line.pop()
                lines.setdefault(group, []).append(line)
    if len(lines.get("seam", [])) != 1:
        raise ValueError(f"{path}: expected one seam polyline")
    return np.array(vertices), np.array(faces, dtype=int), lines


def read_piece(folder, name):
    """Piece `name` ('a' or 'b') of a dform result folder."""
    flat, faces, lines = read_obj(f"{folder}/piece-{name}-flat.obj")
    shape, faces3, lines3 = read_obj(f"{folder}/piece-{name}-3d.obj")
    if flat.shape != shape.shape or not np.array_equal(faces, faces3) or lines != lines3:
        raise ValueError(f"{folder}: piece {name}'s flat and 3D files do not match")
    return Piece(flat[:, :2], shape, faces, lines["seam"][0], lines.get("boundary", []),
                 lines.get("crease", []))


def subdivide(piece):
    """The piece with every triangle split into four at its edge midpoints (flat and 3D alike);
    seam, boundaries and creases get the midpoints of their edges in order."""
    flat, shape = list(piece.flat), list(piece.shape)
    middle = {}

    def mid(u, v):
        key = (min(u, v), max(u, v))
        if key not in middle:
            middle[key] = len(flat)
            flat.append(0.5 * (piece.flat[u] + piece.flat[v]))
            shape.append(0.5 * (piece.shape[u] + piece.shape[v]))
        return middle[key]

    faces = []
    for a, b, c in piece.faces:
        ab, bc, ca = mid(a, b), mid(b, c), mid(c, a)
        faces += [[a, ab, ca], [ab, b, bc], [ca, bc, c], [ab, bc, ca]]

    def loop(line, closed):
        out = []
        for k, u in enumerate(line):
            out.append(u)
            if closed or k + 1 < len(line):
                out.append(mid(u, line[(k + 1) % len(line)]))
        return out

    return Piece(flat, shape, faces, loop(piece.seam, True),
                 [loop(b, True) for b in piece.boundaries], [loop(c, False) for c in piece.creases])


def resample(piece, reference):
    """`reference` (a Piece: its flat mesh, seam, boundaries and creases) carrying `piece`'s
    surface: each reference vertex takes the 3D point of `piece` at the same flat place (the
    barycentric combination of the corners of `piece`'s flat triangle holding it; the nearest
    triangle's, clamped to it, where the place lies just outside `piece`'s outline, as on a curved
    outline sampled at other points). Results meshed differently, resampled onto one reference,
    are compared on one mesh: a fold then counts the same whichever mesh made it."""
    corners = piece.flat[piece.faces]
    origin, side1, side2 = corners[:, 0], corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0]
    det = side1[:, 0] * side2[:, 1] - side1[:, 1] * side2[:, 0]
    shape = np.empty((len(reference.flat), 3))
    for i, q in enumerate(reference.flat):
        d = q - origin
        v = (d[:, 0] * side2[:, 1] - d[:, 1] * side2[:, 0]) / det
        w = (side1[:, 0] * d[:, 1] - side1[:, 1] * d[:, 0]) / det
        weights = np.stack([1.0 - v - w, v, w], 1)
        inside = weights.min(1)
        f = int(np.argmax(inside))
        if inside[f] < -1e-9:  # outside every triangle: the nearest one's closest point
            near = np.argsort(np.linalg.norm(corners.mean(1) - q, axis=1))[:32]
            points = [closest_point(q, corners[t]) for t in near]
            k = int(np.argmin([np.linalg.norm(q - p) for p in points]))
            f = int(near[k])
            weights[f] = barycentric(points[k], corners[f])
        shape[i] = weights[f] @ piece.shape[piece.faces[f]]
    return Piece(reference.flat, shape, reference.faces, reference.seam, reference.boundaries,
                 reference.creases)


def barycentric(q, triangle):
    """Barycentric coordinates of flat point q in a flat triangle (3 x 2)."""
    a, b, c = triangle
    m = np.array([[b[0] - a[0], c[0] - a[0]], [b[1] - a[1], c[1] - a[1]]])
    v, w = np.linalg.solve(m, q - a)
    return np.array([1.0 - v - w, v, w])


def closest_point(q, triangle):
    """The point of a flat triangle (3 x 2, its inside included) nearest to q."""
    weights = barycentric(q, triangle)
    if weights.min() >= 0:
        return q
    best = None
    for k in range(3):
        a, b = triangle[k], triangle[(k + 1) % 3]
        t = min(1.0, max(0.0, float(np.dot(q - a, b - a) / np.dot(b - a, b - a))))
        p = a + t * (b - a)
        if best is None or np.linalg.norm(q - p) < np.linalg.norm(q - best):
            best = p
    return best


class Sheet:
    """Both pieces as one surface. `x` is n x 3 (the start or the solved shape); `faces` m x 3 with
    `face_piece` (0 for A, 1 for B) and `face_flat` (m x 3 x 2, each corner's flat position);
    `index[p]` maps piece p's vertex numbers to the sheet's; `seam` is the seam in sheet numbers."""

    def __init__(self, a, b):
        if len(a.seam) != len(b.seam):
            raise ValueError("the pieces' seams have different vertex counts")
        self.pieces = (a, b)
        index_a = np.arange(len(a.flat))
        index_b = np.full(len(b.flat), -1)
        for i, j in zip(a.seam, b.seam):
            index_b[j] = index_a[i]
        rest = [j for j in range(len(b.flat)) if index_b[j] < 0]
        index_b[rest] = len(a.flat) + np.arange(len(rest))
        self.index = (index_a, index_b)
        self.x = np.vstack([a.shape, b.shape[rest]])
        self.seam = [int(index_a[i]) for i in a.seam]
        self.seam_gap_mm = float(np.max(np.linalg.norm(a.shape[a.seam] - b.shape[b.seam], axis=1)))
        fa, fb = a.faces, b.faces
        if self._same_direction_on_seam(a, b):
            fb = fb[:, [0, 2, 1]]  # B turned so both pieces' triangles face the same side
        self.faces = np.vstack([index_a[fa], index_b[fb]])
        self.face_piece = np.array([0] * len(fa) + [1] * len(fb))
        self.face_flat = np.concatenate([a.flat[fa], b.flat[fb]])
        self._edges()

    @staticmethod
    def _same_direction_on_seam(a, b):
        """Whether A and B's triangles run the seam the same way (then B must be turned)."""
        def directed(piece):
            half = set()
            for f in piece.faces:
                for k in range(3):
                    half.add((f[k], f[(k + 1) % 3]))
            return (piece.seam[0], piece.seam[1]) in half
        return directed(a) == directed(b)

    def _edges(self):
        """Edges keyed by (u, v, owner): owner 2 for a seam edge (shared by the pieces), else the
        piece; `hinge[e]` is True where the edge carries bending (two faces of one piece, no
        crease). `face_edges` lists each face's three edges as (edge, +1 or -1)."""
        seam_pairs = {frozenset((self.seam[i], self.seam[(i + 1) % len(self.seam)]))
                      for i in range(len(self.seam))}
        creases = set()
        for p, piece in enumerate(self.pieces):
            for line in piece.creases:
                for u, v in zip(line, line[1:]):
                    creases.add((p, frozenset((int(self.index[p][u]), int(self.index[p][v])))))
        keys, edge_of, count = [], {}, []
        self.face_edges = []
        for f, tri in enumerate(self.faces):
            p = int(self.face_piece[f])
            row = []
            for k in range(3):
                u, v = int(tri[k]), int(tri[(k + 1) % 3])
                pair = frozenset((u, v))
                key = (min(u, v), max(u, v), 2 if pair in seam_pairs else p)
                if key not in edge_of:
                    edge_of[key] = len(keys)
                    keys.append(key)
                    count.append(0)
                e = edge_of[key]
                count[e] += 1
                row.append((e, 1 if u == key[0] else -1))
            self.face_edges.append(row)
        self.edges = np.array([[k[0], k[1]] for k in keys], dtype=int)
        self.edge_owner = np.array([k[2] for k in keys], dtype=int)
        self.hinge = np.array([k[2] != 2 and count[e] == 2 and (k[2], frozenset(k[:2])) not in creases
                               for e, k in enumerate(keys)])
        if max(count) > 2:
            raise ValueError("an edge with more than two triangles")

    def form_factors(self):
        """Per face (s11, s12, s22): dot products of the flat sides v1-v0 and v2-v0."""
        s1 = self.face_flat[:, 1] - self.face_flat[:, 0]
        s2 = self.face_flat[:, 2] - self.face_flat[:, 0]
        return np.stack([np.sum(s1 * s1, 1), np.sum(s1 * s2, 1), np.sum(s2 * s2, 1)], 1)

    def write_fe(self, path, x, header, kstretch, kbend, poisson):
        """A Surface Evolver datafile of the sheet at positions x (moduli as parameters)."""
        ff = self.form_factors()
        out = ["// " + line for line in header]
        out += [f"parameter kstretch = {kstretch!r}", f"parameter kbend = {kbend!r}",
                "define facet attribute form_factors real[3]",
                "define facet attribute poisson_ratio real",
                "quantity stretch energy modulus kstretch method linear_elastic global",
                "quantity bend energy modulus kbend method dihedral_hooke", "", "vertices"]
        out += [f"{i + 1} {p[0]!r} {p[1]!r} {p[2]!r}" for i, p in enumerate(x)]
        out += ["", "edges"]
        out += [f"{e + 1} {u + 1} {v + 1}" + (" bend" if self.hinge[e] else "")
                for e, (u, v) in enumerate(self.edges)]
        out += ["", "faces"]
        for f, row in enumerate(self.face_edges):
            ids = " ".join(str(s * (e + 1)) for e, s in row)
            s11, s12, s22 = ff[f]
            out.append(f"{f + 1} {ids} form_factors {{{s11!r},{s12!r},{s22!r}}} "
                       f"poisson_ratio {poisson!r} density 0")
        out += ["", "read", ""]
        with open(path, "w", encoding="utf-8") as f:
            f.write("\n".join(out))

    def piece_positions(self, x, p):
        """Piece p's 3D vertex positions taken from sheet positions x."""
        return x[self.index[p]]

    def seam_points(self, x):
        return x[self.seam]


def edge_strains(sheet, x):
    """Relative length change of every edge of both pieces against its piece's flat edge."""
    out = []
    for p, piece in enumerate(sheet.pieces):
        pairs = {(min(u, v), max(u, v)) for f in piece.faces for u, v in zip(f, np.roll(f, -1))}
        pairs = np.array(sorted(pairs))
        flat = np.linalg.norm(piece.flat[pairs[:, 0]] - piece.flat[pairs[:, 1]], axis=1)
        pos = sheet.piece_positions(x, p)
        now = np.linalg.norm(pos[pairs[:, 0]] - pos[pairs[:, 1]], axis=1)
        out.append(now / flat - 1.0)
    return np.concatenate(out)


def hinge_angles(sheet, x):
    """For every edge with two faces: (edge, signed turning angle in rad, |e|^2 / (A1 + A2) with
    the flat edge and areas of its piece). The turning is positive where the neighbour bends
    away from the side the face normals point to: on a closed sheet the normals are made to point
    outwards (positive enclosed volume), so a convex fold is positive; on an open sheet the sign
    follows piece A's orientation."""
    faces_of = {}
    for f, row in enumerate(sheet.face_edges):
        for e, _ in row:
            faces_of.setdefault(e, []).append(f)
    s1 = sheet.face_flat[:, 1] - sheet.face_flat[:, 0]
    s2 = sheet.face_flat[:, 2] - sheet.face_flat[:, 0]
    area = 0.5 * np.abs(s1[:, 0] * s2[:, 1] - s1[:, 1] * s2[:, 0])
    p = x[sheet.faces]
    normal = np.cross(p[:, 1] - p[:, 0], p[:, 2] - p[:, 0])
    normal /= np.linalg.norm(normal, axis=1)[:, None]
    side = 1.0
    if all(len(fs) == 2 for fs in faces_of.values()):
        volume = float(np.sum(np.einsum("ij,ij->i", p[:, 0], np.cross(p[:, 1], p[:, 2]))))
        side = 1.0 if volume > 0 else -1.0
    out = []
    for e, fs in faces_of.items():
        if len(fs) != 2:
            continue
        f, g = fs
        u, v = sheet.edges[e]
        ku = list(sheet.faces[f]).index(u)
        kv = list(sheet.faces[f]).index(v)
        opposite = [w for w in sheet.faces[g] if w != u and w != v][0]
        turn = math.acos(max(-1.0, min(1.0, float(np.dot(normal[f], normal[g])))))
        if float(np.dot(x[opposite] - x[u], normal[f])) * side > 0:
            turn = -turn
        flat_len2 = float(np.sum((sheet.face_flat[f][ku] - sheet.face_flat[f][kv]) ** 2))
        out.append((e, turn, flat_len2 / (area[f] + area[g])))
    return out


def bending(sheet, x):
    """Bending figures over the hinges (interior edges of each piece, creases left out):
    `dihedral_hooke` = sum (1 - cos theta) |e| (Surface Evolver's method, unit modulus) and
    `hinge` = sum theta^2 |e|^2 / (A1 + A2) (discrete shells, flat areas); the seam's and the
    hinges' fold angles (rad, min and max of the signed turning, hinge_angles' sign)."""
    hooke = hinge = 0.0
    seam, folds = [], []
    for e, angle, weight in hinge_angles(sheet, x):
        u, v = sheet.edges[e]
        if sheet.hinge[e]:
            hooke += (1.0 - math.cos(angle)) * float(np.linalg.norm(x[v] - x[u]))
            hinge += angle * angle * weight
            folds.append(angle)
        elif sheet.edge_owner[e] == 2:
            seam.append(angle)
    return {"dihedral_hooke": hooke, "hinge": hinge,
            "seam_fold_min_rad": min(seam) if seam else None,
            "seam_fold_max_rad": max(seam) if seam else None,
            "hinge_fold_min_rad": min(folds) if folds else None,
            "hinge_fold_max_rad": max(folds) if folds else None}


def exact_decimal(value):
    """Shortest decimal that reads back to the same double (Python's repr)."""
    text = repr(float(value))
    return "0" if text in ("0.0", "-0.0") else text


def write_piece_obj(path, piece, positions, layout):
    """A piece OBJ in dform's format (model_files.cpp objText) with the given positions."""
    cols = positions.shape[1]
    lines = [f"# dform piece {'A' if path.endswith(('a-flat.obj', 'a-3d.obj')) else 'B'}, "
             f"{layout} (mm): vertices, faces, then polylines grouped as seam, free boundary "
             "loops and creases"]
    for p in positions:
        z = exact_decimal(p[2]) if cols == 3 else "0"
        lines.append(f"v {exact_decimal(p[0])} {exact_decimal(p[1])} {z}")
    lines += [f"f {a + 1} {b + 1} {c + 1}" for a, b, c in piece.faces]
    lines += ["g seam", "l " + " ".join(str(i + 1) for i in piece.seam)]
    for group, loops in (("boundary", piece.boundaries), ("crease", piece.creases)):
        if loops:
            lines.append(f"g {group}")
        lines += ["l " + " ".join(str(i + 1) for i in line) for line in loops]
    with open(path, "w", encoding="utf-8") as f:
        f.write("\n".join(lines) + "\n")


def write_model(folder, sheet, x):
    """The four piece OBJs of dform's result format for the sheet at positions x."""
    for p, name in enumerate("ab"):
        piece = sheet.pieces[p]
        write_piece_obj(f"{folder}/piece-{name}-flat.obj", piece, piece.flat, "flat layout")
        write_piece_obj(f"{folder}/piece-{name}-3d.obj", piece, sheet.piece_positions(x, p),
                        "3D shape")


def write_json(path, data):
    with open(path, "w", encoding="utf-8") as f:
        json.dump(data, f, indent=1)
        f.write("\n")
