# SPDX-License-Identifier: GPL-3.0-or-later
"""The package's interface as help(), an IDE and a program see it: forward, inverse and
Result.export have explicit keyword signatures (inspect.signature) whose names and defaults are
the compiled module's, a docstring naming every keyword, a mistyped keyword is a TypeError naming
it, dform.Error is a RuntimeError (as the stubs say), and importing dform changes no environment
variable: the templates beside an installed package are found without $DFORM_TEMPLATES."""
import ast
import inspect
import os
import re
import shutil
import subprocess
import sys

import numpy as np
import pytest
from test_package import ellipse

import dform

PACKAGE_PARENT = os.path.dirname(os.path.dirname(dform.__file__))


@pytest.fixture(scope="module")
def result():
    return dform.forward(ellipse(60, 30), ellipse(45, 40.4), fit_perimeter=True, resolution=24)


def python_defaults(function):
    parameters = inspect.signature(function).parameters.values()
    return {p.name: p.default for p in parameters if p.kind is inspect.Parameter.KEYWORD_ONLY}


# The keywords that are no settings (the inputs' extra arrays and names), as the functions take them.
NOT_SETTINGS = {
    "forward": {"holes_a": (), "holes_b": (), "creases_a": (), "creases_b": (),
                "name_a": "piece A", "name_b": "piece B"},
    "inverse": {"name": "curve"},
    "export": {},
}


def table_defaults(function):
    """keyword -> default of each row of the settings table a function takes: the row's default,
    None where the row has no default of its own (its `unset` says what then), and None for the
    weights dict."""
    defaults = dict(NOT_SETTINGS[function])
    for row in dform._dform.setting_rows(function):
        key = "weights" if row["weight"] else row["keyword"]
        defaults[key] = None if row["weight"] or row["unset"] else row["default"]
    return defaults


@pytest.mark.parametrize("name,function", [("forward", dform.forward), ("inverse", dform.inverse),
                                           ("export", dform.Result.export)])
def test_the_keywords_and_defaults_are_the_settings_tables(name, function):
    python, table = python_defaults(function), table_defaults(name)
    assert len(table) >= 7 and list(python) == list(table)
    for keyword in python:
        assert type(python[keyword]) is type(table[keyword]), keyword
        assert python[keyword] == table[keyword], keyword


def test_the_compiled_module_takes_the_keywords_that_are_no_settings():
    """The pybind11 signature line of the compiled forward and inverse names exactly the
    keywords the package adds to the table's."""
    for name in ("forward", "inverse"):
        line = getattr(dform._dform, name).__doc__.splitlines()[0].split(" -> ")[0]
        arguments = ast.parse("def " + line + ": pass").body[0].args
        assert [a.arg for a in arguments.kwonlyargs] == list(NOT_SETTINGS[name]), name


def test_the_positional_parameters_are_the_inputs_only():
    def positional(function):
        return [p.name for p in inspect.signature(function).parameters.values()
                if p.kind is inspect.Parameter.POSITIONAL_OR_KEYWORD]
    assert positional(dform.forward) == ["outline_a", "outline_b"]
    assert positional(dform.inverse) == ["curve"]
    assert positional(dform.Result.export) == ["self", "out_dir"]
    assert not any(p.kind is inspect.Parameter.VAR_KEYWORD
                   for f in (dform.forward, dform.inverse, dform.Result.export)
                   for p in inspect.signature(f).parameters.values())


@pytest.mark.parametrize("function", [dform.forward, dform.inverse, dform.Result.export])
def test_the_docstring_names_every_keyword(function):
    doc = inspect.getdoc(function)
    listed = set(re.findall(r"^(\w+(?:, \w+)?): ", doc, re.MULTILINE))
    names = {name for entry in listed for name in entry.split(", ")}
    parameters = set(inspect.signature(function).parameters) - {"self"}
    assert names == parameters, names ^ parameters
    assert "docs/" not in doc  # the repository's docs are not where the package is installed


def test_the_docstring_is_the_settings_tables_help():
    doc = inspect.getdoc(dform.forward)
    for row in dform._dform.setting_rows("forward"):
        if not row["weight"]:
            assert "{}: {}".format(row["keyword"], row["help"]) in doc, row["keyword"]


def test_a_mistyped_keyword_is_a_type_error_naming_it(result, tmp_path):
    with pytest.raises(TypeError, match=r"forward\(\) got an unexpected keyword argument 'resolutoin'"):
        dform.forward(ellipse(60, 30), ellipse(45, 40.4), resolutoin=24)
    with pytest.raises(TypeError, match=r"inverse\(\) got an unexpected keyword argument 'weight'"):
        dform.inverse(np.zeros((10, 3)), weight={})
    with pytest.raises(TypeError, match=r"export\(\) got an unexpected keyword argument 'profle'"):
        result.export(str(tmp_path / "out"), profle="print")
    assert not (tmp_path / "out").exists()


def test_the_defaults_give_the_same_run_as_the_keywords_spelt_out():
    """Every keyword given its signature's default gives the run the call without them gives."""
    a, b = ellipse(60, 30), ellipse(45, 40.4)
    plain = dform.forward(a, b, fit_perimeter=True, resolution=24)
    spelt = dict(python_defaults(dform.forward), fit_perimeter=True, resolution=24)
    assert len(spelt) > 10
    assert plain == dform.forward(a, b, **spelt)


def test_error_is_a_runtime_error_of_the_package():
    assert issubclass(dform.Error, RuntimeError) and dform.Error.__module__ == "dform"
    with pytest.raises(RuntimeError) as raised:
        dform.read_outline("/nonexistent/outline.svg")
    assert type(raised.value) is dform.Error and raised.value.exit_code == 3
    with open(os.path.join(os.path.dirname(dform.__file__), "__init__.pyi"), encoding="utf-8") as f:
        assert "class Error(RuntimeError):" in f.read()


def fresh_python(code, **env):
    """Runs code in a new interpreter that imports dform from the package under test."""
    environment = {k: v for k, v in os.environ.items() if k != "DFORM_TEMPLATES"}
    environment.update(PYTHONPATH=PACKAGE_PARENT, **env)
    return subprocess.run([sys.executable, "-c", code], env=environment, capture_output=True,
                          text=True, check=False)


def test_importing_dform_sets_no_environment_variable():
    shown = fresh_python("import os, subprocess; before = dict(os.environ); import dform; "
                         "assert dict(os.environ) == before, set(os.environ) ^ set(before); "
                         "print(subprocess.run(['env'], capture_output=True, text=True).stdout)")
    assert shown.returncode == 0, shown.stderr
    assert "DFORM_TEMPLATES" not in shown.stdout


def test_an_installed_package_reads_the_templates_beside_it(tmp_path):
    """A copy of the package whose templates lack the print profile: export(profile="print")
    fails there, naming the profile, so the templates read are the copy's own."""
    templates = os.path.join(os.path.dirname(dform.__file__), "templates")
    if not os.path.isdir(templates):
        pytest.skip("the package under test carries no templates (a build tree's package)")
    copy = tmp_path / "site" / "dform"
    shutil.copytree(os.path.dirname(dform.__file__), copy,
                    ignore=shutil.ignore_patterns("__pycache__"))
    os.remove(copy / "templates" / "profiles" / "print.json")
    code = ("import dform, math, numpy as np, sys\n"
            "t = np.linspace(0, 2 * math.pi, 200, endpoint=False)\n"
            "e = lambda a, b: np.column_stack([a * np.cos(t), b * np.sin(t)])\n"
            "r = dform.forward(e(60, 30), e(45, 40.4), fit_perimeter=True, resolution=24)\n"
            "assert r.export(sys.argv[1] + '/laser')['cutting_files']\n"
            "try:\n    r.export(sys.argv[1] + '/print', profile='print')\n"
            "except dform.Error as e:\n    print(e.exit_code, e)\n")
    environment = {k: v for k, v in os.environ.items() if k != "DFORM_TEMPLATES"}
    environment["PYTHONPATH"] = str(tmp_path / "site")
    shown = subprocess.run([sys.executable, "-c", code, str(tmp_path)], env=environment,
                           capture_output=True, text=True, check=False)
    assert shown.returncode == 0, shown.stderr
    assert shown.stdout.startswith("2 ") and "print" in shown.stdout, shown.stdout
