#!/usr/bin/env python3
"""The Dask batch example (examples/python/batch_dask.py) timed serial and on local clusters
of 1 and 2 worker processes, over the pose files of tests/data/poses, for the benchmark
page: a markdown table on stdout. The cluster's times include starting it.

Usage: batch_bench.py BUILD [--smoke]   (--smoke: two files, for CTest's bench.page_smoke)
"""
import json
import os
import shutil
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
EXAMPLE = os.path.join(ROOT, "examples", "python", "batch_dask.py")
ARGS = ["--tol", "0.2", "--body", "cutter:flat,6,20", "--profile", "circle:3"]


def module_python(build):
    """The interpreter the module was built for (CMake's Python, which may not be the one
    running this script: a pyenv python3 without numpy, say)."""
    for line in open(os.path.join(build, "CMakeCache.txt")):
        if line.startswith("_Python_EXECUTABLE:"):
            return line.split("=", 1)[1].strip()
    return sys.executable


def main():
    build = os.path.abspath(sys.argv[1])
    smoke = "--smoke" in sys.argv[2:]
    python = module_python(build)
    env = dict(os.environ, PYTHONPATH=os.path.join(build, "python"))
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        folder = os.path.join(tmp, "in")
        shutil.copytree(os.path.join(ROOT, "tests", "data", "poses"), folder)
        if smoke:
            for f in sorted(os.listdir(folder))[2:]:
                os.remove(os.path.join(folder, f))
        for how in (["--serial"], ["--workers", "1"], ["--workers", "2"]):
            out = os.path.join(tmp, "out" + "".join(how))
            r = subprocess.run([python, EXAMPLE, folder, out] + ARGS + how,
                               capture_output=True, text=True, env=env)
            if r.returncode != 0:
                sys.exit("batch_dask.py %s failed:\n%s" % (" ".join(how), r.stderr))
            rows.append(json.loads(r.stdout.strip().splitlines()[-1]))
    serial = rows[0]["seconds"]
    print("| run | files | done | refused | time | serial / this |")
    print("| --- | --- | --- | --- | --- | --- |")
    for r in rows:
        print("| %s | %d | %d | %d | %.2f s | %.2f |" % (r["how"], r["files"], r["done"],
                                                         r["refused"], r["seconds"],
                                                         serial / r["seconds"]))


if __name__ == "__main__":
    main()
