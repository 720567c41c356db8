#!/usr/bin/env python3
"""The modules of src/ depend one way (docs/architecture.md): each may include only the modules
below it. Lists every #include of a module a file may not use and exits 1, else 0.

    layering.py SRC_DIR
    layering.py --self-test   (a planted upward include must be found, a clean tree pass)
"""
import os
import re
import sys
import tempfile

# What each module may include besides itself: the data flow io -> meshing -> forward/inverse
# on a generic solver -> validate -> export/report -> pipeline -> sweep -> cli, with core under
# all. The cli still reaches past pipeline into the stages (issue 16 moves the run policy into
# pipeline, and then narrows it to pipeline and core).
ALLOWED = {
    "core": set(),
    "solver": {"core"},
    "io": {"core"},
    "meshing": {"core"},
    "exact": {"core"},
    "forward": {"core", "solver"},
    "inverse": {"core", "solver", "meshing", "forward"},
    "validate": {"core", "exact", "forward"},
    "export": {"core", "validate"},
    "report": {"core", "validate"},
    "pipeline": {"core", "io", "meshing", "solver", "exact", "forward", "inverse", "validate"},
    "sweep": {"core", "io", "pipeline", "report", "validate"},
    "cli": {"core", "io", "solver", "validate", "export", "report", "pipeline", "sweep"},
}

INCLUDE = re.compile(r'^\s*#\s*include\s+"([a-z_]+)/')


def violations(src):
    found = []
    for module in sorted(os.listdir(src)):
        folder = os.path.join(src, module)
        if not os.path.isdir(folder):
            continue
        if module not in ALLOWED:
            found.append(f"{module}/: a module the layering does not know (add it to ALLOWED)")
            continue
        for root, _, files in os.walk(folder):
            for name in sorted(files):
                if not name.endswith((".h", ".hpp", ".cpp")):
                    continue
                path = os.path.join(root, name)
                with open(path, encoding="utf-8") as f:
                    for number, line in enumerate(f, 1):
                        m = INCLUDE.match(line)
                        if m and m.group(1) != module and m.group(1) not in ALLOWED[module]:
                            found.append(f"{os.path.relpath(path, src)}:{number}: {module} includes "
                                         f"{m.group(1)}/, which it may not (allowed: "
                                         f"{', '.join(sorted(ALLOWED[module])) or 'nothing'})")
    return found


def self_test():
    with tempfile.TemporaryDirectory() as src:
        def write(path, text):
            os.makedirs(os.path.dirname(os.path.join(src, path)), exist_ok=True)
            with open(os.path.join(src, path), "w", encoding="utf-8") as f:
                f.write(text)
        write("io/reader.cpp", '#include "io/reader.h"\n#include "core/status.h"\n')
        write("pipeline/run.cpp", '#include "io/reader.h"\n#include "validate/gate.h"\n')
        assert violations(src) == [], violations(src)
        write("io/bad.cpp", '#include "core/status.h"\n  #include "pipeline/run.h"\n')
        found = violations(src)
        assert len(found) == 1 and found[0].startswith("io/bad.cpp:2: io includes pipeline/"), found
        write("core/worse.h", '#include "export/exporter.h"\n')
        assert len(violations(src)) == 2, violations(src)
    print("layering.py: self-test passed")
    return 0


def main():
    if sys.argv[1:] == ["--self-test"]:
        return self_test()
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
