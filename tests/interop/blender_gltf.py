#!/usr/bin/env python3
"""Blender plays qmotion's glTF animation within the certified tolerance.

Writes a glTF animation with `qmotion animate`, imports it into Blender (headless, its own
glTF importer) and steps through it: at every keyframe and at 7 times between consecutive
keys (Blender's subframes), every vertex of the body must lie within the tolerance of where
the exact motion (`qmotion eval`) puts it, in metres. Blender blends rotations component-wise
(its quaternion f-curves), not spherically as glTF does: the certificate covers both.

Exit 0 on success, 1 on a failure. A missing Blender fails too, naming what to install and
the CMake option that turns the test off; with QMOTION_REAL_CLIENTS=OFF it exits 77 (skip).
Usage: blender_gltf.py QMOTION POSES KIND BODY TOL WORK [MAX_INTERVALS]
  KIND: rational (qmotion interpolate) or a quaternion-spline scheme (qmotion qspline)
"""
import json
import math
import os
import shutil
import struct
import subprocess
import sys

import clients


def read_glb(path):
    with open(path, "rb") as f:
        data = f.read()
    magic, version, length = struct.unpack_from("<4sII", data, 0)
    assert magic == b"glTF" and version == 2 and length == len(data), "not a GLB 2 file"
    jlen, jtype = struct.unpack_from("<I4s", data, 12)
    gltf = json.loads(data[20:20 + jlen])
    blen, btype = struct.unpack_from("<I4s", data, 20 + jlen)
    assert jtype == b"JSON" and btype == b"BIN\0"
    return gltf, data[28 + jlen:28 + jlen + blen]


def accessor(gltf, binary, index):
    acc = gltf["accessors"][index]
    view = gltf["bufferViews"][acc["bufferView"]]
    width = {"SCALAR": 1, "VEC3": 3, "VEC4": 4}[acc["type"]]
    fmt = "<%d%s" % (acc["count"] * width, "f" if acc["componentType"] == 5126 else "I")
    flat = struct.unpack_from(fmt, binary, view.get("byteOffset", 0) + acc.get("byteOffset", 0))
    return [flat[i:i + width] for i in range(0, len(flat), width)]


def rotate(q, v):  # q = (w, x, y, z), unit
    w, x, y, z = q
    r = [[1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
         [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
         [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]]
    return [sum(r[i][k] * v[k] for k in range(3)) for i in range(3)]


def main():
    qmotion, poses, kind, body, tol, work = sys.argv[1:7]
    max_intervals = int(sys.argv[7]) if len(sys.argv) > 7 else 60
    blender = os.environ.get("QMOTION_BLENDER", "blender")
    if not shutil.which(blender):
        return clients.missing("Blender (%s)" % blender, "Debian's blender")
    os.makedirs(work, exist_ok=True)
    motion = os.path.join(work, "motion.json")
    make = ([qmotion, "interpolate", poses, "-o", motion] if kind == "rational" else
            [qmotion, "qspline", poses, "--scheme", kind, "-o", motion])
    subprocess.run(make, check=True, capture_output=True)
    glb = os.path.join(work, "animation.glb")
    r = subprocess.run([qmotion, "animate", motion, "--body", body, "--tol", tol, "-o", glb],
                       capture_output=True, text=True)
    if r.returncode:
        print("qmotion animate failed:", r.stdout, r.stderr)
        return 1
    report = json.loads(r.stdout)
    gltf, binary = read_glb(glb)
    mpu = report["metres_per_unit"]
    spu = report["seconds_per_unit"]
    a = report["interval"][0]
    times = [t[0] for t in accessor(gltf, binary, gltf["animations"][0]["samplers"][0]["input"])]
    verts = accessor(gltf, binary, gltf["meshes"][0]["primitives"][0]["attributes"]["POSITION"])
    # Every key, and 7 times inside each of up to max_intervals intervals spread over the motion.
    step = max(1, (len(times) - 1) // max_intervals)
    samples = list(times)
    for i in range(0, len(times) - 1, step):
        samples += [times[i] + (times[i + 1] - times[i]) * j / 8 for j in range(1, 8)]
    samples.sort()
    fps = 24.0
    with open(os.path.join(work, "samples.json"), "w") as f:
        json.dump({"frames": [s * fps for s in samples]}, f)
    result = os.path.join(work, "result.json")
    check = os.path.join(os.path.dirname(os.path.abspath(__file__)), "blender_gltf_check.py")
    # Blender's embedded Python finds its standard library from the python3 on PATH: keep
    # another installation's (pyenv, a virtualenv) out of its way, so that it uses the
    # system's, which has the numpy its glTF importer needs.
    env = {k: v for k, v in os.environ.items() if not k.startswith(("PYENV", "PYTHON", "VIRTUAL_ENV"))}
    env["PATH"] = os.pathsep.join(p for p in os.environ.get("PATH", "").split(os.pathsep)
                                  if ".pyenv" not in p and "virtualenv" not in p and "venv" not in p)
    r = subprocess.run([blender, "--background", "--factory-startup", "--python-exit-code", "1",
                        "--python", check, "--", glb, os.path.join(work, "samples.json"), result],
                       capture_output=True, text=True, env=env)
    if r.returncode or not os.path.exists(result):
        print("Blender failed:", r.stdout[-3000:], r.stderr[-3000:])
        return 1
    with open(result) as f:
        played = json.load(f)
    if abs(played["fps"] - fps) > 0:
        print("Blender's scene runs at %g fps, the samples assumed %g" % (played["fps"], fps))
        return 1
    # Where the exact motion puts each written vertex (metres), at each sample.
    worst, worst_at, matched = 0.0, None, None
    tol_m = float(report["tolerance"]) * mpu
    for s, world in zip(samples, played["positions"]):
        t = min(max(a + s / spu, a), report["interval"][1])  # rounding of a + s / spu
        e = subprocess.run([qmotion, "eval", motion, "--t", repr(t)], capture_output=True,
                           text=True, check=True)
        pose = json.loads(e.stdout)
        p = [c * mpu for c in pose["position"]]
        exact = [[pi + ri for pi, ri in zip(p, rotate(pose["quaternion"], v))] for v in verts]
        if matched is None:  # Blender may reorder or weld vertices: match them once, nearest
            matched = [min(range(len(exact)), key=lambda j: math.dist(w, exact[j])) for w in world]
        for w, j in zip(world, matched):
            d = math.dist(w, exact[j])
            if d > worst:
                worst, worst_at = d, t
    # Blender computes in 32-bit floats: allow their rounding of the positions on top.
    extent = max(math.dist([0, 0, 0], w) for frame in played["positions"] for w in frame)
    slack = 8 * 2.0 ** -24 * extent
    print("Blender played %d keyframes; %d samples (every key and 7 between keys); largest "
          "distance of a vertex from the exact motion %.3g m at t = %s; tolerance %.3g m "
          "(+ %.2g for Blender's floats); certified bound %.3g m"
          % (len(times), len(samples), worst, worst_at, tol_m, slack,
             report["distance_bound"] * mpu))
    if len(played["positions"][0]) != len(verts):
        print("Blender's mesh has %d vertices, the file %d" % (len(played["positions"][0]), len(verts)))
    return 0 if worst <= tol_m + slack else 1


if __name__ == "__main__":
    sys.exit(main())
