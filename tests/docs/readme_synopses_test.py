#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""The README's command-line synopses name every option that `geaware … --help` lists.
Usage: readme_synopses_test.py README.md GEAWARE"""
import re
import subprocess
import sys

readme, geaware = sys.argv[1], sys.argv[2]
text = open(readme, encoding="utf-8").read()
m = re.search(r"## Command line\n.*?```sh\n(.*?)```", text, re.S)
if not m:
    sys.exit("README.md: no ```sh block under '## Command line'")
synopsis = m.group(1)


def help_of(*cmd):
    return subprocess.run([geaware, *cmd, "--help"], capture_output=True, text=True,
                          check=True).stdout


def section(name, text):
    s = re.search(rf"^{name}:\n(.*?)(?:\n\n|\Z)", text, re.S | re.M)
    return s.group(1) if s else ""


# The synopsis of a command: its lines from "geaware CMD" to the next "geaware " line.
def lines_of(cmd):
    out, inside = [], False
    for line in synopsis.splitlines():
        if line.startswith("geaware "):
            inside = line.startswith(f"geaware {cmd} ") or line.startswith(f"geaware {cmd}\t")
        if inside:
            out.append(line)
    return "\n".join(out)


problems = []
commands = re.findall(r"^  (\w+) ", section("Subcommands", help_of()), re.M)
assert commands, "geaware --help lists no subcommands"
for cmd in commands:
    top = help_of(cmd)
    subs = re.findall(r"^  (\w+) ", section("Subcommands", top), re.M)
    for path in ([[cmd, s] for s in subs] or [[cmd]]):
        h = help_of(*path)
        options = set(re.findall(r"^\s+(?:-\w,)?(--[\w-]+)", section("Options", h), re.M))
        options.discard("--help")
        where = lines_of(" ".join(path)) or lines_of(cmd)
        if not where:
            problems.append(f"geaware {' '.join(path)}: no synopsis in the README")
            continue
        for o in sorted(options):
            if not re.search(rf"{re.escape(o)}(?![\w-])", where):
                problems.append(f"geaware {' '.join(path)}: {o} is missing from the README")
if problems:
    print("\n".join(problems))
    sys.exit(1)
print(f"the README's synopses name every option of {len(commands)} commands")
