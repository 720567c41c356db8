#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""The Python reference of dform: one HTML page made by pydoc from the package's docstrings (the
module's, Result's and every function's, the keywords and what each sets among them), installed
with the Debian package python3-dform and by cmake --install as
share/doc/python3-dform/dform.html.

    reference.py PACKAGE_PARENT OUT_HTML    (PACKAGE_PARENT: the folder holding dform/)

pydoc links each module to its file on this machine; those links are left out, as the page is
read where the module is installed, not where it was built.
"""
import pydoc
import re
import sys


def main():
    parent, out = sys.argv[1], sys.argv[2]
    sys.path.insert(0, parent)
    import dform  # noqa: E402  (from PACKAGE_PARENT)

    page = pydoc.HTMLDoc().page("dform " + dform.__version__, pydoc.HTMLDoc().docmodule(dform))
    # The file links: '<a href="file:/...">index</a><br><a href="file:/...">/.../dform/__init__.py</a>'.
    page = re.sub(r'<a href="file:[^"]*">[^<]*</a>(<br>)?', "", page)
    if "href=\"file:" in page or parent in page:
        sys.exit("reference.py: the page still names a file of the build: %s" % parent)
    with open(out, "w", encoding="utf-8") as f:
        f.write(page)


if __name__ == "__main__":
    main()
