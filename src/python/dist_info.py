#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""The dist-info folder of the Python package dform as cmake --install and the Debian package
python3-dform install it beside the package, so that importlib.metadata and pip see the installed
dform with its version, licence and requirements (the same metadata pyproject.toml gives pip).

    dist_info.py PYPROJECT VERSION SITE_DIR    writes SITE_DIR/dform-VERSION.dist-info/

RECORD lists every installed file with its SHA-256 and size, but the compiled module's: the
Debian packaging strips its debug symbols off after this is written, so its hash is left empty,
as PEP 376 allows.
"""
import base64
import hashlib
import os
import sys
import tomllib


def metadata(project, version):
    lines = ["Metadata-Version: 2.1", "Name: " + project["name"], "Version: " + version,
             "Summary: " + project["description"],
             "License: " + project["license"]["text"]]
    for author in project.get("authors", []):
        lines.append("Author-email: %s <%s>" % (author["name"], author["email"]))
    lines.append("Requires-Python: " + project["requires-python"])
    lines += ["Requires-Dist: " + requirement for requirement in project["dependencies"]]
    lines += ["Classifier: " + classifier for classifier in project["classifiers"]]
    return "\n".join(lines) + "\n"


def record_line(site, path, hashed):
    relative = os.path.relpath(path, site)
    if not hashed:
        return relative + ",,"
    with open(path, "rb") as f:
        data = f.read()
    digest = base64.urlsafe_b64encode(hashlib.sha256(data).digest()).rstrip(b"=").decode()
    return "%s,sha256=%s,%d" % (relative, digest, len(data))


def main():
    pyproject, version, site = sys.argv[1:4]
    with open(pyproject, "rb") as f:
        project = tomllib.load(f)["project"]
    info = os.path.join(site, "%s-%s.dist-info" % (project["name"], version))
    os.makedirs(info, exist_ok=True)
    with open(os.path.join(info, "METADATA"), "w", encoding="utf-8") as f:
        f.write(metadata(project, version))
    with open(os.path.join(info, "top_level.txt"), "w", encoding="utf-8") as f:
        f.write("dform\n")
    package = os.path.join(site, "dform")
    lines = []
    for name in sorted(os.listdir(package)):
        path = os.path.join(package, name)
        if os.path.isfile(path) and not name.endswith(".pyc"):
            lines.append(record_line(site, path, not name.endswith(".so")))
    for name in ("METADATA", "top_level.txt"):
        lines.append(record_line(site, os.path.join(info, name), True))
    lines.append(os.path.relpath(os.path.join(info, "RECORD"), site) + ",,")
    with open(os.path.join(info, "RECORD"), "w", encoding="utf-8") as f:
        f.write("\n".join(lines) + "\n")


if __name__ == "__main__":
    main()
