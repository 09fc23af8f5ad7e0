# Runs inside FreeCAD (freecadcmd): reads each STEP/IGES file with FreeCAD's own importer
# and reports whether the shape is valid, how many faces it has, and how far the given
# points of the exact surface lie from it. Inputs and output through environment
# variables (freecadcmd takes no script arguments).
import json
import math
import os

import FreeCAD
import Part

points = json.load(open(os.environ["QMOTION_FC_POINTS"]))
report = {}
for path in os.environ["QMOTION_FC_FILES"].split(","):
    shape = Part.read(path)
    worst = 0.0
    for p in points:
        worst = max(worst, shape.distToShape(Part.Vertex(FreeCAD.Vector(*p)))[0])
    diagonal = shape.BoundBox.DiagonalLength
    report[path] = {
        "valid": shape.isValid(),
        "faces": len(shape.Faces),
        "max_distance": worst,
        "relative_distance": worst / diagonal if diagonal > 0 else worst,
        "freecad": ".".join(FreeCAD.Version()[:3]),
    }
def attempt(f):
    try:
        shape = f()
        return bool(shape is not None and not shape.isNull() and shape.isValid())
    except Exception as e:  # FreeCAD raises Part.OCCError and others
        return "error: " + str(e)[:200]


def uv_exchanged(shape):
    """The same solid with each B-spline face's U and V exchanged: identical geometry."""
    faces = []
    for f in shape.Faces:
        g = f.Surface
        if hasattr(g, "exchangeUV"):
            g = g.copy()
            g.exchangeUV()
            faces.append(Part.Face(g))
        else:
            faces.append(f)
    return Part.Solid(Part.Shell(faces))


# FreeCAD's Shape.Volume (OpenCASCADE's non-adaptive BRepGProp) integrates each face with
# one Gauss rule along U over its whole range, its size taken from the V direction and the
# boundary curves only. On a surface whose detail lies along U that rule is too small. Shown
# on a solid FreeCAD makes itself, no qmotion involved: a pipe along a wavy interpolated path
# (its 95 quintic spans along V), and the same solid with U and V exchanged.
def wavy_pipe():
    V = FreeCAD.Vector
    path = Part.BSplineCurve()
    path.interpolate([V(4 * i, 6 * math.sin(0.9 * i), 4 * math.cos(0.6 * i)) for i in range(16)])
    edge = path.toShape()
    pipe = Part.BRepOffsetAPI.MakePipeShell(Part.Wire(edge))
    pipe.setFrenetMode(True)
    pipe.setMaxDegree(5)
    pipe.setMaxSegments(500)
    start = edge.FirstParameter
    pipe.add(Part.Wire(Part.makeCircle(1.0, edge.valueAt(start), edge.tangentAt(start))))
    pipe.build()
    pipe.makeSolid()
    solid = pipe.shape()
    spans = [(f.Surface.UDegree, f.Surface.NbUKnots - 1, f.Surface.VDegree, f.Surface.NbVKnots - 1)
             for f in solid.Faces if hasattr(f.Surface, "NbUKnots")]
    return {"valid": solid.isValid(), "volume": abs(solid.Volume),
            "volume_uv_exchanged": abs(uv_exchanged(solid).Volume), "degrees_spans_uv": spans}


report["uv_demo"] = wavy_pipe()
report["ops"] = {}
for case in json.loads(os.environ.get("QMOTION_FC_OPS", "[]")):
    shape = Part.read(case["file"])
    r = {"valid": shape.isValid(), "faces": len(shape.Faces), "closed": shape.isClosed()}
    r["offset"] = attempt(lambda: shape.makeOffsetShape(0.5, 1e-6))
    if case["solid"]:
        r["thicken"] = attempt(lambda: shape.makeThickness([], 0.5, 1e-6))
        r["volume"] = shape.Volume
        r["volume_uv_exchanged"] = abs(uv_exchanged(shape).Volume)
        box = shape.BoundBox
        cutter = Part.makeBox(box.XLength, box.YLength / 2, box.ZLength,
                              FreeCAD.Vector(box.XMin, box.YMin, box.ZMin))
        r["cut"] = attempt(lambda: cutter.cut(shape))
        r["fuse"] = attempt(lambda: cutter.fuse(shape))
    else:
        r["thicken"] = attempt(lambda: shape.makeOffsetShape(0.5, 1e-6, fill=True))
    report["ops"][case["name"]] = r

with open(os.environ["QMOTION_FC_RESULT"], "w") as out:
    json.dump(report, out, indent=1)
os._exit(0)  # freecadcmd would otherwise wait for more input
