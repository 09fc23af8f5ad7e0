#!/usr/bin/env python3
"""The refusals table (tests/refusals/refusals.json) run against the qmotion program.

Every row is one kind of bad input: the command that gives it, the exit status it must
end with (2 bad input, 3 a numerical refusal) and the message it must print. The test
runs each row and checks that

  - the program exits with the row's status, and prints `qmotion: error: MESSAGE`, with
    MESSAGE equal to the row's message ("..." in it, written as the ellipsis character,
    stands for any text: a figure that depends on rounding);
  - the message names what the row says it must name (`names`: the file, option or field);
  - no output file is left behind: neither the file given to -o nor a temporary beside it;
  - every file of the folders of bad files (bad_poses, bad_motions, damaged_cad) has a row.

Rows marked "cgal" need the exact modes or the mesh check; --without-cgal (a build with
QMOTION_WITH_CGAL=OFF) skips them.

The same table generates docs/refusals.md (--docs), and --check-docs fails when that page
is not what the table generates, so the page cannot drift from what is tested.

Usage: refusals.py --exe QMOTION --root REPO [--without-cgal] [--docs FILE | --check-docs FILE]
"""
import argparse
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile

FOLDERS = ("bad_poses", "bad_motions", "damaged_cad")
PREFIX = "qmotion: error: "
DOCS_HEAD = """# Bad input

Generated from `tests/refusals/refusals.json` by `tests/refusals/refusals.py --docs`; the
CTest test `refusals.table` runs every row and `refusals.docs` checks that this page is what
the table generates. Exit 2 is bad input, 3 a numerical refusal; in every case the message
names the file, pose, field or option, and no output file is left behind (neither the file
given to `-o` nor a temporary beside it). Commands run from the repository's top; `{out}`
is a scratch folder, and the setup commands a row needs are in the table. `…` in a message
stands for figures that depend on rounding. The fuzz targets replay their past findings as
`fuzz.<name>.regressions`; library calls raise the same messages (`qmotion::Error`, and in
Python `ValueError` for 2, `ArithmeticError` for 3).

"""


def substitute(arg, root, out):
    return (arg.replace("{data}", "tests/data").replace("{examples}", "examples")
            .replace("{out}", out))


def shown(arg):
    """An argument as the docs show it: the scratch folder named {out}."""
    return arg.replace("{data}", "tests/data").replace("{examples}", "examples")


def pattern(message):
    parts = [re.escape(p) for p in message.split("\u2026")]
    return re.compile("^" + ".*?".join(parts) + "$", re.S)


def run(exe, args, root, out):
    r = subprocess.run([exe] + [substitute(a, root, out) for a in args], cwd=root,
                       capture_output=True, text=True, timeout=300)
    return r.returncode, r.stdout, r.stderr


def check_row(exe, root, row, out):
    """Problems with one row (an empty list when it holds)."""
    problems = []
    for setup in row.get("setup", []):
        status, _, err = run(exe, setup, root, out)
        if status != 0:
            return ["setup %s exited %d: %s" % (" ".join(setup), status, err.strip())]
    outputs = [substitute(row["args"][i + 1], root, out)
               for i, a in enumerate(row["args"][:-1]) if a == "-o"]
    for o in outputs:
        if os.path.exists(os.path.join(root, o)):
            os.remove(os.path.join(root, o))
    status, _, err = run(exe, row["args"], root, out)
    lines = [l for l in err.splitlines() if l.startswith(PREFIX)]
    if status != row["exit"]:
        problems.append("exit %d, expected %d (%s)" % (status, row["exit"], err.strip()))
    if len(lines) != 1:
        problems.append("expected one line '%s...', found: %s" % (PREFIX, err.strip()))
    else:
        message = lines[0][len(PREFIX):].replace(out + "/", "")
        if not pattern(row["message"]).match(message):
            problems.append("message differs:\n      got:      %s\n      expected: %s" %
                            (message, row["message"]))
        for name in row.get("names", []):
            if substitute(name, root, out).replace(out + "/", "") not in message:
                problems.append("the message does not name %r: %s" % (name, message))
    for o in outputs:
        if os.path.exists(os.path.join(root, o)):
            problems.append("output left behind: " + o)
    for f in os.listdir(out):
        if ".tmp-" in f:
            problems.append("temporary left behind: " + f)
    return problems


def coverage(root, rows):
    """Bad files without a row."""
    named = {a for row in rows for a in row.get("args", [])}
    missing = []
    for folder in FOLDERS:
        for f in sorted(os.listdir(os.path.join(root, "tests/data", folder))):
            if f.endswith(".dat") and "{data}/%s/%s.src" % (folder, f[:-4]) in named:
                continue  # a KRL program's data list, read with its .src
            if "{data}/%s/%s" % (folder, f) not in named:
                missing.append("tests/data/%s/%s has no row in the refusals table" % (folder, f))
    return missing


def cell(text):
    return text.replace("|", "\\|").replace("\n", " ")


def docs(rows):
    out = [DOCS_HEAD, "| input | command | exit | message |", "| --- | --- | --- | --- |"]
    for row in rows:
        if "args" in row:
            cmd = " ".join(shown(a) for a in row["args"])
            setup = "; ".join("qmotion " + " ".join(shown(a) for a in s)
                              for s in row.get("setup", []))
            command = "`qmotion %s`" % cmd + (" (after `%s`)" % setup if setup else "")
        else:
            command = "(library) " + row["covered_by"]
        out.append("| %s | %s | %d | %s |" % (cell(row["input"]), cell(command), row["exit"],
                                              cell(row["message"])))
    return "\n".join(out) + "\n"


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--exe")
    ap.add_argument("--root", required=True)
    ap.add_argument("--without-cgal", action="store_true", help="skip the rows marked cgal")
    ap.add_argument("--docs", help="write the docs page to this file")
    ap.add_argument("--check-docs", help="fail unless this page is what the table generates")
    a = ap.parse_args()
    with open(os.path.join(a.root, "tests/refusals/refusals.json"), encoding="utf-8") as f:
        rows = json.load(f)["refusals"]
    if a.docs or a.check_docs:
        text = docs(rows)
        if a.docs:
            with open(a.docs, "w", encoding="utf-8") as f:
                f.write(text)
            return 0
        with open(a.check_docs, encoding="utf-8") as f:
            if f.read() != text:
                print("%s is not what tests/refusals/refusals.json generates; run "
                      "tests/refusals/refusals.py --root . --docs %s" % (a.check_docs,
                                                                        a.check_docs))
                return 1
        return 0
    failures = coverage(a.root, rows)
    out = tempfile.mkdtemp(prefix="qmotion_refusals_")
    try:
        for row in rows:
            if "args" not in row or (a.without_cgal and row.get("cgal")):
                continue
            for p in check_row(a.exe, a.root, row, out):
                failures.append("%s (qmotion %s): %s" % (row["input"], " ".join(row["args"]), p))
    finally:
        shutil.rmtree(out, ignore_errors=True)
    for f in failures:
        print("FAIL " + f)
    print("%d rows, %d failures" % (len(rows), len(failures)))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
