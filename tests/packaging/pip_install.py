#!/usr/bin/env python3
"""`pip install .` as a Python user runs it (docs/library.md, "pip"): a fresh venv over the
system's packages, Debian's setuptools as the backend (--no-build-isolation), no package
index; then the README's Python tour from another folder, on the installed module alone.
`pip wheel .` makes a wheel that holds the module and the library it loads.

The build reuses the compiler cache: it is configured with this tree's own options
(warnings, CGAL, viewer), so its objects are the cache's entries. Prints the seconds each
step took.

Usage: pip_install.py ROOT BUILD POSES WORK
"""
import os
import shutil
import subprocess
import sys
import time
import zipfile


def cache_value(build, key):
    for line in open(os.path.join(build, "CMakeCache.txt")):
        if line.startswith(key + ":"):
            return line.split("=", 1)[1].strip()
    return None


def main():
    root, build, poses, work = sys.argv[1:5]
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    flags = ["-D%s=%s" % (k, cache_value(build, k)) for k in
             ("QMOTION_WARNINGS_AS_ERRORS", "QMOTION_WITH_CGAL", "QMOTION_VIEWER",
              "CMAKE_CXX_COMPILER") if cache_value(build, k)]
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "PIP_INDEX_URL")}
    env["QMOTION_CMAKE_ARGS"] = " ".join(flags)
    env["PIP_NO_INDEX"] = "1"
    seconds = {}

    def step(name, cmd, **kw):
        start = time.perf_counter()
        r = subprocess.run(cmd, env=env, capture_output=True, text=True, **kw)
        seconds[name] = round(time.perf_counter() - start, 1)
        if r.returncode != 0:
            sys.exit("FAIL: %s: %s\n%s%s" % (name, " ".join(cmd), r.stdout[-6000:], r.stderr[-6000:]))
        return r.stdout

    venv = os.path.join(work, "venv")
    step("venv", [sys.executable, "-m", "venv", "--system-site-packages", venv])
    py = os.path.join(venv, "bin", "python")
    step("pip install", [py, "-m", "pip", "install", "--no-build-isolation", root])
    elsewhere = os.path.join(work, "elsewhere")
    os.makedirs(elsewhere)
    where = step("import", [py, "-c", "import qmotion; print(qmotion.__file__)"], cwd=elsewhere)
    if not os.path.realpath(where.strip()).startswith(os.path.realpath(venv)):
        sys.exit("FAIL: qmotion was imported from %s, not from the venv" % where.strip())
    module_dir = os.path.dirname(where.strip())
    ldd = step("ldd", ["ldd", where.strip()])
    lib = [l for l in ldd.splitlines() if "libqmotion.so" in l]
    if not lib or module_dir not in lib[0]:
        sys.exit("FAIL: the module does not load the venv's libqmotion.so: %s" % lib)
    out = os.path.join(elsewhere, "out")
    os.makedirs(out)
    step("tour", [py, os.path.join(root, "examples", "python", "tour.py"), poses, out],
         cwd=elsewhere)
    if not os.path.getsize(os.path.join(out, "tour_tube.step")):
        sys.exit("FAIL: the tour wrote no STEP file")
    dist = os.path.join(work, "dist")
    step("pip wheel", [py, "-m", "pip", "wheel", "--no-build-isolation", "--no-deps", "-w",
                       dist, root])
    wheels = [f for f in os.listdir(dist) if f.endswith(".whl")]
    if len(wheels) != 1 or "linux" not in wheels[0]:
        sys.exit("FAIL: expected one platform wheel in %s, found %s" % (dist, wheels))
    names = zipfile.ZipFile(os.path.join(dist, wheels[0])).namelist()
    for want in ("qmotion.cpython", "libqmotion.so", "libqmotion_occt.so"):
        if not any(n.startswith(want) for n in names):
            sys.exit("FAIL: the wheel %s has no %s*: %s" % (wheels[0], want, names))
    print("pip install, tour and wheel: ok;", wheels[0], "seconds:", seconds)


if __name__ == "__main__":
    main()
