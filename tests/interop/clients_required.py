#!/usr/bin/env python3
"""A missing real client fails its tests (QMOTION_REAL_CLIENTS=ON, the default).

Runs the FreeCAD tests (the files, and the add-on's features) with QMOTION_FREECADCMD
naming no program, the rs274 tests of
cli_tests with QMOTION_RS274 naming no program, and the Blender and glTF validator tests
with QMOTION_BLENDER and QMOTION_NODE naming no program, the viewer's with
QMOTION_CHROMIUM naming no program, and LinuxCNC's simulator with QMOTION_LINUXCNC naming no
program: each must fail (exit 1, not the
skip code 77, not a pass) and say what to install and which CMake option turns the test off.

Usage: clients_required.py RUN_FREECAD.py QMOTION DATA CLI_TESTS WORK
"""
import os
import subprocess
import sys


def main():
    run_freecad, qmotion, data, cli_tests, work = sys.argv[1:6]
    missing = os.path.join(work, "no-such-client")
    failures = []
    env = dict(os.environ, QMOTION_FREECADCMD=missing, QMOTION_REAL_CLIENTS="ON")
    r = subprocess.run([sys.executable, run_freecad, qmotion, data, work], env=env,
                       capture_output=True, text=True)
    out = r.stdout + r.stderr
    if r.returncode != 1 or "QMOTION_REAL_CLIENTS=OFF" not in out:
        failures.append("FreeCAD missing: exit %d, expected 1 naming the option:\n%s" % (r.returncode, out))
    env = dict(os.environ, QMOTION_RS274=missing)
    r = subprocess.run([cli_tests, "--gtest_filter=Cli.Toolpath*LinuxCncs*"], env=env,
                       capture_output=True, text=True)
    out = r.stdout + r.stderr
    if r.returncode == 0 or "SKIPPED" in out or "QMOTION_REAL_CLIENTS=OFF" not in out:
        failures.append("rs274 missing: exit %d, expected a failure naming the option:\n%s"
                        % (r.returncode, out[-3000:]))
    here = os.path.dirname(os.path.abspath(__file__))
    env = dict(os.environ, QMOTION_BLENDER=missing, QMOTION_NODE=missing,
               QMOTION_CHROMIUM=missing, QMOTION_LINUXCNC=missing, QMOTION_FREECADCMD=missing,
               QMOTION_REAL_CLIENTS="ON")
    for script, args in (("run_freecad_features.py", [work, os.path.join(data, "poses", "five_positions.json")]),
                         ("blender_gltf.py", [qmotion, os.path.join(data, "helix_10.json"),
                                               "rational", "box:1,1,1", "0.01"]),
                         ("gltf_validator.py", [qmotion, data]),
                         ("viewer.py", [qmotion, data]),
                         ("linuxcnc_sim.py", [qmotion, data])):
        r = subprocess.run([sys.executable, os.path.join(here, script)] + args + [work],
                           env=env, capture_output=True, text=True)
        out = r.stdout + r.stderr
        if r.returncode != 1 or "QMOTION_REAL_CLIENTS=OFF" not in out:
            failures.append("%s with its client missing: exit %d, expected 1 naming the option:\n%s"
                            % (script, r.returncode, out[-3000:]))
    for f in failures:
        print(f)
    if not failures:
        print("a missing FreeCAD, rs274, Blender, glTF validator, Chromium and LinuxCNC each "
              "fail their tests, naming the option")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
