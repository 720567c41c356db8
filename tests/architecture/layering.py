#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""The modules of src/ depend one way (docs/architecture.md): each may include only the modules
below it, and the command line links the pipeline alone. A module's public headers are in
include/dform/<module>/ (beside src/), included as an installed project reads them,
"dform/<module>/<header>.h"; its private headers are beside its sources, included by their bare
names from the module's own files only. Lists every #include of a module a file may not use, of
another module's private header, of a header that is not there, or written without the dform/
prefix (or every module the CLI links besides the pipeline) and exits 1, else 0.

    layering.py SRC_DIR    (its public headers in SRC_DIR/../include/dform)
    layering.py --cli-links "LINK;LIBRARIES"   (the dform target's LINK_LIBRARIES property)
    layering.py --core-copies SRC_DIR   (export defines none of core/polyline.h's 2D helpers again)
    layering.py --docs SRC_DIR DOCS_DIR   (docs/architecture.md's table and docs/conventions.md's
                                          module list say what ALLOWED and src/ say; each
                                          src/<module>/CMakeLists.txt links only what ALLOWED lets
                                          its module include)
    layering.py --self-test   (a planted upward include or link must be found, a clean tree pass)
"""
import os
import re
import sys
import tempfile

# What each module may include besides itself: the data flow io -> meshing -> model (the D-Form
# solve on a generic solver) -> forward/inverse, neither using the other -> validate ->
# export/report -> pipeline (runs: one, a sweep's, a batch's)
# -> cli, studio and the Python module, with core under all. The cli sees the pipeline, the
# studio (which it starts) and core only;
# the Python module reads outlines and curves given as arrays as io reads their files.
ALLOWED = {
    "core": set(),
    "solver": {"core"},
    "io": {"core"},
    "meshing": {"core"},
    "exact": {"core"},
    "ruled": {"core", "solver", "exact"},
    "model": {"core", "solver", "meshing", "exact", "ruled"},
    "forward": {"core", "solver", "meshing", "exact", "ruled", "model"},
    "inverse": {"core", "solver", "meshing", "exact", "model"},
    "validate": {"core", "exact"},
    "export": {"core", "validate"},
    "report": {"core", "validate"},
    "pipeline": {"core", "io", "meshing", "solver", "exact", "ruled", "model", "forward", "inverse",
                 "validate", "export", "report"},
    "cli": {"core", "pipeline", "studio"},
    "python": {"core", "io", "pipeline"},
    # The studio reads uploads as io reads files, runs them through the pipeline and judges the
    # result in memory with validate's gate, as the pipeline does for a written result.
    "studio": {"core", "io", "pipeline", "validate"},
}

INCLUDE = re.compile(r'^\s*#\s*include\s+"dform/([a-z_]+)/([^"]+)"')
UNPREFIXED = re.compile(r'^\s*#\s*include\s+[<"](' + "|".join(ALLOWED) + r')/')
PRIVATE = re.compile(r'^\s*#\s*include\s+"([^"/]+)"')


def public_folder(src):
    """include/dform, beside src/: the public headers, one folder per module."""
    return os.path.join(os.path.dirname(os.path.abspath(src)), "include", "dform")


def module_files(src, module):
    """(path, public) for every C++ file of `module`: its sources and private headers in src/,
    its public headers in include/dform/."""
    for folder, public in ((os.path.join(src, module), False),
                           (os.path.join(public_folder(src), module), True)):
        for root, _, files in os.walk(folder):
            for name in sorted(files):
                if name.endswith((".h", ".hpp", ".cpp")):
                    yield os.path.join(root, name), public


def include_problems(src, module, path, public, line):
    """What is wrong with one line's #include in a file of `module` (None when nothing)."""
    bare = UNPREFIXED.match(line)
    if bare:
        return f"includes {bare.group(1)}/ without the dform/ prefix"
    m = INCLUDE.match(line)
    if m:
        if m.group(1) != module and m.group(1) not in ALLOWED[module]:
            return (f"{module} includes {m.group(1)}/, which it may not (allowed: "
                    f"{', '.join(sorted(ALLOWED[module])) or 'nothing'})")
        if not os.path.isfile(os.path.join(public_folder(src), m.group(1), m.group(2))):
            private = os.path.isfile(os.path.join(src, m.group(1), m.group(2)))
            return (f"includes dform/{m.group(1)}/{m.group(2)}, which is "
                    + ("a private header of " + m.group(1) if private else "not there")
                    + f" (public headers are in include/dform/{m.group(1)}/)")
        return None
    m = PRIVATE.match(line)
    if m:
        if public:
            return f"a public header includes the private header {m.group(1)}"
        if not os.path.isfile(os.path.join(os.path.dirname(path), m.group(1))):
            return f"includes {m.group(1)}, which is not a private header of {module}"
    return None


def violations(src):
    found = []
    include = public_folder(src)
    for module in sorted(set(os.listdir(src)) | set(os.listdir(include) if os.path.isdir(include) else [])):
        if not os.path.isdir(os.path.join(src, module)) and not os.path.isdir(os.path.join(include, module)):
            continue
        if module not in ALLOWED:
            found.append(f"{module}/: a module the layering does not know (add it to ALLOWED)")
            continue
        for path, public in module_files(src, module):
            shown = os.path.relpath(path, os.path.dirname(os.path.dirname(include)) if public else src)
            if public and path.endswith(".cpp"):
                found.append(f"{shown}: a source file among the public headers")
            if public and os.path.isfile(os.path.join(src, module, os.path.basename(path))):
                found.append(f"{shown}: a private header of the same name is in src/{module}/")
            with open(path, encoding="utf-8") as f:
                for number, line in enumerate(f, 1):
                    problem = include_problems(src, module, path, public, line)
                    if problem:
                        found.append(f"{shown}:{number}: {problem}")
    return found


# The CLI's own targets may link these besides third-party libraries: the pipeline (which brings
# core), the studio (`dform studio`) and the warning flags.
CLI_MAY_LINK = {"dform::pipeline", "dform::studio", "dform_warnings"}


def cli_link_violations(link_libraries):
    ours = [lib for lib in link_libraries.split(";") if lib.startswith(("dform::", "dform_"))]
    return [f"the cli links {lib}, which it may not (only {', '.join(sorted(CLI_MAY_LINK))})"
            for lib in ours if lib not in CLI_MAY_LINK]


# core's 2D helpers (core/polyline.h) are the one copy: export, which draws in 2D, uses them
# rather than defining a function of the same name again (a renamed copy is what the
# `duplicates` tool finds).
DECLARED = re.compile(r"^[A-Za-z][\w:<>,\s\*&]*?[\s\*&](\w+)\(", re.M)


def core_helper_copies(src, module="export", header="core/polyline.h"):
    with open(os.path.join(public_folder(src), header), encoding="utf-8") as f:
        names = set(DECLARED.findall(f.read()))
    found = []
    for root, _, files in os.walk(os.path.join(src, module)):
        for name in sorted(files):
            path = os.path.join(root, name)
            with open(path, encoding="utf-8") as f:
                text = f.read()
            for helper in sorted(names):
                # A definition: a return type at the start of a line, the name, its parameters
                # and a body (not a call, which has no type before it, nor a declaration).
                definition = re.compile(r"^[A-Za-z][\w:<>,\s\*&]*?[\s\*&]" + helper +
                                        r"\([^;{]*\)\s*(const\s*)?\{", re.M)
                for m in definition.finditer(text):
                    line = text.count("\n", 0, m.start()) + 1
                    found.append(f"{os.path.relpath(path, src)}:{line}: {module} defines {helper}, "
                                 f"which {header} has")
    return found


# A module's row in docs/architecture.md: | module | target | what it does | may use |
TABLE_ROW = re.compile(r"^\|\s*([a-z_]+)\s*\|.*\|\s*([^|]*?)\s*\|\s*$")
CONVENTIONS_LIST = re.compile(r"`src/<module>/` holds one stage: (.*?)\. Each folder", re.S)
LINKED = re.compile(r"dform::([a-z_]+)")


def modules(src):
    return sorted(m for m in os.listdir(src) if os.path.isdir(os.path.join(src, m)))


def doc_violations(src, docs):
    """Where the docs or a module's CMakeLists.txt disagree with ALLOWED and the folders of src/."""
    found = []
    names = set(ALLOWED)
    with open(os.path.join(docs, "architecture.md"), encoding="utf-8") as f:
        rows = [m.groups() for m in map(TABLE_ROW.match, f) if m and m.group(1) in names]
    said = dict(rows)
    for module in modules(src):
        if module not in said:
            found.append(f"architecture.md: no row for the module {module}")
            continue
        if said[module] == "everything above":
            used = set(m for m, _ in rows[:[m for m, _ in rows].index(module)])
        else:
            used = {w for w in re.findall(r"[a-z_]+", said[module]) if w in names} - {module}
        if used != ALLOWED[module]:
            found.append(f"architecture.md: {module} may use {', '.join(sorted(used)) or 'nothing'}"
                         f" by its table, {', '.join(sorted(ALLOWED[module])) or 'nothing'} by the"
                         f" layering test")
    with open(os.path.join(docs, "conventions.md"), encoding="utf-8") as f:
        m = CONVENTIONS_LIST.search(f.read())
    listed = sorted(re.findall(r"`([a-z_]+)`", m.group(1))) if m else []
    if listed != modules(src):
        found.append(f"conventions.md: lists the modules {', '.join(listed)}; src/ has "
                     f"{', '.join(modules(src))}")
    for module in modules(src):
        path = os.path.join(src, module, "CMakeLists.txt")
        if not os.path.exists(path):
            continue
        with open(path, encoding="utf-8") as f:
            linked = set(LINKED.findall(f.read())) - {module}
        for other in sorted(linked - ALLOWED.get(module, set())):
            found.append(f"{module}/CMakeLists.txt links dform::{other}, which {module} may not use")
    return found


def self_test():
    with tempfile.TemporaryDirectory() as root:
        src = os.path.join(root, "src")
        def write(path, text, folder=src):
            os.makedirs(os.path.dirname(os.path.join(folder, path)), exist_ok=True)
            with open(os.path.join(folder, path), "w", encoding="utf-8") as f:
                f.write(text)
        def public(path, text=""):
            write(path, text, os.path.join(root, "include", "dform"))
        for header in ("io/reader.h", "core/status.h", "core/types.h", "validate/gate.h",
                       "pipeline/run.h", "export/exporter.h", "forward/forward.h",
                       "inverse/pre_dform.h", "solver/problem.h", "io/outline_reader.h"):
            public(header)
        write("io/reader.cpp", '#include "dform/io/reader.h"\n#include "dform/core/status.h"\n')
        write("pipeline/run.cpp", '#include "dform/io/reader.h"\n#include "dform/validate/gate.h"\n')
        assert violations(src) == [], violations(src)
        write("io/bad.cpp", '#include "dform/core/status.h"\n  #include "dform/pipeline/run.h"\n')
        found = violations(src)
        assert len(found) == 1 and found[0].startswith("io/bad.cpp:2: io includes pipeline/"), found
        write("core/worse.h", '#include "dform/export/exporter.h"\n')
        assert len(violations(src)) == 2, violations(src)
        # A module included without the prefix is found even where the module is allowed.
        write("io/bare.cpp", '#include "core/status.h"\n#include <io/reader.h>\n')
        found = violations(src)
        assert [f for f in found if f.startswith("io/bare.cpp")] == [
            "io/bare.cpp:1: includes core/ without the dform/ prefix",
            "io/bare.cpp:2: includes io/ without the dform/ prefix"], found
        os.remove(os.path.join(src, "io/bare.cpp"))
        # forward and inverse share the model below them and use neither the other; validate
        # judges meshes and uses no solver.
        write("inverse/solve.cpp", '#include "dform/model/terms.h"\n#include "dform/forward/forward.h"\n')
        write("forward/solve.cpp", '#include "dform/model/terms.h"\n#include "dform/inverse/pre_dform.h"\n')
        public("model/terms.h", '#include "dform/solver/problem.h"\n#include "dform/forward/forward.h"\n')
        write("validate/metrics.cpp", '#include "dform/core/types.h"\n#include "dform/solver/problem.h"\n')
        found = violations(src)
        assert [f.split(": ")[0] for f in found] == [
            "core/worse.h:1", "forward/solve.cpp:2", "inverse/solve.cpp:2", "io/bad.cpp:2",
            "include/dform/model/terms.h:2", "validate/metrics.cpp:2"], found
        # The studio uses the pipeline, io and validate, nothing else of the stages.
        write("studio/server.cpp", '#include "dform/pipeline/run.h"\n#include "dform/io/outline_reader.h"\n')
        assert len(violations(src)) == 6, violations(src)
        write("studio/worse.cpp", '#include "dform/export/exporter.h"\n')
        found = violations(src)
        assert len(found) == 7 and any(f.startswith("studio/worse.cpp:1: studio includes export/") for f in found), found
        for planted in ("core/worse.h", "forward/solve.cpp", "inverse/solve.cpp", "io/bad.cpp",
                        "validate/metrics.cpp", "studio/worse.cpp"):
            os.remove(os.path.join(src, planted))
        os.remove(os.path.join(root, "include", "dform", "model", "terms.h"))
        assert violations(src) == [], violations(src)
        # A private header is included by its bare name from its own module's folder only; a
        # public header includes public ones only, and a dform/ include names a file that is there.
        write("io/svg_path.h", "")
        write("io/svg.cpp", '#include "svg_path.h"\n#include "dform/io/reader.h"\n')
        assert violations(src) == [], violations(src)
        write("pipeline/peek.cpp", '#include "dform/io/svg_path.h"\n#include "svg_path.h"\n'
                                   '#include "dform/core/missing.h"\n')
        public("io/leaky.h", '#include "svg_path.h"\n')
        found = violations(src)
        assert found == [
            "include/dform/io/leaky.h:1: a public header includes the private header svg_path.h",
            "pipeline/peek.cpp:1: includes dform/io/svg_path.h, which is a private header of io "
            "(public headers are in include/dform/io/)",
            "pipeline/peek.cpp:2: includes svg_path.h, which is not a private header of pipeline",
            "pipeline/peek.cpp:3: includes dform/core/missing.h, which is not there (public "
            "headers are in include/dform/core/)"], found
        public("core/polyline.h", "double closedLength(const Eigen::MatrixXd& P);\n"
                                  "bool segmentsIntersect(const Vec2& a,\n    const Vec2& b);\n")
        write("export/draw.cpp", "double width(const Polyline& p) { return closedLength(p); }\n")
        assert core_helper_copies(src) == [], core_helper_copies(src)
        write("export/copy.cpp", "namespace {\nstatic double closedLength(const Polyline& p,\n"
                                 "                           int k) {\n  return 0;\n}\n}\n")
        found = core_helper_copies(src)
        assert found == ["export/copy.cpp:2: export defines closedLength, which core/polyline.h has"], found
    with tempfile.TemporaryDirectory() as root:
        src, docs = os.path.join(root, "src"), os.path.join(root, "docs")
        for module in ("core", "io"):
            os.makedirs(os.path.join(src, module))
        os.makedirs(docs)
        def write_docs(io_uses, listed):
            with open(os.path.join(docs, "architecture.md"), "w", encoding="utf-8") as f:
                f.write("| module | target | what it does | may use |\n|---|---|---|---|\n"
                        "| core | `dform::core` | types | Eigen |\n"
                        f"| io | `dform::io` | files | {io_uses} |\n")
            with open(os.path.join(docs, "conventions.md"), "w", encoding="utf-8") as f:
                f.write(f"- `src/<module>/` holds one stage: {listed}. Each folder defines\n")
        write_docs("core; svgpp privately", "`core`, `io`")
        assert doc_violations(src, docs) == [], doc_violations(src, docs)
        write_docs("core, meshing", "`core`, `io`")
        assert len(doc_violations(src, docs)) == 1, doc_violations(src, docs)
        write_docs("core", "`core`")
        assert len(doc_violations(src, docs)) == 1, doc_violations(src, docs)
        write_docs("core", "`core`, `io`")
        with open(os.path.join(src, "io", "CMakeLists.txt"), "w", encoding="utf-8") as f:
            f.write("target_link_libraries(dform_io PUBLIC dform::core PRIVATE dform::export)\n")
        found = doc_violations(src, docs)
        assert found == ["io/CMakeLists.txt links dform::export, which io may not use"], found
    assert cli_link_violations("dform::pipeline;dform::studio;CLI11::CLI11;dform_warnings") == []
    found = cli_link_violations("dform::pipeline;dform::export;CLI11::CLI11;dform_report")
    assert len(found) == 2 and "dform::export" in found[0] and "dform_report" in found[1], found
    print("layering.py: self-test passed")
    return 0


def main():
    if sys.argv[1:] == ["--self-test"]:
        return self_test()
    if len(sys.argv) == 3 and sys.argv[1] == "--cli-links":
        found = cli_link_violations(sys.argv[2])
        for v in found:
            print(v)
        print(f"cli links: {sys.argv[2]}")
        return 1 if found else 0
    if len(sys.argv) == 4 and sys.argv[1] == "--docs":
        found = doc_violations(sys.argv[2], sys.argv[3])
        for v in found:
            print(v)
        print(f"docs and CMake links against the layering: {len(found)} difference(s)")
        return 1 if found else 0
    if len(sys.argv) == 3 and sys.argv[1] == "--core-copies":
        found = core_helper_copies(sys.argv[2])
        for v in found:
            print(v)
        print(f"core helper copies in export: {len(found)}")
        return 1 if found else 0
    if len(sys.argv) != 2:
        print(__doc__, file=sys.stderr)
        return 2
    found = violations(sys.argv[1])
    for v in found:
        print(v)
    print(f"layering: {len(found)} include(s) against the modules' order")
    return 1 if found else 0


if __name__ == "__main__":
    sys.exit(main())
