#!/usr/bin/env python3
"""Writes the poses of a coil: 25 poses over two turns of a helix of radius 10 and the given
pitch, the moving z axis along the helix's tangent and x pointing at its axis.

    python3 coil.py PITCH OUT.json

coil_open.json is pitch 20 and coil_tight.json pitch 2. coil_touching.json is pitch 6.02764:
a tube of radius 3 along it overlaps the next turn by about 1e-5, which CGAL's check on the
sweep's tessellation does not see and the proof on the exact surfaces does.
"""
import json
import math
import sys


def coil(pitch, radius=10.0, n=25):
    poses = []
    for k in range(n):
        th = 4 * math.pi * k / (n - 1)
        pos = [radius * math.cos(th), radius * math.sin(th), pitch * th / (2 * math.pi)]
        t = [-radius * math.sin(th), radius * math.cos(th), pitch / (2 * math.pi)]
        norm = math.sqrt(sum(a * a for a in t))
        t = [a / norm for a in t]
        x = [-math.cos(th), -math.sin(th), 0.0]
        y = [t[1] * x[2] - t[2] * x[1], t[2] * x[0] - t[0] * x[2], t[0] * x[1] - t[1] * x[0]]
        matrix = [[x[i], y[i], t[i]] for i in range(3)]
        poses.append({"t": k / (n - 1), "position": pos, "rotation": {"matrix": matrix}})
    return {"units": "mm", "poses": poses}


if __name__ == "__main__":
    with open(sys.argv[2], "w") as f:
        json.dump(coil(float(sys.argv[1])), f, indent=1)
