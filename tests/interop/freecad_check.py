# Runs inside FreeCAD (freecadcmd): reads each STEP/IGES file with FreeCAD's own importer
# and reports whether the shape is valid, how many faces it has, and how far the given
# points of the exact surface lie from it. Inputs and output through environment
# variables (freecadcmd takes no script arguments).
import json
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


report["ops"] = {}
for case in json.loads(os.environ.get("QMOTION_FC_OPS", "[]")):
    shape = Part.read(case["file"])
    r = {"valid": shape.isValid(), "faces": len(shape.Faces), "closed": shape.isClosed()}
    r["offset"] = attempt(lambda: shape.makeOffsetShape(0.5, 1e-6))
    if case["solid"]:
        r["thicken"] = attempt(lambda: shape.makeThickness([], 0.5, 1e-6))
        r["volume"] = shape.Volume
        box = shape.BoundBox
        cutter = Part.makeBox(box.XLength, box.YLength / 2, box.ZLength,
                              FreeCAD.Vector(box.XMin, box.YMin, box.ZMin))
        r["cut"] = attempt(lambda: cutter.cut(shape))
    else:
        r["thicken"] = attempt(lambda: shape.makeOffsetShape(0.5, 1e-6, fill=True))
    report["ops"][case["name"]] = r

with open(os.environ["QMOTION_FC_RESULT"], "w") as out:
    json.dump(report, out, indent=1)
os._exit(0)  # freecadcmd would otherwise wait for more input
