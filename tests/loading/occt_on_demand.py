#!/usr/bin/env python3
"""OpenCASCADE is loaded only by the commands that need it (docs/architecture.md).

    occt_on_demand.py QMOTION DATA_DIR WORK_DIR

The dynamic loader's own record (LD_DEBUG=files) says which libraries a run opened: no
OpenCASCADE toolkit and no libqmotion_occt for --version, interpolate, info, eval and
JSON output; both for STEP and IGES output and for reading a STEP profile back.
"""
import os
import subprocess
import sys


def opened(exe, args, cwd):
    env = dict(os.environ, LD_DEBUG="files")
    r = subprocess.run([exe] + args, cwd=cwd, env=env, capture_output=True, text=True)
    if r.returncode != 0:
        sys.exit(f"qmotion {' '.join(args)} exited {r.returncode}: {r.stderr[-2000:]}")
    # The loader's lines read "file=NAME [0];  needed by ..." or "... dynamically loaded by".
    return {line.split("file=")[1].split()[0].split("/")[-1]
            for line in r.stderr.splitlines() if "file=" in line}


def main():
    exe, data, work = sys.argv[1:4]
    os.makedirs(work, exist_ok=True)
    poses = os.path.join(data, "poses", "five_positions.json")
    without = [
        ["--version"],
        ["interpolate", poses, "-o", "m.json"],
        ["info", "m.json"],
        ["eval", "m.json", "--t", "0.5"],
        ["trajectory", "m.json", "--point", "1,2,3", "-o", "tr.json"],
        ["sweep", "m.json", "--profile", "circle:3", "-o", "sw.json"],
    ]
    with_occt = [
        ["trajectory", "m.json", "--point", "1,2,3", "-o", "tr.step"],
        ["sweep", "m.json", "--profile", "rect:4,2", "-o", "sw.igs"],
        ["sweep", "m.json", "--profile", "tr.step", "-o", "sw2.json"],
    ]
    failures = 0
    for args in without:
        names = opened(exe, args, work)
        occt = sorted(n for n in names if n.startswith("libTK") or n.startswith("libqmotion_occt"))
        if occt:
            print(f"FAIL: qmotion {' '.join(args)} loaded {', '.join(occt)}")
            failures += 1
        else:
            print(f"ok: qmotion {' '.join(args)} loaded no OpenCASCADE ({len(names)} libraries)")
    for args in with_occt:
        names = opened(exe, args, work)
        missing = [n for n in ("libqmotion_occt.so", "libTKernel.so")
                   if not any(m.startswith(n) for m in names)]
        if missing:
            print(f"FAIL: qmotion {' '.join(args)} did not load {', '.join(missing)}")
            failures += 1
        else:
            print(f"ok: qmotion {' '.join(args)} loaded libqmotion_occt and OpenCASCADE")
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
