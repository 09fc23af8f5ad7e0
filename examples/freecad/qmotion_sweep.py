# FreeCAD macro: the kinematic surface of a profile under a qmotion motion, built as
# Part.BSplineSurface objects from qmotion's own poles, weights and knots (no file in
# between) and added to the active document.
#
# In FreeCAD's Python console (the qmotion module installed, or on sys.path):
#     exec(open("/path/to/qmotion_sweep.py").read())
#     qmotion_sweep("poses.json", "circle:3")
# or change POSES and PROFILE below and run it as a macro.
import FreeCAD
import Part

import qmotion

POSES = "poses.json"  # a pose file (docs/formats.md), or a list of rows [t, x, y, z, qw, qx, qy, qz]
PROFILE = "circle:3"  # any qmotion profile: a .json/.step/.igs file, rect:w,h, segment:...


def distinct(knots):
    """Full clamped knot vector -> (distinct values, multiplicities), FreeCAD's convention."""
    values, mults = [], []
    for k in knots:
        if values and values[-1] == k:
            mults[-1] += 1
        else:
            values.append(float(k))
            mults.append(1)
    return values, mults


def to_part_surface(s):
    """A qmotion.NurbsSurface as a Part.BSplineSurface (same poles, weights, knots: u = t)."""
    uk, um = distinct(s.knots_u)
    vk, vm = distinct(s.knots_v)
    poles = [[FreeCAD.Vector(*p) for p in row] for row in s.poles.tolist()]
    weights = s.weights.tolist()
    bs = Part.BSplineSurface()
    bs.buildFromPolesMultsKnots(poles, um, vm, uk, vk, False, False, s.degree_u, s.degree_v, weights)
    return bs


def qmotion_sweep(poses=POSES, profile=PROFILE, doc=None, **options):
    """Interpolates the poses (options as for qmotion.interpolate), sweeps the profile and
    adds one Part::Feature per profile edge to the document. Returns the surfaces."""
    motion = qmotion.interpolate(poses, **options)
    surfaces = [to_part_surface(s) for s in qmotion.sweep(motion, profile)]
    doc = doc or FreeCAD.ActiveDocument or FreeCAD.newDocument("qmotion")
    for i, bs in enumerate(surfaces):
        doc.addObject("Part::Feature", "qmotion_sweep_%d" % i).Shape = bs.toShape()
    doc.recompute()
    return surfaces


if __name__ == "__main__" and FreeCAD.GuiUp:
    qmotion_sweep()
