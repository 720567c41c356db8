#!/bin/bash
# SPDX-License-Identifier: GPL-3.0-or-later
# The Python package as a user installs it: `pip install --no-build-isolation .` into a virtual
# environment with Debian's packages (numpy, pytest, mypy), offline, reusing the CMake build (it
# builds the target dform_python there, nothing else), then the Python tests run against the
# installed package from a folder outside the source tree, without $DFORM_TEMPLATES (the package
# carries its templates) and without build/python on the path.
#   installed_package_test.sh BUILD_DIR SOURCE_DIR PYTHON
set -euo pipefail
build=$1 source=$2 python=$3
work=$(mktemp -d "${TMPDIR:-/tmp}/dform-pip-test.XXXXXX")
trap 'rm -rf "$work"' EXIT
fail() { echo "installed package test: $*" >&2; exit 1; }

"$python" -m venv --system-site-packages "$work/venv" || fail "python3 -m venv failed (python3-venv)"
(cd "$source" && DFORM_CMAKE_BUILD_DIR="$build" DFORM_PIP_BUILD_BASE="$work/pip-build" \
  CMAKE_BUILD_PARALLEL_LEVEL=2 "$work/venv/bin/python" -m pip install --no-build-isolation \
  --no-index --no-cache-dir --disable-pip-version-check .) > "$work/pip.log" 2>&1 ||
  fail "pip install failed: $(tail -5 "$work/pip.log")"
package=$("$work/venv/bin/python" -c 'import sysconfig; print(sysconfig.get_paths()["platlib"])')/dform
[ -f "$package/py.typed" ] && [ -f "$package/__init__.pyi" ] || fail "no py.typed or stubs in $package"
[ -f "$package/templates/gates/default.json" ] || fail "no templates in $package"
! compgen -G "$source/src/python/*.egg-info" > /dev/null ||
  fail "pip install left its egg-info in the source tree"
mkdir "$work/elsewhere"
cd "$work/elsewhere"
env -u DFORM_TEMPLATES -u PYTHONPATH DFORM_PACKAGE_DIR="$package" \
  "$work/venv/bin/python" -m pytest -q -p no:cacheprovider "$source/tests/python"
