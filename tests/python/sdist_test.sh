#!/bin/bash
# SPDX-License-Identifier: GPL-3.0-or-later
# The Python package's sdist as a user gets it: `python3 -m build --sdist --no-isolation` from the
# source tree, then `pip install dform-VERSION.tar.gz` into a clean virtual environment (Debian's
# numpy and pytest from the system, nothing else, offline), which compiles the module from the
# sdist alone (its own CMake build of the libraries and the module: minutes), then the Python
# tests from a folder outside the source tree against the installed package, without
# $DFORM_TEMPLATES. The sdist holds what the build needs and nothing of a build folder.
#   sdist_test.sh SOURCE_DIR PYTHON
set -euo pipefail
source=$1 python=$2
work=$(mktemp -d "${TMPDIR:-/tmp}/dform-sdist-test.XXXXXX")
trap 'rm -rf "$work"' EXIT
fail() { echo "sdist test: $*" >&2; exit 1; }

version=$(sed -n 's/^project(dform VERSION \([0-9.]*\).*/\1/p' "$source/CMakeLists.txt")
(cd "$source" && DFORM_PIP_BUILD_BASE="$work/sdist-build" "$python" -m build --sdist --no-isolation \
  --outdir "$work/dist" .) > "$work/build.log" 2>&1 || fail "python3 -m build --sdist failed: $(tail -5 "$work/build.log")"
sdist=$work/dist/dform-$version.tar.gz
[ -f "$sdist" ] || fail "no dform-$version.tar.gz: $(ls "$work/dist")"
contents=$(tar -tzf "$sdist" | sed "s|^dform-$version/||")
for file in CMakeLists.txt LICENSE README.md setup.py pyproject.toml MANIFEST.in src/CMakeLists.txt \
  src/pipeline/run.cpp include/dform/pipeline/run.h src/python/dform_module.cpp src/python/dform/__init__.py \
  src/python/dform/__init__.pyi templates/gates/default.json packaging/debian.cmake PKG-INFO; do
  grep -qx -- "$file" <<< "$contents" || fail "the sdist has no $file"
done
if grep -Eq '^(build|build-pip|out)[^/]*/|__pycache__|\.pyc$|\.so$|egg-info/' <<< "$contents"; then
  fail "the sdist holds build output: $(grep -E '^(build|build-pip|out)[^/]*/|__pycache__|\.pyc$|\.so$|egg-info/' <<< "$contents" | head -3)"
fi
# Read whole before grep -q, which stops at the first match (and would end tar with SIGPIPE,
# a failure under pipefail).
info=$(tar -xzOf "$sdist" "dform-$version/PKG-INFO")
grep -qx 'License: GPL-3.0-or-later' <<< "$info" || fail "the sdist's PKG-INFO has no licence"

"$python" -m venv --system-site-packages "$work/venv" || fail "python3 -m venv failed (python3-venv)"
! "$work/venv/bin/python" -c 'import dform' 2> /dev/null || fail "the clean environment already has a dform"
mkdir "$work/elsewhere"
cd "$work/elsewhere"
# pip unpacks the sdist under $work/tmp (a new name each time); ccache, with paths under $work taken
# relative to the build folder, finds a previous run's objects again.
mkdir "$work/tmp"
TMPDIR="$work/tmp" CCACHE_BASEDIR="$work" CCACHE_NOHASHDIR=true CMAKE_BUILD_PARALLEL_LEVEL=2 \
  "$work/venv/bin/python" -m pip install --no-build-isolation --no-index \
  --no-cache-dir --disable-pip-version-check "$sdist" > "$work/pip.log" 2>&1 ||
  fail "pip install of the sdist failed: $(tail -5 "$work/pip.log")"
package=$("$work/venv/bin/python" -c 'import sysconfig; print(sysconfig.get_paths()["platlib"])')/dform
[ -f "$package/templates/gates/default.json" ] || fail "no templates in the installed $package"
env -u DFORM_TEMPLATES -u PYTHONPATH DFORM_PACKAGE_DIR="$package" \
  "$work/venv/bin/python" -m pytest -q -p no:cacheprovider "$source/tests/python"
