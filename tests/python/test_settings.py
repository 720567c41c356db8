# SPDX-License-Identifier: GPL-3.0-or-later
"""The settings table from Python (dform._dform.setting_rows, pipeline/settings.h): every row of
dform.forward, dform.inverse and Result.export is a keyword argument that takes its default and
refuses a value out of its range or choices with a dform.Error (exit code 2) naming the keyword,
never a command-line flag; the type stubs list exactly the table's keywords; the docstrings list
every keyword with its default."""
import ast
import math
import os
import re

import pytest

import dform
from dform import _dform

FUNCTIONS = ("forward", "inverse", "export")
STUBS = os.path.join(os.path.dirname(dform.__file__), "__init__.pyi")


def keywords_of(function):
    return sorted({row["keyword"] for row in _dform.setting_rows(function)})


def call_with(function, keyword, value, row):
    """job_settings with one keyword (a weight as its entry of the dict `weights`)."""
    if row["weight"]:
        return _dform.job_settings(function, weights={row["weight"]: value})
    return _dform.job_settings(function, **{keyword: value})


def bad_value(row):
    if row["choices"]:
        return "no-such-choice"
    if row["range"] == "true or false":
        return "yes"
    if row["range"].startswith("a fraction"):
        return 1.5
    if row["key"] in ("export.sheet", "export.page", "export.scale"):
        return {"export.sheet": "big", "export.page": "B9", "export.scale": "huge"}[row["key"]]
    if row["range"] == "text":
        return ""
    match = re.match(r"(between|at least|above|in [\[(]) ?(-?[\d.e+]+)", row["range"])
    assert match, row
    low = float(match.group(2))
    return low if row["range"].startswith(("above", "in (")) else low - 1


def value_at(settings, key):
    head, _, rest = key.partition(".")
    inner = settings.get(head)
    return inner.get(rest) if rest and isinstance(inner, dict) else inner


@pytest.mark.parametrize("function", FUNCTIONS)
def test_every_row_takes_its_default_and_refuses_a_bad_value(function):
    rows = _dform.setting_rows(function)
    assert rows, function
    for row in rows:
        keyword = row["keyword"]
        taken = call_with(function, keyword, row["default"], row)
        if row["default"] is not None:
            got = value_at(taken, row["key"])
            assert got == row["default"] or (isinstance(got, float) and
                                              math.isclose(got, row["default"])), row
        with pytest.raises(dform.Error) as refused:
            call_with(function, keyword, bad_value(row), row)
        text = str(refused.value)
        assert refused.value.exit_code == 2, text
        named = "weights['{}']".format(row["weight"]) if row["weight"] else keyword
        assert text.startswith(named + " "), (row["key"], text)
        assert not re.search(r"--[a-z]", text), text


def test_an_unknown_keyword_is_refused_naming_the_settings():
    with pytest.raises(dform.Error) as refused:
        _dform.job_settings("forward", colour="red")
    assert refused.value.exit_code == 2 and "'colour'" in str(refused.value)
    assert "resolution" in str(refused.value)


def stub_keywords():
    """Each stubbed function's keyword-only arguments."""
    with open(STUBS, encoding="utf-8") as f:
        tree = ast.parse(f.read())
    found = {}
    for node in ast.walk(tree):
        if isinstance(node, ast.FunctionDef) and node.name in FUNCTIONS:
            found[node.name] = sorted(a.arg for a in node.args.kwonlyargs)
    return found


def test_the_stubs_list_the_tables_keywords():
    stubs = stub_keywords()
    own = {"forward": {"holes_a", "holes_b", "creases_a", "creases_b", "name_a", "name_b"},
           "inverse": {"name"}, "export": set()}
    for function in FUNCTIONS:
        assert sorted(set(stubs[function]) - own[function]) == keywords_of(function), function


def test_the_docstrings_list_every_keyword_with_its_default():
    for function, doc in (("forward", dform.forward.__doc__), ("inverse", dform.inverse.__doc__),
                          ("export", dform.Result.export.__doc__)):
        for row in _dform.setting_rows(function):
            if row["weight"]:
                assert "{}={}".format(row["weight"], row["default"]) in doc, row
            else:
                assert "    {}: ".format(row["keyword"]) in doc, row
