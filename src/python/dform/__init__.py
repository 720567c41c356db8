"""D-Forms: two flat pieces zipped along their boundaries, and the 3D shape they make.

dform.forward (two outlines -> their D-Form) and dform.inverse (a closed 3D seam curve -> the two
flat pieces) return a Result: numpy arrays and dicts that print, compare and pickle (for
multiprocessing and joblib), and a result folder written as the command line writes it
(docs/python.md). The solves run in the compiled dform._dform.
"""
import copy as _copy
import math as _math
import os as _os

import numpy as _np

# An installed package carries the templates (export profiles, gates, report) beside it; a build
# tree or the Debian package finds them as the command does ($DFORM_TEMPLATES, share/dform).
_TEMPLATES = _os.path.join(_os.path.dirname(__file__), "templates")
if "DFORM_TEMPLATES" not in _os.environ and _os.path.isdir(_TEMPLATES):
    _os.environ["DFORM_TEMPLATES"] = _TEMPLATES

from . import _dform  # noqa: E402  (after the templates are known)
from ._dform import Error, __version__, read_curve, read_outline  # noqa: E402

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

    def export(self, out_dir, **options):
        if self._run is None:
            name, args, kwargs = self._call
            self._run = getattr(_dform, name)(*args, **kwargs)
        return self._run.export(out_dir, **options)

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


def forward(outline_a, outline_b, **options):
    call = ("forward", _copy.deepcopy((outline_a, outline_b)), _copy.deepcopy(options))
    return Result(_dform.forward(outline_a, outline_b, **options), call)


def inverse(curve, **options):
    call = ("inverse", _copy.deepcopy((curve,)), _copy.deepcopy(options))
    return Result(_dform.inverse(curve, **options), call)


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


forward.__doc__ = """Two flat outlines (n, 2) in mm -> the D-Form they make (docs/python.md).
    holes_a, holes_b, creases_a, creases_b: lists of (n, 2) arrays; name_a, name_b: the pieces'
    names (default "piece A", "piece B"). The settings, as keyword arguments:
""" + _settings_doc("forward")
inverse.__doc__ = """A closed 3D seam curve (n, 3) in mm -> the two flat pieces that make it.
    name: the curve's name (default "curve"). The settings, as keyword arguments:
""" + _settings_doc("inverse")
Result.export.__doc__ = """Writes the result folder as `dform forward` does: meshes, report.json,
    report.html and, when the gate passes, the cutting files; returns the gate's verdict and
    checks. The export settings, as keyword arguments:
""" + _settings_doc("export")
