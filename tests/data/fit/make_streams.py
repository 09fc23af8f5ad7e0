#!/usr/bin/env python3
"""Writes the pose streams of tests/data/fit (run from this folder; the files are committed).

noisy_helix.json: 400 poses of a smooth helical motion (t in [0, 1]) moved by at most 0.003 mm
and turned by at most 0.015 degrees at random (seeded): a stream `qmotion fit --tol 0.01
--angle-tol 0.05` meets with a tenth of the poses' control points, and that --tol 1e-4 cannot.
"""
import json
import math
import random


def qmul(a, b):
    w1, x1, y1, z1 = a
    w2, x2, y2, z2 = b
    return (w1 * w2 - x1 * x2 - y1 * y2 - z1 * z2, w1 * x2 + x1 * w2 + y1 * z2 - z1 * y2,
            w1 * y2 - x1 * z2 + y1 * w2 + z1 * x2, w1 * z2 + x1 * y2 - y1 * x2 + z1 * w2)


def about(axis, angle):
    n = math.sqrt(sum(a * a for a in axis))
    s = math.sin(angle / 2)
    return (math.cos(angle / 2),) + tuple(s * a / n for a in axis)


def offset(rng, limit):
    v = [rng.gauss(0, 1) for _ in range(3)]
    n = math.sqrt(sum(c * c for c in v))
    return [c / n * limit * rng.random() for c in v]


rng = random.Random(20261204)
poses = []
for i in range(400):
    u = i / 399
    p = [60 * math.cos(3 * u), 60 * math.sin(3 * u), 40 * u]
    q = qmul(about((0, 0, 1), 3 * u), about((1, 0.3, 0), 0.5 * math.sin(2 * u)))
    p = [a + b for a, b in zip(p, offset(rng, 0.003))]
    r = offset(rng, math.radians(0.015))
    q = qmul(q, about(r, math.sqrt(sum(c * c for c in r))))
    poses.append({"t": round(u, 12), "position": [round(c, 9) for c in p],
                  "rotation": {"quaternion": [round(c, 15) for c in q]}})
with open("noisy_helix.json", "w") as f:
    json.dump({"units": "mm", "poses": poses}, f, indent=0)
    f.write("\n")
