# SPDX-License-Identifier: GPL-3.0-or-later
"""The package dform as a library: its version is the CMake project's, results print, compare and
pickle (multiprocessing), the pieces are numpy arrays, the package under test is the one meant
(DFORM_PACKAGE_DIR: the build tree or an installed copy), and every command-line option a message
can name reaches Python as the keyword that sets it."""
import math
import multiprocessing
import os
import pickle
import re

import numpy as np
import pytest

import dform

SOURCE = os.environ["DFORM_SOURCE"]


def ellipse(a, b, n=300):
    t = np.linspace(0, 2 * math.pi, n, endpoint=False)
    return np.column_stack([a * np.cos(t), b * np.sin(t)])


@pytest.fixture(scope="module")
def result():
    return dform.forward(ellipse(60, 30), ellipse(45, 40.4), fit_perimeter=True, resolution=40)


def test_the_package_under_test_is_the_one_meant():
    expected = os.path.realpath(os.environ["DFORM_PACKAGE_DIR"])
    assert os.path.realpath(os.path.dirname(dform.__file__)) == expected
    assert os.path.realpath(os.path.dirname(dform._dform.__file__)) == expected


def test_the_version_is_the_cmake_projects():
    with open(os.path.join(SOURCE, "CMakeLists.txt"), encoding="utf-8") as cmake_lists:
        version = re.search(r"project\(dform VERSION ([0-9.]+)", cmake_lists.read()).group(1)
    assert dform.__version__ == version


def test_a_result_prints_its_model_pieces_and_figures(result):
    text = repr(result)
    assert text.startswith("<dform.Result forward model='exact'")
    for piece in (result.piece_a, result.piece_b):
        assert "{}: {} vertices, {} triangles".format(
            piece["name"], len(piece["flat"]), len(piece["faces"])) in text
    assert "L_max={:.4g}".format(result.figures["L_max"]) in text


def test_every_array_of_a_piece_is_numpy(result):
    for piece in (result.piece_a, result.piece_b):
        assert piece["flat"].dtype == np.float64 and piece["flat"].shape[1] == 2
        assert piece["shape"].dtype == np.float64 and piece["shape"].shape[1] == 3
        assert piece["faces"].dtype.kind == "i" and piece["faces"].shape[1] == 3
        assert isinstance(piece["seam"], np.ndarray) and piece["seam"].dtype.kind == "i"
        assert piece["seam"].shape == (40,)
        assert piece["seam"].min() >= 0 and piece["seam"].max() < len(piece["flat"])


def test_a_pickled_result_unpickles_equal_and_exports_the_same_folder(result, tmp_path):
    again = pickle.loads(pickle.dumps(result))
    assert again == result and again is not result
    assert np.array_equal(again.piece_b["shape"], result.piece_b["shape"])
    assert again.messages == result.messages and again.model_reason == result.model_reason
    # Equality looks at every number: one vertex moved by a nanometre is another result.
    moved = pickle.loads(pickle.dumps(result))
    moved.piece_b["shape"][0, 0] += 1e-6
    assert moved != result
    other = dform.forward(ellipse(60, 30), ellipse(60, 30), resolution=40)
    assert other != result
    # The unpickled result solves its call again to write the folder: the same report figures.
    first = result.export(str(tmp_path / "first"), cutting_files=False)
    second = again.export(str(tmp_path / "second"), cutting_files=False)
    assert [c["value"] for c in first["checks"] if not math.isnan(c["value"])] == \
        [c["value"] for c in second["checks"] if not math.isnan(c["value"])]


def test_an_inverse_result_pickles_with_its_target():
    curve = dform.read_curve(os.path.join(SOURCE, "samples", "inverse", "tennis-ball.obj"))
    result = dform.inverse(curve, resolution=40)
    again = pickle.loads(pickle.dumps(result))
    assert again == result and again.target.shape == (40, 3)
    assert repr(again).startswith("<dform.Result inverse model='exact'")


def solve_in_a_worker(b):
    return dform.forward(ellipse(60, 30), ellipse(45, b), fit_perimeter=True, resolution=30)


def test_results_come_back_from_worker_processes():
    with multiprocessing.get_context("spawn").Pool(2) as pool:
        results = pool.map(solve_in_a_worker, [40.4, 35.0])
    assert results == [solve_in_a_worker(40.4), solve_in_a_worker(35.0)]


def test_an_error_pickles_with_its_exit_code():
    with pytest.raises(dform.Error) as raised:
        dform.read_outline(os.path.join(SOURCE, "samples", "forward", "no-such-file.svg"))
    again = pickle.loads(pickle.dumps(raised.value))
    assert type(again) is dform.Error and again.exit_code == 3
    assert str(again) == str(raised.value)


def message_of(call):
    with pytest.raises(dform.Error) as raised:
        call()
    text = str(raised.value)
    assert not re.search(r"--[a-z]", text), text
    return raised.value.exit_code, text


def test_messages_name_the_keywords_of_forward():
    a, b = ellipse(60, 30), ellipse(45, 40.4)
    code, text = message_of(lambda: dform.forward(a, b, resolution=40))
    assert code == 4 and "(fit_perimeter scales piece B to match)" in text
    code, text = message_of(lambda: dform.forward(a, b, fit_perimeter=True, interior_edge=0.1))
    assert code == 2 and text.startswith("interior_edge must be a number between 0.25 and 8")
    code, text = message_of(lambda: dform.forward(a, b, fit_perimeter=True, join="inner,inner"))
    assert code == 4 and "join inner needs a piece with exactly one hole" in text
    code, text = message_of(lambda: dform.forward(a, b, holes_a=[ellipse(10, 10)[::-1]],
                                                  fit_perimeter=True))
    assert code == 4 and "choose it with join, e.g. join inner,inner)" in text
    square = np.array([[0, 0], [100, 0], [100, 100], [0, 100]], float)
    notch = np.array([[0, 0], [100, 0], [100, 40], [40, 40], [40, 100], [0, 100]], float)
    code, text = message_of(lambda: dform.forward(notch, square, resolution=40, model="exact"))
    assert code == 5 and "piece A and piece B: model exact: " in text
    flipped = dform.forward(a, b, fit_perimeter=True, resolution=30, flip=True, model="paper")
    assert flipped.model_reason == "asked for (model paper)"
    assert ("info", "piece B is zipped turned over (flip): its flat pattern is mirrored") \
        in flipped.messages


def test_messages_name_the_keywords_of_export(result, tmp_path):
    out = str(tmp_path / "out")
    for options, expected in (
            ({"sheet": "big"}, "sheet must look like 600x400mm"),
            ({"page": "B9"}, "page must be A4, Letter, A3, Tabloid"),
            ({"scale": "huge"}, "scale must be a number (0.8)"),
            ({"gate": "nope"}, 'gate: unknown gate "nope"')):
        code, text = message_of(lambda: result.export(out, **options))
        assert code == 2 and text.startswith(expected), options
    laser = result.export(out, page="A4")
    assert laser["export_error"].endswith("give its size with sheet WxHmm")
    printed = result.export(out, profile="print", sheet="600x400mm")
    assert "so sheet does not apply; choose the paper with page " in printed["export_error"]
    held = result.export(out, cutting_files=False)
    assert held["checks"][-1]["detail"] == "no export (export.cutting_files false)"
