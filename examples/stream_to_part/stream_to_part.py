#!/usr/bin/env python3
"""The whole loop, from a noisy pose stream to the material a cutter removes.

A CAM system's G1 stream of 10^4 poses for a ball cutter (D 6 mm) along a wavy groove, tool
tilting as it goes, with measurement-like noise (within a third of the tolerances), goes
through qmotion's commands:

  1. fit --between      a lean motion within 0.01 mm / 0.05 deg of the stream's polyline,
                        proven along the whole motion;
  2. toolpath --rotary  G-code for a table-tilting A/C machine, certified for what the
                        machine's own linear interpolation of its axes does;
  3. volume             the ball cutter's swept volume, a mesh that encloses it for certain;
  4. render             a figure of the motion and the swept volume.

Usage: stream_to_part.py QMOTION OUT_DIR [--table FILE] [--check-docs docs/fitting.md]
Writes the stream, the motion, the program, the mesh and the figure into OUT_DIR, prints
what each step reports, and checks every promise the steps make (exit 1 if one fails).
With --table, writes the figures as a Markdown table; --check-docs fails unless the page
holds that very table between its <!-- stream_to_part --> markers (CTest runs it so).
"""
import argparse
import json
import math
import os
import random
import re
import subprocess
import sys

POSES = 10000
TOL, ANGLE_TOL = 0.01, 0.05  # mm, degrees
CHORD_TOL = 0.01
VOLUME_TOL = 0.1
CUTTER = "cutter:ball,6,20"


def quaternion(axis, angle):
    n = math.sqrt(sum(a * a for a in axis))
    s = math.sin(angle / 2) / n
    return (math.cos(angle / 2), axis[0] * s, axis[1] * s, axis[2] * s)


def multiply(a, b):
    return (a[0] * b[0] - a[1] * b[1] - a[2] * b[2] - a[3] * b[3],
            a[0] * b[1] + a[1] * b[0] + a[2] * b[3] - a[3] * b[2],
            a[0] * b[2] - a[1] * b[3] + a[2] * b[0] + a[3] * b[1],
            a[0] * b[3] + a[1] * b[2] - a[2] * b[1] + a[3] * b[0])


def write_stream(path):
    """The groove: 200 mm along x, waving in y and z; the tool tilts by up to 20 degrees about
    y and 10 about x. Each pose moved by less than TOL/3.5 and turned by less than
    ANGLE_TOL/3.5 (a random direction, a uniform length)."""
    rng = random.Random(54)
    with open(path, "w") as f:
        f.write("x,y,z,qw,qx,qy,qz\n")
        for i in range(POSES):
            u = i / (POSES - 1)
            x, y, z = 200 * u, 20 * math.sin(2 * math.pi * u * 2), 5 * math.cos(2 * math.pi * u)
            r = multiply(quaternion((0, 1, 0), math.radians(20) * math.sin(2 * math.pi * u)),
                         quaternion((1, 0, 0), math.radians(10) * math.cos(3 * math.pi * u)))
            d = [rng.gauss(0, 1) for _ in range(3)]
            n = math.sqrt(sum(c * c for c in d))
            k = TOL / 3.5 * rng.random() / n
            x, y, z = x + d[0] * k, y + d[1] * k, z + d[2] * k
            a = [rng.gauss(0, 1) for _ in range(3)]
            r = multiply(r, quaternion(a, math.radians(ANGLE_TOL / 3.5) * rng.random()))
            f.write("%.6f,%.6f,%.6f,%.12f,%.12f,%.12f,%.12f\n" % ((x, y, z) + r))


def run(exe, *args):
    r = subprocess.run([exe] + [str(a) for a in args], capture_output=True, text=True)
    if r.returncode != 0:
        sys.exit("qmotion %s failed (%d): %s" % (args[0], r.returncode, r.stderr))
    return r


def number(pattern, text):
    return float(re.search(pattern, text).group(1))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("qmotion")
    ap.add_argument("out")
    ap.add_argument("--table")
    ap.add_argument("--check-docs")
    a = ap.parse_args()
    os.makedirs(a.out, exist_ok=True)
    path = lambda name: os.path.join(a.out, name)
    write_stream(path("stream.csv"))
    failures = []

    fit = run(a.qmotion, "fit", path("stream.csv"), "--tol", TOL, "--angle-tol", ANGLE_TOL,
              "--between", "-o", path("motion.json")).stdout
    points = int(number(r"control points: (\d+)", fit))
    pos_bound = number(r"between poses, position: at most (\S+) mm", fit)
    ang_bound = number(r"between poses, angle: at most (\S+) deg", fit)
    if not (pos_bound <= TOL and ang_bound <= ANGLE_TOL):
        failures.append("fit: a bound above the tolerance")

    tp = json.loads(run(a.qmotion, "toolpath", path("motion.json"), "--point", "0,0,0",
                        "--chord-tol", CHORD_TOL, "--rotary", "ac", "--c-hold", "-o",
                        path("groove.ngc")).stdout)
    if not (tp["max_path_deviation_bound"] <= CHORD_TOL and
            tp["machine_interpolation_bound"] <= CHORD_TOL):
        failures.append("toolpath: a bound above the chord tolerance")

    vol = json.loads(run(a.qmotion, "volume", path("motion.json"), "--body", CUTTER, "--tol",
                         VOLUME_TOL, "-o", path("groove.stl")).stdout)
    if not (vol["distance_bound"] <= VOLUME_TOL and vol["closed"]):
        failures.append("volume: bound above the tolerance or an open mesh")

    run(a.qmotion, "render", path("motion.json"), "-o", path("figure.svg"), "--body", CUTTER,
        "--view", "iso", "--frames", "5", "--title", "stream to part")
    if "swept-volume" not in open(path("figure.svg")).read():
        failures.append("render: no swept volume in the figure")
    run(a.qmotion, "render", path("motion.json"), "-o", path("figure.png"), "--body", CUTTER,
        "--view", "iso", "--frames", "5", "--title", "stream to part", "--size", "800,450")

    rows = [
        ("stream", "%d poses, noise within %.4g mm and %.4g deg" % (POSES, TOL / 3.5, ANGLE_TOL / 3.5)),
        ("fit --between", "%d control points (%.0f times fewer than poses); proven between poses: "
         "%.3g mm, %.3g deg" % (points, POSES / points, pos_bound, ang_bound)),
        ("toolpath --rotary ac", "%d blocks; proven: chords within %.3g mm, the machine's "
         "interpolation of its axes within %.3g mm (tolerance %g mm)" %
         (tp["segments"], tp["max_path_deviation_bound"], tp["machine_interpolation_bound"],
          CHORD_TOL)),
        ("volume", "%d triangles, every vertex within %.3g mm (proven), closed: %s" %
         (vol["triangles"], vol["distance_bound"], "yes" if vol["closed"] else "no")),
        ("", "volume between %.0f and %.0f mm^3 (certified)" % tuple(vol["volume_bounds"])),
        ("render", "`figure.svg`: the motion and its swept volume"),
    ]
    table = "| step | result |\n| --- | --- |\n" + "".join("| %s | %s |\n" % r for r in rows)
    print(table)
    if a.table:
        open(a.table, "w").write(table)
    if a.check_docs:  # the table docs/fitting.md quotes between its markers
        text = open(a.check_docs).read()
        m = re.search(r"<!-- stream_to_part -->\n(.*?)<!-- /stream_to_part -->", text, re.S)
        if not m or m.group(1) != table:
            failures.append("%s: the stream_to_part table is not this run's" % a.check_docs)
    for f in failures:
        print("stream_to_part: " + f, file=sys.stderr)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
