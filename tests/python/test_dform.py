# SPDX-License-Identifier: GPL-3.0-or-later
"""The Python module `dform` (docs/python.md): numpy in and out, the same D-Form as the command
line makes of the same outlines, every bad input a dform.Error with the documented exit code, and
a result folder that `dform validate` accepts. Run by ctest (python_module) with PYTHONPATH set to
build/python and DFORM_SAMPLES, DFORM_EXE set."""
import json
import math
import os
import re
import subprocess

import numpy as np
import pytest

import dform

SAMPLES = os.environ["DFORM_SAMPLES"]
EXE = os.environ["DFORM_EXE"]


def sample(name):
    return os.path.join(SAMPLES, name)


def ellipse(a, b, n=400, clockwise=False):
    t = np.linspace(0, 2 * math.pi, n, endpoint=False)
    if clockwise:
        t = -t
    return np.column_stack([a * np.cos(t), b * np.sin(t)])


def test_the_outlines_of_the_sample_files_give_the_dform_of_the_command(tmp_path):
    a = dform.read_outline(sample("forward/ellipses-a.svg"))
    b = dform.read_outline(sample("forward/ellipses-b.svg"))
    result = dform.forward(a["outline"], b["outline"], resolution=60)
    out = tmp_path / "cli"
    subprocess.run([EXE, "forward", sample("forward/ellipses-a.svg"),
                    sample("forward/ellipses-b.svg"), "--resolution", "60", "--no-export",
                    "--gate", "none", "-q", "-o", str(out)], check=True)
    report = json.loads((out / "report.json").read_text())
    assert result.model == report["model"]["name"] == "exact"
    # The same solve: the figures agree to the digits report.json keeps.
    for key in ("L_error", "L_max", "seam_length_a_mm", "exact_distance_rms_rel"):
        assert result.figures[key] == pytest.approx(report["metrics"][key], rel=1e-12, abs=1e-15)
    piece = result.piece_a
    assert piece["flat"].shape == (report["mesh"]["vertices_a"], 2)
    assert piece["shape"].shape == (report["mesh"]["vertices_a"], 3)
    assert piece["faces"].shape == (report["mesh"]["triangles_a"], 3)
    assert len(piece["seam"]) == 60


def test_glued_edges_keep_their_flat_lengths():
    result = dform.forward(ellipse(60, 30), ellipse(45, 40.4), fit_perimeter=True, resolution=50)
    for piece in (result.piece_a, result.piece_b):
        faces = piece["faces"]
        for i, j in ((0, 1), (1, 2), (2, 0)):
            flat = np.linalg.norm(piece["flat"][faces[:, i]] - piece["flat"][faces[:, j]], axis=1)
            shape = np.linalg.norm(piece["shape"][faces[:, i]] - piece["shape"][faces[:, j]], axis=1)
            # The exact model bends without stretching: L_max is the largest relative change.
            assert np.max(np.abs(shape - flat) / flat) <= result.figures["L_max"] + 1e-12
    a_seam = result.piece_a["shape"][result.piece_a["seam"]]
    b_seam = result.piece_b["shape"][result.piece_b["seam"]]
    assert np.max(np.linalg.norm(a_seam - b_seam, axis=1)) <= result.figures["seam_gap_mm"] + 1e-12


def test_a_clockwise_outline_starts_where_it_was_drawn():
    ccw = dform.forward(ellipse(60, 30), ellipse(60, 30), start_b=0.25, resolution=40)
    cw = dform.forward(ellipse(60, 30, clockwise=True), ellipse(60, 30), start_b=0.25,
                       resolution=40)
    # Either way round, the same D-Form, its seam starting at the outline's first point (60, 0):
    # within what the exact model's equal chords move a seam point (0.14 mm here), where the
    # other end of the ellipse would be 120 mm away.
    first = [r.piece_a["flat"][r.piece_a["seam"][0]] for r in (ccw, cw)]
    assert np.allclose(first[0], first[1], atol=1e-9)
    assert np.linalg.norm(first[0] - [60, 0]) < 0.5
    assert np.allclose(ccw.piece_a["shape"][ccw.piece_a["seam"]],
                       cw.piece_a["shape"][cw.piece_a["seam"]], atol=1e-6)


def test_bad_input_is_an_error_with_its_exit_code():
    square = np.array([[0, 0], [100, 0], [100, 100], [0, 100]], float)
    with pytest.raises(dform.Error) as unequal:
        dform.forward(square, ellipse(10, 10), resolution=40)
    assert unequal.value.exit_code == 4 and "piece A and piece B" in str(unequal.value)
    with pytest.raises(dform.Error) as crossing:
        dform.forward(np.array([[0, 0], [100, 100], [100, 0], [0, 100]], float), square)
    assert crossing.value.exit_code == 4 and "crosses itself" in str(crossing.value)
    with pytest.raises(dform.Error) as nan:
        dform.forward(np.array([[0, 0], [math.nan, 0], [100, 100]], float), square)
    assert nan.value.exit_code == 4 and "not a finite number" in str(nan.value)
    with pytest.raises(dform.Error) as shape:
        dform.forward(np.zeros((5, 3)), square)
    assert shape.value.exit_code == 2 and "(n, 2)" in str(shape.value)
    for options in ({"resolution": 3}, {"model": "magic"}, {"weights": {"nope": 1.0}}):
        with pytest.raises(dform.Error) as usage:
            dform.forward(square, square, **options)
        assert usage.value.exit_code == 2, options
    with pytest.raises(dform.Error) as missing:
        dform.read_outline(sample("forward/no-such-file.svg"))
    assert missing.value.exit_code == 3


def test_inverse_from_points_round_trips_the_tennis_ball():
    curve = dform.read_curve(sample("inverse/tennis-ball.obj"))
    result = dform.inverse(curve, resolution=60)
    assert result.model == "exact"
    assert result.figures["D_error"] < 1e-9
    assert result.figures["roundtrip_rms_rel"] < 1e-6
    assert result.target.shape == (60, 3)
    with pytest.raises(dform.Error) as flat:
        dform.inverse(np.zeros((10, 3)))
    assert flat.value.exit_code in (4,)


def test_export_writes_a_folder_that_validates(tmp_path):
    a = dform.read_outline(sample("forward/ellipses-a.svg"))
    b = dform.read_outline(sample("forward/ellipses-b.svg"))
    result = dform.forward(a["outline"], b["outline"], resolution=60, name_a="ellipses-a",
                           name_b="ellipses-b")
    outcome = result.export(str(tmp_path / "out"), profile="print")
    assert outcome["gate_passed"] is True and outcome["cutting_files"] is True
    for name in ("report.json", "report.html", "pattern.pdf", "piece-a-3d.obj"):
        assert (tmp_path / "out" / name).stat().st_size > 0
    report = json.loads((tmp_path / "out" / "report.json").read_text())
    assert report["job"]["piece_a"] == "ellipses-a"
    assert any(text.startswith("exact model") for _, text in result.messages)
    assert subprocess.run([EXE, "validate", str(tmp_path / "out")],
                          capture_output=True).returncode == 0
    with pytest.raises(dform.Error) as profile:
        result.export(str(tmp_path / "other"), profile="nope")
    assert profile.value.exit_code == 2 and not (tmp_path / "other").exists()
    # Joints, material and kerf as keywords; a bad value is named by its keyword.
    result.export(str(tmp_path / "holes"), joint="holes", material="plywood", kerf=0.2)
    pattern = json.loads((tmp_path / "holes" / "pattern.json").read_text())
    assert pattern["joint"]["kind"] == "holes" and pattern["joint"]["thickness_mm"] == 3.0
    assert pattern["kerf_mm"] == 0.2 and len(pattern["joint_holes"]) > 10
    with pytest.raises(dform.Error) as joint:
        result.export(str(tmp_path / "bad-joint"), joint="tape")
    assert joint.value.exit_code == 2 and "joint must be" in str(joint.value)
    with pytest.raises(dform.Error) as edge:
        result.export(str(tmp_path / "bad-edge"), hole_edge=1.0)
    assert "hole_edge" in str(edge.value)
    result.export(str(tmp_path / "slots"), joint="slots", slot_length=6.0)
    pattern = json.loads((tmp_path / "slots" / "pattern.json").read_text())
    assert pattern["joint"]["slot_length_mm"] == 6.0 and len(pattern["joint_slots"]) > 10
    with pytest.raises(dform.Error) as slot:
        result.export(str(tmp_path / "bad-slot"), joint="slots", slot_length=1.0)
    assert "slot_length" in str(slot.value)


def test_export_takes_the_hinge_and_the_numbers(tmp_path):
    """numbers= puts the ticks' numbers on the tabs, the face or both; hinge= turns the plywood's
    hinge off, and on a flexible sheet is refused naming the keyword; report.json keeps both."""
    a = dform.read_outline(sample("forward/ellipses-a.svg"))
    b = dform.read_outline(sample("forward/ellipses-b.svg"))
    result = dform.forward(a["outline"], b["outline"], resolution=60, model="exact")

    def labels(name, **settings):
        result.export(str(tmp_path / name), profile="print", **settings)
        svg = (tmp_path / name / "pattern.svg").read_text()
        report = json.loads((tmp_path / name / "report.json").read_text())
        assert all(report["job"]["export"].get(k) == v for k, v in settings.items()), report["job"]
        return (len(re.findall(r'id="[AB]-tick-\d+-tab-label"', svg)),
                len(re.findall(r'id="[AB]-tick-\d+-label"', svg)))

    on_face, on_tabs, on_both = labels("face", numbers="face"), labels("tabs", numbers="tabs"), \
        labels("both", numbers="both")
    assert on_face[0] == 0 and on_face[1] > 20
    assert on_tabs[0] > 10 and on_tabs[1] < on_face[1]
    assert on_both == (on_tabs[0], on_face[1])

    def hinges(name, **settings):
        result.export(str(tmp_path / name), material="plywood", **settings)
        pattern = json.loads((tmp_path / name / "pattern.json").read_text())
        report = json.loads((tmp_path / name / "report.json").read_text())
        assert report["job"]["export"].get("hinge") == settings.get("hinge"), report["job"]
        return sum(len(p.get("hinges", [])) for p in pattern["pieces"])

    assert hinges("plywood") > 0 and hinges("plywood-on", hinge=True) == hinges("plywood")
    assert hinges("plywood-off", hinge=False) == 0
    with pytest.raises(dform.Error) as card:
        result.export(str(tmp_path / "card"), material="card", hinge=True)
    assert card.value.exit_code == 2 and str(card.value).startswith("hinge:")
    assert not (tmp_path / "card").exists()
