#!/usr/bin/env python3
"""The page of `qmotion view` works in headless Chromium, offline, and its kernel is ours.

For a B-spline motion (10 poses, 7 segments), a Bezier one (5 poses, affine rotation,
minimal-order translation), a KKS quaternion spline (10 poses) and a quintic one with
tensions (5 poses), writes a page with a profile, a body and a traced point, and opens
it in Debian's chromium through viewer_check.mjs (puppeteer-core, from npm ci in
tests/interop) with every request outside the file refused. Then checks:
- no console error and no request outside the file;
- the canvas is not blank (its pixels, decoded in a blank page);
- the page's WebAssembly evaluation at 50 parameters equals `qmotion eval` to 1e-12 relative;
- after editing a position and a rotation through the page's own inputs, the page's motion at
  50 parameters equals `qmotion interpolate` (or `qmotion qspline --param given`) on the
  edited poses (with the method the file records) to 1e-12 relative, and differs from the motion before the edit; the trajectory the
  page draws lies on the native one (32-bit floats);
- the other poses are unchanged;
- the page's Save buttons give a pose file from which `qmotion interpolate` (with the
  recorded method) makes the edited motion, and a motion file that `qmotion eval` finds
  equal to the page's motion, both to 1e-12 relative;
- the view buttons look from +z, -y and +x, and dragging the canvas turns the camera;
- with --volume (the B-spline case), the page draws `qmotion volume`'s mesh at the same
  tolerance (vertex for vertex, as 32-bit floats), and no volume otherwise.
A missing Chromium, Node.js or puppeteer-core fails, naming what to install and the CMake
option that turns the test off; with QMOTION_REAL_CLIENTS=OFF it exits 77 (skip).
Usage: viewer.py QMOTION DATA WORK [--screenshot PNG]
"""
import json
import math
import os
import shutil
import subprocess
import sys

import clients

SAMPLES = 50


def run(cmd):
    r = subprocess.run(cmd, capture_output=True, text=True)
    if r.returncode:
        raise SystemExit("%s failed (exit %d): %s" % (" ".join(cmd), r.returncode, r.stderr))
    return r.stdout


def native_eval(qmotion, motion, t, point=None):
    cmd = [qmotion, "eval", motion, "--t", repr(t)]
    if point:
        cmd += ["--point", ",".join(repr(x) for x in point)]
    return json.loads(run(cmd))


def interpolate_args(method):
    """The native command that makes the motion again with the page's method."""
    if "scheme" in method:  # a quaternion spline, fitted again at its knots
        args = ["qspline", "--scheme", method["scheme"], "--param", method["param"]]
        if method["scheme"] == "quintic":
            args += ["--tension", ",".join(repr(a) for a in method["tension"])]
        return args
    args = ["interpolate", "--form", method["form"], "--rotation", method["rotation"], "--translation",
            method["translation"], "--param", method["param"]]
    if method["form"] != "bezier":
        args += ["--degree", str(method["k"]), "--translation-degree", str(method["l"])]
    elif method["translation"] == "trt":
        args += ["--trt-degrees", "%d,%d" % (method["l"], method["l2"])]
    return args


def compare(what, page_samples, qmotion, motion, scale, failures):
    """The page's poses at its samples against `qmotion eval` on `motion`: largest error."""
    worst = 0.0
    for s in page_samples:
        n = native_eval(qmotion, motion, s["t"])
        p, q = s["pose"][:3], s["pose"][3:]
        dp = math.dist(p, n["position"]) / scale
        dq = math.dist(q, n["quaternion"])
        worst = max(worst, dp, dq)
    if not worst <= 1e-12:
        failures.append("%s: the page differs from qmotion eval by %.3g (relative)" % (what, worst))
    return worst


def camera_failures(name, rep):
    """Each view button looks from its direction; dragging the canvas turns the camera."""
    want = {"top": [0, 0, 1], "front": [0, -1, 0], "side": [1, 0, 0]}
    failures = []
    for view, d in want.items():
        got = rep["views"][view]["from"]
        # three.js's OrbitControls keeps the camera 1e-6 rad off the poles (its makeSafe), so
        # "top" may look from 1e-6 beside +z once the animation loop has run the controls.
        if math.dist(got, d) > 1e-5:
            failures.append("%s: the %s button looks from %s, not %s" % (name, view, got, d))
    iso, orbited = rep["views"]["iso"]["from"], rep["orbited"]["from"]
    turned = math.degrees(math.acos(max(-1.0, min(1.0, sum(a * b for a, b in zip(iso, orbited))))))
    if not turned > 5:
        failures.append("%s: dragging the canvas turned the camera by %.3g degrees" % (name, turned))
    return failures


def read_obj(path):
    vertices, triangles = [], 0
    for line in open(path):
        if line.startswith("v "):
            vertices.append([float(x) for x in line.split()[1:4]])
        elif line.startswith("f "):
            triangles += 1
    return vertices, triangles


def volume_failures(name, qmotion, motion, work, tol, report, drawn):
    """The page draws `qmotion volume`'s mesh at the same tolerance (as 32-bit floats)."""
    obj = os.path.join(work, name + "-volume.obj")
    run([qmotion, "volume", motion, "--body", "cutter:ball,4,10", "--tol", repr(tol), "-o", obj])
    vertices, triangles = read_obj(obj)
    if len(drawn) != 1 or drawn[0]["triangles"] != triangles != 0 or report["volume_triangles"] != triangles:
        return ["%s: the page draws %s volume triangles, `view` reports %s, `volume` writes %d" %
                (name, [d["triangles"] for d in drawn], report["volume_triangles"], triangles)]
    xs = drawn[0]["positions"]
    scale = max(max(abs(c) for c in v) for v in vertices)
    worst = max(math.dist(xs[3 * i:3 * i + 3], v) for i, v in enumerate(vertices)) / scale
    if not worst <= 1e-6 or not 0 < report["volume_distance_bound"] <= tol:
        return ["%s: the drawn volume is %.3g (relative) off `volume`'s mesh, bound %s" %
                (name, worst, report["volume_distance_bound"])]
    return []


def case(qmotion, node, chromium, here, work, name, poses, make, edits, screenshot,
         volume_tol=None):
    """make: the command and options that make the motion from the poses."""
    failures = []
    motion = os.path.join(work, name + ".json")
    page = os.path.join(work, name + ".html")
    run([qmotion, make[0], poses, "-o", motion] + make[1:])
    point = [3.0, -2.0, 1.5]
    volume = ["--volume", "--body-tol", repr(volume_tol)] if volume_tol else []
    view_report = json.loads(run([qmotion, "view", motion, "-o", page, "--profile", "rect:4,2", "--body",
                                  "cutter:ball,4,10", "--point", "0,0,0", "--point",
                                  ",".join(map(repr, point))] + volume))
    edits_path = os.path.join(work, name + "-edits.json")
    downloads = os.path.join(work, name + "-downloads")
    shutil.rmtree(downloads, ignore_errors=True)
    os.makedirs(downloads)
    with open(edits_path, "w") as f:
        json.dump({"samples": SAMPLES, "edits": edits, "downloads": downloads}, f)
    out = os.path.join(work, name + "-report.json")
    cmd = [node, os.path.join(here, "viewer_check.mjs"), chromium, page, edits_path, out]
    if screenshot:
        cmd.append(screenshot)
    r = subprocess.run(cmd, capture_output=True, text=True, timeout=240)
    if r.returncode or not os.path.exists(out):
        return ["%s: viewer_check.mjs failed (exit %d): %s%s" % (name, r.returncode, r.stdout, r.stderr)]
    with open(out) as f:
        rep = json.load(f)
    if "failure" in rep:
        return ["%s: in the page: %s" % (name, rep["failure"])]
    if rep["console_errors"]:
        failures.append("%s: console errors: %s" % (name, rep["console_errors"]))
    if rep["outside_requests"]:
        failures.append("%s: requests outside the file: %s" % (name, rep["outside_requests"]))
    c = rep["canvas"]
    if c["drawn"] < 0.005 * c["pixels"] or c["colours"] < 4:
        failures.append("%s: the canvas looks blank: %s" % (name, c))

    # The scale of "relative": the largest position the motion reaches among the samples.
    scale = max(1.0, max(math.hypot(*s["pose"][:3]) for s in rep["before"]))
    before = compare(name + " as written", rep["before"], qmotion, motion, scale, failures)

    # The edited poses, through the native interpolate with the recorded method.
    edited = os.path.join(work, name + "-edited-poses.json")
    with open(edited, "w") as f:
        json.dump({"units": "mm", "poses": [
            dict({"position": p["position"], "rotation": {"quaternion": p["quaternion"]}},
                 **({"t": p["t"]} if p["t"] is not None else {}))
            for p in rep["poses_after"]]}, f)
    edited_motion = os.path.join(work, name + "-edited.json")
    again = interpolate_args(rep["method"])
    run([qmotion, again[0], edited, "-o", edited_motion] + again[1:])
    after = compare(name + " after the edits", rep["after"], qmotion, edited_motion, scale, failures)
    moved = max(math.dist(a["pose"][:3], b["pose"][:3]) for a, b in zip(rep["before"], rep["after"]))
    if not moved > 1e-3 * scale:
        failures.append("%s: the edits did not change the motion (%.3g)" % (name, moved))
    changed = [i for i, (a, b) in enumerate(zip(rep["poses_before"], rep["poses_after"])) if a != b]
    expected = sorted({int(e["id"].split("-")[1]) for e in edits})
    if changed != expected:
        failures.append("%s: poses %s changed, expected %s" % (name, changed, expected))
    for e in edits:
        _, i, field, k = e["id"].split("-")
        if field == "position" and rep["poses_after"][int(i)]["position"][int(k)] != e["value"]:
            failures.append("%s: pose %s's position is not the value typed" % (name, i))

    # The Save buttons' files: the pose file, read back by the native interpolate with the
    # recorded method, makes the page's edited motion; the motion file is that motion.
    saved = rep.get("downloads", {})
    if set(saved) != {"poses", "motion"}:
        failures.append("%s: the Save buttons gave %s, not a pose file and a motion file" % (name, saved))
    else:
        saved_motion = os.path.join(work, name + "-from-saved-poses.json")
        run([qmotion, again[0], saved["poses"], "-o", saved_motion] + again[1:])
        compare(name + " from the saved pose file", rep["after"], qmotion, saved_motion, scale, failures)
        compare(name + " as the saved motion file", rep["after"], qmotion, saved["motion"], scale, failures)
    failures += camera_failures(name, rep)
    if volume_tol:
        failures += volume_failures(name, qmotion, motion, work, volume_tol, view_report,
                                    rep["drawn_volume"])
    elif rep["drawn_volume"]:
        failures.append("%s: a swept volume is drawn though none was asked for" % name)

    # The drawn trajectories lie on the native ones (the page draws 32-bit floats).
    drawn_worst = 0.0
    for path in rep["drawn_paths"]:
        xs = path["positions"]
        n = len(xs) // 3
        a, b = rep["range"]
        for i in range(0, n, max(1, n // 12)):
            t = b if i == n - 1 else a + (b - a) * i / (n - 1)
            want = native_eval(qmotion, edited_motion, t, path["point"])["point"]
            drawn_worst = max(drawn_worst, math.dist(xs[3 * i:3 * i + 3], want) / scale)
    if not drawn_worst <= 1e-6:
        failures.append("%s: a drawn trajectory is %.3g (relative) off the native one"
                        % (name, drawn_worst))
    print("%s: %d paths drawn, canvas %d of %d pixels drawn, %d colours; page vs qmotion eval "
          "%.2g before and %.2g after the edits (relative); edits moved the motion by %.3g; drawn "
          "trajectory %.2g off" % (name, len(rep["drawn_paths"]), c["drawn"], c["pixels"],
                                   c["colours"], before, after, moved, drawn_worst))
    return failures


def main():
    args = sys.argv[1:]
    screenshot = None
    if "--screenshot" in args:
        i = args.index("--screenshot")
        screenshot = os.path.abspath(args[i + 1])
        del args[i:i + 2]
    qmotion, data, work = args[:3]
    here = os.path.dirname(os.path.abspath(__file__))
    node = shutil.which(os.environ.get("QMOTION_NODE", "node"))
    chromium = shutil.which(os.environ.get("QMOTION_CHROMIUM", "chromium"))
    if not node or not chromium or not os.path.isdir(os.path.join(here, "node_modules", "puppeteer-core")):
        return clients.missing("Chromium, Node.js or the npm package puppeteer-core",
                               "Debian's chromium, nodejs and npm, then npm ci in tests/interop")
    os.makedirs(work, exist_ok=True)
    five = os.path.join(work, "five.json")
    with open(os.path.join(data, "helix_10.json")) as f:
        helix = json.load(f)
    with open(five, "w") as f:
        json.dump({"units": "mm", "poses": helix["poses"][::2]}, f)
    failures = case(qmotion, node, chromium, here, work, "bspline",
                    os.path.join(data, "helix_10.json"), ["interpolate"],
                    [{"id": "pose-3-position-0", "value": 41.5},
                     {"id": "pose-6-rotation-2", "value": 35}], screenshot, volume_tol=1.0)
    failures += case(qmotion, node, chromium, here, work, "bezier", five,
                     ["interpolate", "--rotation", "affine", "--translation", "minimal"],
                     [{"id": "pose-2-position-2", "value": 12.25},
                      {"id": "pose-1-rotation-0", "value": -20}], None)
    failures += case(qmotion, node, chromium, here, work, "kks", os.path.join(data, "helix_10.json"),
                     ["qspline", "--scheme", "kks"],
                     [{"id": "pose-4-position-1", "value": 50},
                      {"id": "pose-7-rotation-1", "value": 40}], None)
    failures += case(qmotion, node, chromium, here, work, "quintic", five,
                     ["qspline", "--scheme", "quintic", "--tension", "0.2,0.5,0.8,0.5,0.3"],
                     [{"id": "pose-3-position-0", "value": -30}], None)
    for f in failures:
        print("FAIL:", f)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
