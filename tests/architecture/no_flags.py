#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Library code never words a command-line flag (docs/conventions.md): a message about a setting
names it by mention() (core/setting.h) and each shell words it its own way. Lists every string
literal of src/ and include/ outside src/cli/ that holds a flag ("--resolution", "--no-export")
and exits 1, else 0. The command line's own sources (src/cli/) word flags, and the settings
table's rows (src/pipeline/setting_rows.cpp) are where each setting's flag is written, once;
comments may name them.

    no_flags.py ROOT
    no_flags.py --self-test   (a planted flag in a message must be found, one in a comment not)
"""
import os
import re
import sys
import tempfile

# The settings table: the one place a setting's flag is written (its flag column).
TABLE = os.path.join("src", "pipeline", "setting_rows.cpp")
FLAG = re.compile(r"(?<![\w-])--[a-z][a-z0-9-]*")
# A C++ string literal (escapes kept), and a raw one R"(...)".
STRING = re.compile(r'R"\((.*?)\)"|"((?:[^"\\\n]|\\.)*)"')


def code_of(line, in_block):
    """The line without its comments, and whether a /* */ comment runs on past it."""
    out, i = "", 0
    while i < len(line):
        if in_block:
            end = line.find("*/", i)
            if end < 0:
                return out, True
            i, in_block = end + 2, False
            continue
        m = STRING.match(line, i)
        if m:
            out += m.group(0)
            i = m.end()
        elif line.startswith("//", i):
            break
        elif line.startswith("/*", i):
            in_block, i = True, i + 2
        else:
            out += line[i]
            i += 1
    return out, in_block


def flags_in_messages(root):
    found = []
    for folder in ("src", "include"):
        for base, _, files in os.walk(os.path.join(root, folder)):
            rel = os.path.relpath(base, root)
            if rel == os.path.join("src", "cli") or rel.startswith(os.path.join("src", "cli") + os.sep):
                continue
            for name in sorted(files):
                if not name.endswith((".h", ".hpp", ".cpp")):
                    continue
                path = os.path.join(base, name)
                if os.path.relpath(path, root) == TABLE:
                    continue
                in_block = False
                with open(path, encoding="utf-8") as f:
                    for number, line in enumerate(f, 1):
                        code, in_block = code_of(line.rstrip("\n"), in_block)
                        for m in STRING.finditer(code):
                            text = m.group(1) if m.group(1) is not None else m.group(2)
                            for flag in FLAG.findall(text):
                                found.append(f"{os.path.relpath(path, root)}:{number}: the flag "
                                             f"{flag} in a string (name the setting with mention())")
    return found


def self_test():
    with tempfile.TemporaryDirectory() as root:
        def write(path, text):
            os.makedirs(os.path.dirname(os.path.join(root, path)), exist_ok=True)
            with open(os.path.join(root, path), "w", encoding="utf-8") as f:
                f.write(text)
        write("src/export/ok.cpp", '// --kerf is the command line\'s\nint k = n--;\n'
                                   'auto s = mention(Setting::Kerf) + " must be";\n'
                                   '/* --page\n --sheet */ const char* x = "a-b--c";\n')
        write("src/cli/main.cpp", 'add_option("--kerf", k, "the kerf");\n')
        write("src/pipeline/setting_rows.cpp", 'row(Setting::Kerf, "--kerf", "kerf");\n')
        assert flags_in_messages(root) == [], flags_in_messages(root)
        write("src/export/bad.cpp", 'return Status{Usage, "--kerf must be between 0 and 5"};\n'
                                    'x = 1;  // "--quiet" in a comment\n'
                                    'auto y = R"(try --no-export)";\n')
        write("include/dform/pipeline/bad.h", 'const char* k = "give a larger \\"--sheet\\"";\n')
        found = flags_in_messages(root)
        assert [f.split(": ")[0] for f in found] == [
            "src/export/bad.cpp:1", "src/export/bad.cpp:3", "include/dform/pipeline/bad.h:1"] or \
            sorted(f.split(": ")[0] for f in found) == sorted([
                "src/export/bad.cpp:1", "src/export/bad.cpp:3",
                "include/dform/pipeline/bad.h:1"]), found
    print("no_flags.py: self-test passed")
    return 0


def main():
    if sys.argv[1:] == ["--self-test"]:
        return self_test()
    if len(sys.argv) != 2:
        print(__doc__, file=sys.stderr)
        return 2
    found = flags_in_messages(sys.argv[1])
    for line in found:
        print(line)
    print(f"command-line flags in library strings: {len(found)}")
    return 1 if found else 0


if __name__ == "__main__":
    sys.exit(main())
