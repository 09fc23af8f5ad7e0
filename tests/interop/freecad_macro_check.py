# Runs inside FreeCAD (freecadcmd): the example macro builds Part.BSplineSurface objects
# from qmotion's poles, weights and knots; each, evaluated by FreeCAD at 400 (u, v), must
# equal qmotion's own evaluation within 1e-12 of the bounding-box diagonal, and its face
# must be valid. Inputs and output through environment variables.
import json
import os
import random
import sys

import FreeCAD

sys.path.insert(0, os.environ["QMOTION_FC_MACRO_DIR"])
import qmotion  # noqa: E402 (on PYTHONPATH: the built module)
import qmotion_sweep  # noqa: E402

report = {}
doc = FreeCAD.newDocument("qmotion_test")
for name, poses, profile in json.loads(os.environ["QMOTION_FC_CASES"]):
    surfaces = qmotion_sweep.qmotion_sweep(poses, profile, doc)
    ours = qmotion.sweep(qmotion.interpolate(poses), profile)
    rng = random.Random(20261201)
    worst, size, valid = 0.0, 0.0, True
    for bs, s in zip(surfaces, ours):
        box = bs.toShape().BoundBox
        size = max(size, box.DiagonalLength)
        valid = valid and bs.toShape().isValid()
        for _ in range(400):
            u = rng.uniform(s.knots_u[0], s.knots_u[-1])
            v = rng.uniform(s.knots_v[0], s.knots_v[-1])
            p = bs.value(u, v)
            q = s(u, v)
            worst = max(worst, ((p.x - q[0]) ** 2 + (p.y - q[1]) ** 2 + (p.z - q[2]) ** 2) ** 0.5)
    report[name] = {"surfaces": len(surfaces), "features": len(doc.Objects), "valid": valid,
                    "max_distance": worst, "relative": worst / size if size > 0 else worst}
with open(os.environ["QMOTION_FC_RESULT"], "w") as out:
    json.dump(report, out, indent=1)
os._exit(0)
