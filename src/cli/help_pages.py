#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""The man page and the bash completion of dform, made from the command's own --help texts, so
that neither can describe options the command does not have.

    help_pages.py DFORM OUT_DIR DATADIR    writes OUT_DIR/dform.1.gz and OUT_DIR/dform.bash

DATADIR is the installed share folder (/usr/share for the Debian packages), where the page's FILES
section finds the templates, the completion and the installed docs.

dform --help lists the subcommands; each `dform SUB --help` gives its usage, positionals and
options (CLI11's layout: a section title ending in ':', then one entry per line, the name padded
to a column and its description).
"""
import datetime
import gzip
import os
import re
import subprocess
import sys

ENTRY = re.compile(r"^  (\S.*?)(?:\s{2,}(.*))?$")


def help_text(dform, *args):
    out = subprocess.run([dform, *args, "--help"], check=True, capture_output=True, text=True)
    return out.stdout


def sections(text):
    """{title: [(name, description), ...]} and the lines before the first section."""
    found, intro, current = {}, [], None
    for line in text.splitlines():
        if re.match(r"^[A-Z][A-Za-z ]*:$", line):
            current = line[:-1]
            found[current] = []
        elif current and line.startswith("  "):
            m = ENTRY.match(line)
            if m and not line.startswith("   "):
                found[current].append([m.group(1).strip(), (m.group(2) or "").strip()])
            elif found[current]:  # a description wrapped onto the next line
                found[current][-1][1] += " " + line.strip()
        elif current is None and line.strip():
            intro.append(line.strip())
    return found, intro


def option_names(entry):
    """'-o,--output TEXT REQUIRED' -> ['-o', '--output']."""
    return [n for n in re.split(r"[ ,]", entry) if n.startswith("-")]


def roff(text):
    return text.replace("\\", "\\e").replace("-", "\\-").replace("'", "\\(aq")


EXAMPLES = [
    ("Make the D-Form of two outlines, with its report, pattern and previews:",
     "dform forward piece-a.svg piece-b.svg -o out/"),
    ("The two flat pieces whose seam follows a closed 3D curve:",
     "dform inverse seam.obj -o out/"),
    ("Every starting pair of two outlines, with a gallery to compare them:",
     "dform sweep a.svg b.svg --starts 16 -o sweep/"),
    ("Export a saved result again for a 600 x 400 mm laser sheet:",
     "dform export out/ --profile laser --sheet 600x400mm"),
    ("Check a saved result against the strict gate, the verdict as one JSON object:",
     "dform validate out/ --gate strict --json"),
    ("Design in the browser, starting from two outlines:",
     "dform studio piece-a.svg piece-b.svg"),
]


def files_section(datadir):
    """The installed files the page names: templates, completion, the docs of each package."""
    doc = datadir + "/doc"
    entries = [
        (datadir + "/dform/templates/",
         "export profiles (profiles/), quality-gate presets (gates/), the report page (report/), "
         "report.json's schema (schema/) and the studio's page (studio/); $DFORM_TEMPLATES "
         "names another such folder"),
        (datadir + "/bash-completion/completions/dform", "the bash completion"),
        (doc + "/dform/", "the user documentation: README.md, cli.md (every command, its options "
         "and outputs), export.md, report.md, validation.md, studio.md and the others"),
        (doc + "/dform/cli-output.schema.json",
         "the JSON Schema of the one object every command prints with --json"),
        (doc + "/libdform-dev/",
         "the C++ library (package libdform-dev): api.md and the API reference, html/index.html"),
        (doc + "/python3-dform/",
         "the Python module (package python3-dform): python.md and the reference, dform.html"),
    ]
    lines = [".SH FILES"]
    for path, what in entries:
        lines += [".TP", "\\fI" + roff(path) + "\\fR", roff(what) + "."]
    return lines


def man_page(dform, version, commands, datadir):
    top, intro = sections(help_text(dform))
    date = datetime.date.fromtimestamp(os.stat(dform).st_mtime).isoformat()
    lines = [f'.TH DFORM 1 "{date}" "dform {version}" "User Commands"', ".SH NAME",
             "dform \\- " + roff(intro[0].split(": ", 1)[-1]), ".SH SYNOPSIS",
             "\\fBdform\\fR \\fISUBCOMMAND\\fR [\\fIOPTIONS\\fR] [\\fIFILES\\fR]",
             ".SH DESCRIPTION",
             "A D-Form is made by cutting two flat pieces with the same perimeter and zipping "
             "their edges together. Each subcommand below has its own options; "
             "\\fBdform\\fR \\fISUBCOMMAND\\fR \\fB\\-\\-help\\fR prints them.", ".SH COMMANDS"]
    for name, summary in top.get("Subcommands", []):
        lines += [".SS " + roff(name), roff(summary) + "."]
        found, usage = commands[name]
        lines += [".PP", "Usage: dform " + roff(" ".join(usage[-1].split()[2:]) if usage else name)]
        for title in ("Positionals", "Options"):
            for entry, description in found.get(title, []):
                lines += [".TP", "\\fB" + roff(entry) + "\\fR", roff(description)]
    lines += [".SH EXIT STATUS", "0 success; 1 internal error; 2 usage; 3 unreadable input; "
              "4 invalid input; 5 solve failed; 6 output failed; 7 quality gate failed; "
              "130 interrupted (143 on SIGTERM).",
              ".SH ENVIRONMENT", ".TP", "\\fBDFORM_TEMPLATES\\fR",
              roff("the templates folder to use instead of the installed one (it must hold gates/, "
                   "profiles/ and report/; anything else is an error, exit 3)."),
              ".TP", "\\fBXDG_RUNTIME_DIR\\fR",
              roff("where dform studio keeps the private page that opens the browser (else the "
                   "temporary folder, $TMPDIR or /tmp)."),
              ".SH EXAMPLES"]
    for what, command in EXAMPLES:
        lines += [".PP", roff(what), ".PP", ".RS", "\\fB" + roff(command) + "\\fR", ".RE"]
    lines += files_section(datadir)
    lines += [".SH SEE ALSO", "The files under " + roff(datadir + "/doc/dform/") +
              " (cli.md for every command), and \\fBdform\\fR \\fISUBCOMMAND\\fR "
              "\\fB\\-\\-help\\fR."]
    return "\n".join(lines) + "\n"


def choices(entry):
    """'--model auto|exact|paper|general' -> ['auto', 'exact', 'paper', 'general'] (the values
    --help lists for an option of the settings table that takes one of them), else []."""
    m = re.match(r"^\S+ ([A-Za-z0-9_,.-]+(?:\|[A-Za-z0-9_,.-]+)+)$", entry)
    return m.group(1).split("|") if m else []


def completion(top, commands):
    cases, values = [], {}
    for name, _ in top.get("Subcommands", []):
        found, _ = commands[name]
        options = sorted({n for entry, _ in found.get("Options", []) for n in option_names(entry)})
        cases.append(f'    {name}) options="{" ".join(options)}" ;;')
        for entry, _ in found.get("Options", []):
            for option in option_names(entry):
                if choices(entry):
                    values[option] = choices(entry)
    subcommands = " ".join(name for name, _ in top.get("Subcommands", []))
    value_cases = "".join(f'    {option}) COMPREPLY=($(compgen -W "{" ".join(v)}" -- "$current"));'
                          " return ;;\n" for option, v in sorted(values.items()))
    return f"""# bash completion for dform, made from its --help texts (help_pages.py)
_dform() {{
  local current=${{COMP_WORDS[COMP_CWORD]}} previous=${{COMP_WORDS[COMP_CWORD-1]}} options
  if [ "$COMP_CWORD" -eq 1 ]; then
    COMPREPLY=($(compgen -W "{subcommands} --help --version" -- "$current"))
    return
  fi
  case "${{COMP_WORDS[1]}}" in
{chr(10).join(cases)}
    *) options="" ;;
  esac
  case "$previous" in
{value_cases}  esac
  if [ "$previous" = --profile ]; then
    COMPREPLY=($(compgen -W "$(dform export --list-profiles 2>/dev/null)" -- "$current"))
  elif [[ "$current" == -* ]]; then
    COMPREPLY=($(compgen -W "$options" -- "$current"))
  else
    COMPREPLY=($(compgen -f -- "$current"))
  fi
}}
complete -o filenames -F _dform dform
"""


def main():
    dform, out, datadir = sys.argv[1:4]
    version = subprocess.run([dform, "--version"], check=True, capture_output=True,
                             text=True).stdout.split()[-1]
    top, _ = sections(help_text(dform))
    commands = {}
    for name, _ in top.get("Subcommands", []):
        text = help_text(dform, name)
        found, _ = sections(text)
        commands[name] = (found, [l for l in text.splitlines() if l.startswith("Usage:")])
    with gzip.GzipFile(os.path.join(out, "dform.1.gz"), "wb", mtime=0) as f:
        f.write(man_page(dform, version, commands, datadir).encode())
    with open(os.path.join(out, "dform.bash"), "w", encoding="utf-8") as f:
        f.write(completion(top, commands))


if __name__ == "__main__":
    main()
