# Runs inside FreeCAD (freecadcmd), with the add-on installed in FreeCAD's user Mod folder
# (run_freecad_features.py): qmotion's parametric features are valid after recompute, equal
# qmotion's own evaluation within 1e-12 of their size, follow an edit of their inputs, keep
# their certificates, and survive saving and reopening the document. Writes a JSON list of
# failures (empty: pass) to QMOTION_FC_RESULT.
import json
import math
import os
import random
import sys
import time

import FreeCAD
import Part

sys.path.insert(0, os.environ["QMOTION_PYTHONPATH"])
import qmotion  # noqa: E402
import qmotion_freecad as qf  # noqa: E402 (found by FreeCAD in its Mod folder)
from qmotion_freecad import shapes  # noqa: E402

failures = []
clock = {"start": time.perf_counter()}


def lap(name):
    clock[name] = round(time.perf_counter() - clock.pop("start"), 2)
    clock["start"] = time.perf_counter()


rng = random.Random(20261207)


def expect(ok, what):
    if not ok:
        failures.append(what)


def dist(p, q):
    return math.sqrt(sum((a - b) ** 2 for a, b in zip(p, q)))


def vec(v):
    return (v.x, v.y, v.z)


poses = json.load(open(os.environ["QMOTION_FC_POSES"]))["poses"]
placements, times = [], []
for p in poses:
    r = p["rotation"]
    if "quaternion" in r:
        w, x, y, z = r["quaternion"]
        rotation = FreeCAD.Rotation(x, y, z, w)
    else:
        rotation = FreeCAD.Rotation(FreeCAD.Vector(*r["axis_angle"]["axis"]),
                                    r["axis_angle"]["angle_deg"])
    placements.append(FreeCAD.Placement(FreeCAD.Vector(*p["position"]), rotation))
    times.append(p["t"])

doc = FreeCAD.newDocument("qmotion_features")
motion = qf.make_motion(doc, placements, times)
doc.recompute()
m = qf.motion_of(motion)
size = motion.Shape.BoundBox.DiagonalLength
expect(motion.Kind == "q-motion" and motion.Degree > 0 and motion.InterpolationResidual < 1e-9,
       "motion certificate: %s %s %s" % (motion.Kind, motion.Degree, motion.InterpolationResidual))
for t, pl in zip(times, placements):  # interpolation at every pose, against FreeCAD's map
    for x in ((0, 0, 0), (3, -2, 5)):
        expect(dist(m.place(t, x), vec(pl.multVec(FreeCAD.Vector(*x)))) < 1e-9 * size,
               "motion misses the placement at t = %g" % t)
expect(motion.Shape.isValid(), "the motion's trajectory is not valid")


def check_sweep(sweep, profile_obj, radius=None):
    """Faces equal qmotion's surfaces within 1e-12 of the size; on a circle of radius r about
    the moving origin every point lies r from the origin's trajectory."""
    mm = qf.motion_of(sweep.Motion)
    ours = qmotion.sweep(mm, shapes.profile_document(profile_obj.Shape))
    faces = sweep.Shape.Faces
    expect(sweep.Shape.isValid() and len(faces) == len(ours) == sweep.Faces,
           "%s: %d faces, qmotion %d, valid %s" % (sweep.Label, len(faces), len(ours),
                                                  sweep.Shape.isValid()))
    worst, box = 0.0, sweep.Shape.BoundBox.DiagonalLength
    for f, s in zip(faces, ours):
        for _ in range(200):
            u = rng.uniform(s.knots_u[0], s.knots_u[-1])
            v = rng.uniform(s.knots_v[0], s.knots_v[-1])
            p = vec(f.Surface.value(u, v))
            worst = max(worst, dist(p, s(u, v)))
            if radius is not None:
                r = dist(p, mm.place(u, (0, 0, 0)))
                expect(abs(r - radius) < 1e-9 * box, "%s: a point %g from the path, not %g" %
                       (sweep.Label, r, radius))
    expect(worst <= 1e-12 * box, "%s: %g from qmotion's surfaces (size %g)" % (sweep.Label, worst, box))
    return worst / box


circle = doc.addObject("Part::Circle", "Circle")
circle.Radius = 3
sweep = qf.make_sweep(doc, motion, circle)
doc.recompute()
report = {"circle": check_sweep(sweep, circle, 3.0)}
expect(sweep.Exact and sweep.DegreeU == qmotion.trajectory(m, (3, -2, 5)).degree and sweep.DegreeV == 2,
       "sweep certificate: %s %s %s" % (sweep.Exact, sweep.DegreeU, sweep.DegreeV))
circle.Radius = 5  # the edit: the sweep follows
doc.recompute()
report["circle_edited"] = check_sweep(sweep, circle, 5.0)

wire = doc.addObject("Part::Feature", "Wire")
wire.Shape = Part.makePolygon([FreeCAD.Vector(*p) for p in
                               ((-2, -1, 0), (2, -1, 0), (2, 1, 0), (-2, 1, 0), (-2, -1, 0))])
rect = qf.make_sweep(doc, motion, wire, name="RectSweep")
doc.recompute()
report["wire"] = check_sweep(rect, wire)
expect(rect.Faces == 4 and rect.Shape.ShapeType == "Shell",
       "a closed wire of 4 edges gives %d faces, a %s" % (rect.Faces, rect.Shape.ShapeType))

traj = qf.make_trajectory(doc, motion, (0, 0, 20))
doc.recompute()
for point in ((0, 0, 20), (4, 1, -3)):
    if point != (0, 0, 20):
        traj.Point = FreeCAD.Vector(*point)
        doc.recompute()
    c = traj.Shape.Edges[0].Curve
    worst = max(dist(vec(c.value(t)), m.place(t, point))
                for t in [times[0] + (times[-1] - times[0]) * k / 49 for k in range(50)])
    expect(worst <= 1e-12 * size, "trajectory of %s: %g from qmotion's place" % (point, worst))
    expect(traj.Exact and traj.Shape.isValid(), "trajectory certificate or validity")

lap("motion, sweeps, trajectory")
vol = qf.make_swept_volume(doc, motion, "cutter:flat,6,20", tol=2.0)
doc.recompute()
expect(vol.Shape.isValid() and vol.Shape.ShapeType == "Solid" and vol.Shape.isClosed(),
       "swept volume is not a valid closed solid")
expect(0 < vol.DistanceBound <= 2.0 and vol.Triangles == len(vol.Shape.Faces),
       "swept volume certificate: %s %s" % (vol.DistanceBound, vol.Triangles))
expect(vol.VolumeLower <= vol.Shape.Volume, "the solid holds less than the volume's lower bound")
for t in times:  # the cutter's axis end points at every pose lie inside the solid
    for x in ((0, 0, 0.01), (0, 0, 19.99), (2.9, 0, 10)):
        expect(vol.Shape.isInside(FreeCAD.Vector(*m.place(t, x)), 1e-9, True),
               "the cutter's point %s at t = %g is outside the solid" % (x, t))
lap("swept volume")
before = vol.Shape.Volume
vol.Body = "cutter:flat,4,20"
doc.recompute()
expect(vol.Shape.isValid() and vol.Shape.Volume < before, "the swept volume did not follow its body")
lap("swept volume edited")
box = doc.addObject("Part::Box", "Box")
box.Length, box.Width, box.Height = 10, 5, 3
vbox = qf.make_swept_volume(doc, motion, box, tol=2.0, name="BoxVolume")
doc.recompute()
expect(vbox.Shape.isValid() and vbox.Shape.ShapeType == "Solid", "a Part box's swept volume")
for t in times:
    for x in ((0.01, 0.01, 0.01), (9.99, 4.99, 2.99)):
        expect(vbox.Shape.isInside(FreeCAD.Vector(*m.place(t, x)), 1e-9, True),
               "the box's corner %s at t = %g is outside its swept volume" % (x, t))

lap("box volume")
# Editing the motion: every dependent recomputes to the new motion.
moved = list(motion.Placements)
moved[2] = FreeCAD.Placement(moved[2].Base + FreeCAD.Vector(0, 0, 7), moved[2].Rotation)
motion.Placements = moved
doc.recompute()
m2 = qf.motion_of(motion)
expect(dist(m2.place(times[2], (0, 0, 0)), vec(moved[2].Base)) < 1e-9 * size,
       "the edited motion misses its edited placement")
report["circle_after_motion_edit"] = check_sweep(sweep, circle, 5.0)

spline = qf.make_motion(doc, placements, times, scheme="kks", name="Kks")
ssweep = qf.make_sweep(doc, spline, circle, name="KksSweep")
doc.recompute()
expect(spline.Kind == "quaternion-spline" and not ssweep.Exact and ssweep.Shape.isValid(),
       "a quaternion spline's sweep: %s %s" % (spline.Kind, ssweep.Exact))

# Saved and reopened: the features rebuild from their properties alone.
path = os.path.join(os.environ["QMOTION_FC_WORK"], "features.FCStd")
doc.saveAs(path)
FreeCAD.closeDocument(doc.Name)
doc = FreeCAD.openDocument(path)
circle, sweep = doc.getObject("Circle"), doc.getObject("Sweep")
circle.Radius = 4
doc.recompute()
report["reopened_edited"] = check_sweep(sweep, circle, 4.0)
expect(all(o.isValid() for o in doc.Objects), "invalid objects after reopening: %s" %
       [o.Label for o in doc.Objects if not o.isValid()])

with open(os.environ["QMOTION_FC_RESULT"], "w") as out:
    lap("the rest")
    clock.pop("start")
    json.dump({"failures": failures, "relative": report, "seconds": clock}, out, indent=1)
os._exit(0)
