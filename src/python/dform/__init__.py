# SPDX-License-Identifier: GPL-3.0-or-later
"""D-Forms: two flat pieces zipped along their boundaries, and the 3D shape they make.

dform.forward (two outlines -> their D-Form) and dform.inverse (a closed 3D seam curve -> the two
flat pieces) return a Result: numpy arrays and dicts that print, compare and pickle (for
multiprocessing and joblib), and a result folder written as the command line writes it
(help(dform.forward), help(dform.Result.export); python.md in the docs of the Debian package
python3-dform). Every problem raises dform.Error, a RuntimeError whose exit_code is the command
line's. The solves run in the compiled dform._dform.
"""
import copy as _copy
import inspect as _inspect
import math as _math

import numpy as _np

# The templates (export profiles, gates, report) are found by the compiled module as the command
# finds them, the folder `templates` beside the module first (a pip-installed package carries
# it); the environment is left as it was, so programs started from Python inherit no setting.
from . import _dform
from ._dform import Error, __version__, read_curve, read_outline

__all__ = ["Error", "Result", "__version__", "forward", "inverse", "read_curve", "read_outline"]


def _same(x, y):
    """Equal values, arrays element by element and NaN equal to NaN (a figure may be NaN)."""
    if isinstance(x, _np.ndarray) or isinstance(y, _np.ndarray):
        return (isinstance(x, _np.ndarray) and isinstance(y, _np.ndarray) and x.shape == y.shape
                and x.dtype == y.dtype and _np.array_equal(x, y, equal_nan=x.dtype.kind == "f"))
    if isinstance(x, dict) and isinstance(y, dict):
        return x.keys() == y.keys() and all(_same(x[k], y[k]) for k in x)
    if isinstance(x, (list, tuple)) and isinstance(y, (list, tuple)):
        return type(x) is type(y) and len(x) == len(y) and all(map(_same, x, y))
    if isinstance(x, float) and isinstance(y, float) and _math.isnan(x) and _math.isnan(y):
        return True
    return type(x) is type(y) and x == y


class Result:
    """A solved D-Form: its model, pieces, figures and messages, and export() of its folder.

    Its data are plain numpy arrays, dicts and strings, read once from the solve. It pickles to
    those data and the call that made it; an unpickled result has the same data and compares
    equal, and its export() solves the same call again (the same answer) to write the folder.
    """

    _FIELDS = ("model", "model_reason", "piece_a", "piece_b", "figures", "messages", "target")

    def __init__(self, run, call):
        self._run = run
        self._call = call  # (function name, positional arguments, keyword arguments)
        self._data = {name: getattr(run, name) for name in self._FIELDS}

    model = property(lambda self: self._data["model"],
                     doc="'exact', 'paper' or 'general': which model made the shape")
    model_reason = property(lambda self: self._data["model_reason"],
                            doc="why that model: its conditions met, or which failed")
    piece_a = property(lambda self: self._data["piece_a"],
                       doc="dict: name, flat (n, 2) mm, shape (n, 3) mm, faces (m, 3), seam (k,)")
    piece_b = property(lambda self: self._data["piece_b"], doc="piece B, as piece_a")
    figures = property(lambda self: self._data["figures"],
                       doc="the figures report.json records under 'metrics'")
    messages = property(lambda self: self._data["messages"],
                        doc="[(level, text)] as the run said them")
    target = property(lambda self: self._data["target"],
                      doc="inverse: the resampled curve (n, 3) the seam follows, else None")

    def export(self, out_dir, **settings):
        settings = _given(Result.export, (self, out_dir), settings)
        if self._run is None:
            name, args, kwargs = self._call
            self._run = getattr(_dform, name)(*args, **kwargs)
        return self._run.export(out_dir, **settings)

    def __getstate__(self):
        return {"data": self._data, "call": self._call}

    def __setstate__(self, state):
        self._run = None
        self._data = state["data"]
        self._call = state["call"]

    def __eq__(self, other):
        if not isinstance(other, Result):
            return NotImplemented
        return _same(self._data, other._data)

    __hash__ = None  # mutable contents (numpy arrays): not hashable

    def __repr__(self):
        pieces = ", ".join(
            "{}: {} vertices, {} triangles".format(p["name"], len(p["flat"]), len(p["faces"]))
            for p in (self.piece_a, self.piece_b))
        figures = self.figures
        shown = ["{}={:.4g}".format(k, figures[k]) for k in ("L_max", "seam_gap_mm")
                 if isinstance(figures.get(k), (int, float))]
        kind = "inverse" if self.target is not None else "forward"
        return "<dform.Result {} model={!r} ({}){}>".format(
            kind, self.model, pieces, "; " + ", ".join(shown) if shown else "")


def forward(outline_a, outline_b, **settings):
    options = _given(forward, (outline_a, outline_b), settings)
    call = ("forward", _copy.deepcopy((outline_a, outline_b)), _copy.deepcopy(options))
    return Result(_dform.forward(outline_a, outline_b, **options), call)


def inverse(curve, **settings):
    options = _given(inverse, (curve,), settings)
    call = ("inverse", _copy.deepcopy((curve,)), _copy.deepcopy(options))
    return Result(_dform.inverse(curve, **options), call)


def _given(function, arguments, keywords):
    """The keywords of a call checked against `function`'s signature (a mistyped one is Python's
    TypeError naming it), those left at None (not given: the setting's own rule) dropped."""
    try:
        _inspect.signature(function).bind(*arguments, **keywords)
    except TypeError as refused:
        raise TypeError("{}() {}".format(function.__name__, refused)) from None
    return {k: v for k, v in keywords.items() if v is not None}


def _signature(function, inputs, named):
    """The signature of `function` ("forward", "inverse", "export"): its inputs, the keywords
    `named` (name, default) that are no settings, then one keyword per row of the settings table
    (dform._dform.setting_rows), in the table's order, with the table's default, or None where
    the setting has no default of its own (row["unset"] says what then); the weights' rows are
    one keyword, `weights`, a dict of term weights (default None: each term's own)."""
    keyword = _inspect.Parameter.KEYWORD_ONLY
    parameters = [_inspect.Parameter(name, _inspect.Parameter.POSITIONAL_OR_KEYWORD)
                  for name in inputs]
    parameters += [_inspect.Parameter(name, keyword, default=default) for name, default in named]
    for row in _dform.setting_rows(function):
        name = "weights" if row["weight"] else row["keyword"]
        if name not in [p.name for p in parameters]:
            default = None if row["weight"] or row["unset"] else row["default"]
            parameters.append(_inspect.Parameter(name, keyword, default=default))
    return _inspect.Signature(parameters)


def _settings_doc(function):
    """The keyword arguments of `function` as the settings table (dform._dform.setting_rows) has
    them: each with its default (or what it is when not given), range and help."""
    lines, weights = [], []
    for row in _dform.setting_rows(function):
        if row["weight"]:
            weights.append("{}={}".format(row["weight"], row["default"]))
            continue
        default = row["unset"] if row["unset"] else repr(row["default"])
        unit = " ({})".format(row["unit"]) if row["unit"] else ""
        lines.append("    {}: {}{}; {}; default {}".format(
            row["keyword"], row["help"], unit, row["range"], default))
    if weights:
        lines.append("    weights: a dict of term weights, each >= 0; defaults " + ", ".join(weights))
    return "\n".join(lines)


# Each function's keywords are named in its signature (inspect.signature, help(), an IDE) and
# listed in its docstring, both read from the settings table the command line and job files use.
forward.__signature__ = _signature("forward", ("outline_a", "outline_b"), (
    ("holes_a", ()), ("holes_b", ()), ("creases_a", ()), ("creases_b", ()),
    ("name_a", "piece A"), ("name_b", "piece B")))
inverse.__signature__ = _signature("inverse", ("curve",), (("name", "curve"),))
Result.export.__signature__ = _signature("export", ("self", "out_dir"), ())
forward.__doc__ = """Two flat outlines -> the D-Form they make, as a Result (`dform forward`).

    outline_a, outline_b: arrays (n, 2) of the pieces' outlines in mm, either orientation. A bad
    array, an outline that crosses itself or perimeters that differ (see fit_perimeter) raise
    dform.Error with the command's exit code (2 usage, 4 invalid input, 5 the solve failed); a
    mistyped keyword is a TypeError naming it. Keywords:
    holes_a, holes_b: holes inside each piece, a list of (k, 2) arrays in mm; default none
    creases_a, creases_b: fold lines from boundary to boundary, a list of (k, 2) arrays in mm
    name_a, name_b: the pieces' names in messages and report.json; default "piece A", "piece B"
""" + _settings_doc("forward")
inverse.__doc__ = """A closed 3D seam curve -> the two flat pieces that make it, as a Result.

    curve: an array (n, 3) of points in mm, closed (the last point joins the first). A bad array
    or a curve the pieces cannot follow raises dform.Error with the command's exit code; a
    mistyped keyword is a TypeError naming it. Keywords:
    name: the curve's name in messages and report.json; default "curve"
""" + _settings_doc("inverse")
Result.export.__doc__ = """Writes the result folder as `dform forward -o` does, as one transaction.

    It holds the meshes, report.json, report.html and, unless the gate fails, the cutting files.
    Returns {"folder", "gate_passed" (None with gate "none"), "checks" (name, value, limit,
    verdict, detail each), "cutting_files" (whether they were written) and, when the export
    failed, "export_error"}. A bad value raises dform.Error (exit_code 2); a mistyped keyword is a
    TypeError naming it.
    out_dir: the result folder, created or replaced whole
""" + _settings_doc("export")
