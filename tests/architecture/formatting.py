#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""The C++ sources of src/, include/ and tests/ are formatted as .clang-format says (Google style, 100
columns): lists every file clang-format would change and exits 1, else 0. Fix with
`clang-format -i FILE`.

    formatting.py CLANG_FORMAT ROOT
    formatting.py CLANG_FORMAT --self-test   (a planted misformatted file must be found)
"""
import os
import shutil
import subprocess
import sys
import tempfile

FOLDERS = ("src", "include", "tests")


def sources(root):
    for folder in FOLDERS:
        for base, _, files in os.walk(os.path.join(root, folder)):
            for name in sorted(files):
                if name.endswith((".h", ".hpp", ".cpp")):
                    yield os.path.join(base, name)


def misformatted(clang_format, root):
    """The files clang-format would change: one run over all of them, its warnings name each."""
    style = "--style=file:" + os.path.join(root, ".clang-format")
    paths = list(sources(root))
    run = subprocess.run([clang_format, style, "--dry-run", "--Werror"] + paths,
                         capture_output=True, text=True)
    named = {line.split(":", 1)[0] for line in run.stderr.splitlines() if ": error: " in line}
    found = sorted(os.path.relpath(path, root) for path in paths if path in named)
    if run.returncode != 0 and not found:
        raise SystemExit(f"clang-format failed: {run.stderr.strip()}")
    return found


def self_test(clang_format, project_root):
    with tempfile.TemporaryDirectory() as root:
        shutil.copy(os.path.join(project_root, ".clang-format"), root)
        os.makedirs(os.path.join(root, "src", "core"))
        path = os.path.join(root, "src", "core", "sum.cpp")
        with open(path, "w") as f:
            f.write("int sum(int a, int b) { return a + b; }\n")
        if misformatted(clang_format, root):
            print("self-test: a formatted file was flagged")
            return 1
        with open(path, "w") as f:
            f.write("int sum(int a,int b){return a+b;}\n")
        if misformatted(clang_format, root) != ["src/core/sum.cpp"]:
            print("self-test: a misformatted file was not found")
            return 1
    print("self-test passed")
    return 0


def main():
    root = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    if len(sys.argv) == 3 and sys.argv[2] == "--self-test":
        return self_test(sys.argv[1], root)
    if len(sys.argv) != 3:
        print(__doc__)
        return 2
    found = misformatted(sys.argv[1], sys.argv[2])
    for path in found:
        print(f"{path}: not formatted as .clang-format says (clang-format -i {path})")
    return 1 if found else 0


if __name__ == "__main__":
    sys.exit(main())
