# SPDX-License-Identifier: GPL-3.0-or-later
"""Builds the Python package dform (pyproject.toml): the Python part from src/python/dform, the
compiled dform._dform by CMake (the target dform_python only, Release), the templates as package
data. CMake configures a build folder of its own under build-pip/ (or $DFORM_PIP_BUILD_BASE, where
setuptools' own build and egg-info go too), or, when DFORM_CMAKE_BUILD_DIR names an existing dform
CMake build (absolute or relative to this folder), builds the target there and takes the module
from it. The version is the CMake project's. pip shows a build's own output only with -v, so the
build's progress also goes to the terminal pip runs in, as one line updated at each step."""
import os
import re
import shutil
import subprocess
import sys
import sysconfig

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

ROOT = os.path.dirname(os.path.abspath(__file__))
BUILD_BASE = os.environ.get("DFORM_PIP_BUILD_BASE") or os.path.join(ROOT, "build-pip")


def project_version():
    with open(os.path.join(ROOT, "CMakeLists.txt"), encoding="utf-8") as cmake_lists:
        found = re.search(r"project\(dform VERSION ([0-9][0-9.]*)", cmake_lists.read())
    if not found:
        sys.exit("dform: error: CMakeLists.txt: no 'project(dform VERSION x.y.z)'")
    return found.group(1)


# A step of the build as Make ("[ 42%] Building CXX object ...") or Ninja ("[12/80] ...") shows it.
STEP = re.compile(r"\[\s*(?:(\d+)%|(\d+)/(\d+))\] (.*)")


def progress_stream():
    """Where the build's progress goes: the terminal pip runs in (pip shows a build's own output
    only with -v), else nowhere but the build's output."""
    try:
        return open("/dev/tty", "w", encoding="utf-8")
    except OSError:
        return None


def run(command, progress=None):
    """Runs command, its output passed on line by line; with `progress`, each step CMake
    counts ("[ 42%] Building CXX object ...") is also shown there as one updated line."""
    print("dform: " + " ".join(command), flush=True)
    with subprocess.Popen(command, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                          errors="replace") as process:
        for line in process.stdout:
            sys.stdout.write(line)
            sys.stdout.flush()
            step = STEP.match(line)
            if progress and step:
                done = (int(step.group(1)) if step.group(1) else
                        100 * int(step.group(2)) // max(1, int(step.group(3))))
                progress.write("\rdform: building the C++ module, %3d %% %-60.60s"
                               % (done, step.group(4)))
                progress.flush()
    if progress:
        progress.write("\n")
        progress.flush()
    if process.returncode != 0:
        raise subprocess.CalledProcessError(process.returncode, command)


class CMakeBuild(build_ext):
    """build_ext for the one extension dform._dform, made by CMake rather than by setuptools."""

    def build_extension(self, ext):
        existing = os.environ.get("DFORM_CMAKE_BUILD_DIR")
        if existing:
            build_dir = os.path.join(ROOT, existing)
            if not os.path.isfile(os.path.join(build_dir, "CMakeCache.txt")):
                sys.exit("dform: error: DFORM_CMAKE_BUILD_DIR=%s: not a configured CMake build"
                         % existing)
        else:
            build_dir = os.path.join(os.path.abspath(self.build_temp), "cmake")
            run(["cmake", "-S", ROOT, "-B", build_dir, "-DCMAKE_BUILD_TYPE=Release",
                 "-DDFORM_BUILD_TESTS=OFF", "-DDFORM_BUILD_BENCH=OFF",
                 # no line tables: a wheel has no separate debug symbols to keep them in
                 "-DDFORM_DEBUG_INFO=OFF",
                 "-DDFORM_PYTHON3=" + os.path.realpath(sys.executable)])
        jobs = os.environ.get("CMAKE_BUILD_PARALLEL_LEVEL") or str(os.cpu_count() or 1)
        progress = progress_stream()
        try:
            run(["cmake", "--build", build_dir, "--target", "dform_python", "--parallel", jobs],
                progress)
        finally:
            if progress:
                progress.close()
        built = os.path.join(build_dir, "python", "dform",
                             "_dform" + sysconfig.get_config_var("EXT_SUFFIX"))
        if not os.path.isfile(built):
            sys.exit("dform: error: %s: no module for this Python (%s) in the CMake build"
                     % (built, sys.version.split()[0]))
        target = self.get_ext_fullpath(ext.name)
        os.makedirs(os.path.dirname(target), exist_ok=True)
        shutil.copyfile(built, target)
        # The export profiles, gates and report templates, found by dform/__init__.py.
        templates = os.path.join(os.path.dirname(target), "templates")
        shutil.rmtree(templates, ignore_errors=True)
        shutil.copytree(os.path.join(ROOT, "templates"), templates)


os.makedirs(BUILD_BASE, exist_ok=True)
setup(
    version=project_version(),
    packages=["dform"],
    package_dir={"": "src/python"},
    package_data={"dform": ["py.typed", "*.pyi"]},
    ext_modules=[Extension("dform._dform", sources=[])],
    cmdclass={"build_ext": CMakeBuild},
    options={"build": {"build_base": BUILD_BASE}, "egg_info": {"egg_base": BUILD_BASE}},
    zip_safe=False,
)
