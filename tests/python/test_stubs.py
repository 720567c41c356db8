# SPDX-License-Identifier: GPL-3.0-or-later
"""The type stubs (dform/__init__.pyi) against the package under test: mypy's stubtest checks
every public name, signature and type where mypy is installed (scripts/install-deps installs
python3-mypy); without it, the stubs must name exactly the package's public names."""
import ast
import importlib.util
import os
import subprocess
import sys

import pytest

import dform

STUBS = os.path.join(os.path.dirname(dform.__file__), "__init__.pyi")


def public_names_of_the_stubs():
    with open(STUBS, encoding="utf-8") as stubs:
        tree = ast.parse(stubs.read())
    names = set()
    for node in tree.body:
        if isinstance(node, (ast.FunctionDef, ast.ClassDef)):
            names.add(node.name)
        elif isinstance(node, (ast.AnnAssign, ast.Assign)):
            targets = [node.target] if isinstance(node, ast.AnnAssign) else node.targets
            names.update(t.id for t in targets if isinstance(t, ast.Name))
    return {name for name in names if not name.startswith("_") or name == "__version__"}


def test_the_stubs_name_every_public_name_and_no_other():
    assert public_names_of_the_stubs() == set(dform.__all__)
    assert all(hasattr(dform, name) for name in dform.__all__)
    public = {name for name in dir(dform) if not name.startswith("_")}
    assert public == set(dform.__all__) - {"__version__"}


@pytest.mark.skipif(importlib.util.find_spec("mypy") is None, reason="mypy is not installed")
def test_stubtest_finds_the_stubs_true_to_the_module():
    package_parent = os.path.dirname(os.path.dirname(dform.__file__))
    env = dict(os.environ, PYTHONPATH=package_parent, MYPY_CACHE_DIR=os.devnull)
    done = subprocess.run([sys.executable, "-m", "mypy.stubtest", "dform"], env=env,
                          capture_output=True, text=True, cwd=package_parent)
    assert done.returncode == 0, done.stdout + done.stderr
