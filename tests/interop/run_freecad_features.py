#!/usr/bin/env python3
"""Interop test: the FreeCAD add-on (freecad/, docs/freecad.md) installed by its own rule
(`cmake --install BUILD --component freecad`, into a scratch DESTDIR) where FreeCAD looks for
add-ons, then driven headless by freecad_features_check.py: create, recompute, edit,
recompute, save, reopen.

Usage: run_freecad_features.py BUILD POSES WORK_DIR
Environment: QMOTION_PYTHONPATH (the built module's folder), QMOTION_FREECAD_MOD_DIR (the
configured add-on folder, which must end in .local/share/FreeCAD/Mod/qmotion: the test
points HOME at the scratch copy). Exit 0 pass, 1 fail (a missing freecadcmd fails), 77 skip
(QMOTION_REAL_CLIENTS=OFF).
"""
import json
import os
import shutil
import subprocess
import sys

import clients

SUFFIX = os.path.join(".local", "share", "FreeCAD", "Mod", "qmotion")


def main():
    build, poses, work = sys.argv[1:4]
    freecad = clients.freecad()
    if isinstance(freecad, int):
        return freecad
    mod = os.environ["QMOTION_FREECAD_MOD_DIR"]
    if not mod.endswith(SUFFIX):
        print("QMOTION_FREECAD_MOD_DIR=%s is not a user Mod folder (…/%s): the test cannot "
              "point FreeCAD at a scratch copy of it" % (mod, SUFFIX))
        return 1
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    stage = os.path.join(work, "destdir")
    r = subprocess.run(["cmake", "--install", build, "--component", "freecad"],
                       env=dict(os.environ, DESTDIR=stage), capture_output=True, text=True)
    if r.returncode != 0:
        print("FAIL: cmake --install --component freecad:\n" + r.stdout + r.stderr)
        return 1
    installed = stage + mod
    home = installed[: -len(SUFFIX)]
    for f in ("Init.py", "InitGui.py", "qmotion_freecad/features.py", "qmotion_freecad/icons/sweep.svg"):
        if not os.path.exists(os.path.join(installed, f)):
            print("FAIL: the install rule did not install %s" % f)
            return 1
    result = os.path.join(work, "result.json")
    env = dict(os.environ, HOME=home, QMOTION_FC_POSES=poses, QMOTION_FC_RESULT=result,
               QMOTION_FC_WORK=work)
    env.pop("XDG_DATA_HOME", None)
    env.pop("PYTHONPATH", None)  # the add-on must come from FreeCAD's Mod folder
    here = os.path.dirname(os.path.abspath(__file__))
    run = subprocess.run([freecad, os.path.join(here, "freecad_features_check.py")], env=env,
                         stdin=subprocess.DEVNULL, capture_output=True, text=True, timeout=900)
    if not os.path.exists(result):
        print("FAIL: FreeCAD wrote no result:\n" + run.stdout[-4000:] + run.stderr[-4000:])
        return 1
    report = json.load(open(result))
    print(json.dumps(report, indent=1))
    for f in report["failures"]:
        print("FAIL:", f)
    return 1 if report["failures"] else 0


if __name__ == "__main__":
    sys.exit(main())
