#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""scripts/check-docs must catch a wrong number: it is run on temporary documents whose blocks
are the real output of a geaware command, then with one digit changed, and so on.
Usage: check_docs_test.py CHECKER GEAWARE"""
import os
import re
import subprocess
import sys
import tempfile

checker, geaware = sys.argv[1], sys.argv[2]
CMD = "geaware model --heights 0.1:0.3:0.1"
failures = []


def check(name, doc, want_exit, want_in_output=()):
    with tempfile.TemporaryDirectory() as tmp:
        os.mkdir(os.path.join(tmp, "docs"))
        path = os.path.join(tmp, "docs", "t.md")
        open(path, "w", encoding="utf-8").write(doc)
        p = subprocess.run([sys.executable, checker, "--root", tmp, "--geaware", geaware, path],
                           capture_output=True, text=True)
        out = p.stdout + p.stderr
        if p.returncode != want_exit or any(s not in out for s in want_in_output):
            failures.append(f"{name}: exit {p.returncode} (want {want_exit}), output:\n{out}")


def block(lines, opts=""):
    return f"Text.\n\n<!-- check{opts}: {CMD} -->\n```\n" + "\n".join(lines) + "\n```\n"


real = subprocess.run(["bash", "-c", CMD.replace("geaware", geaware, 1)], capture_output=True,
                      text=True, check=True)
out = (real.stdout + real.stderr).rstrip("\n").split("\n")
numbered = [i for i, l in enumerate(out) if re.search(r"\d\.\d{3}", l)]
assert numbered, f"no numbers in the output of {CMD}:\n{out}"

# 1. The output itself matches.
check("verbatim", block(out), 0, ["1 of 1 blocks match"])

# 2. One digit changed in one number: caught, and the line is shown.
i = numbered[len(numbered) // 2]
m = list(re.finditer(r"\d\.(\d{3})", out[i]))[-1]
digit = m.start(1) + 2
wrong = out[i][:digit] + str((int(out[i][digit]) + 1) % 10) + out[i][digit + 1:]
bad = out[:i] + [wrong] + out[i + 1:]
check("one digit wrong", block(bad), 1, ["FAIL", wrong.strip()])

# 3. A missing line is caught; an extra line in the doc is caught.
check("line missing", block(out[:-1]), 1, ["FAIL"])
check("line added", block(out + ["0.4 extra"]), 1, ["FAIL"])

# 4. A tolerance that covers the change accepts it; a tighter one does not.
check("within rtol", block(bad, " rtol=0.05"), 0)
check("beyond atol", block(bad, " atol=1e-9"), 1, ["FAIL"])

# 5. `…` stands for the changed number; `…` alone for any lines; subset skips lines.
ellipsis = out[i][:m.start()] + "…" + out[i][m.end():]
check("ellipsis in a line", block(out[:i] + [ellipsis] + out[i + 1:]), 0)
check("ellipsis lines", block(out[:1] + ["…"] + out[-1:]), 0)
check("subset", block([out[i]], " match=subset"), 0)
check("subset, wrong", block([wrong], " match=subset"), 1, ["FAIL"])

# 6. The wrong exit status is caught; a console block carries its own command.
check("exit status", block(out, " exit=1"), 1, ["exit status 0"])
console = "<!-- check -->\n```console\n$ " + CMD + "\n" + "\n".join(out) + "\n```\n"
check("console block", console, 0, ["1 of 1 blocks match"])
check("console block, wrong", console.replace(out[i], wrong), 1, ["FAIL"])

# 7. Slow blocks are skipped unless --all; a marker without a block is a usage error.
check("slow skipped", block(bad, " slow"), 0, ["1 slow skipped"])
check("marker alone", "<!-- check: geaware --help -->\ntext\n", 2, ["fenced block"])

if failures:
    print("\n\n".join(failures))
    sys.exit(1)
print("check-docs catches wrong numbers, missing and extra lines, wrong exit codes")
