# FreeCAD macro: the kinematic surface of a profile under a qmotion motion, built as
# Part.BSplineSurface objects from qmotion's own poles, weights and knots (no file in
# between) and added to the active document.
#
# In FreeCAD's Python console (the qmotion module and the add-on qmotion_freecad installed,
# or the macro run from a clone, which finds the add-on beside examples/):
#     exec(open("/path/to/qmotion_sweep.py").read())
#     qmotion_sweep("poses.json", "circle:3")
# or change POSES and PROFILE below and run it as a macro.
import os
import sys

import FreeCAD

import qmotion

try:  # the add-on's conversions (freecad/, docs/guide/freecad.md), installed or in a clone
    from qmotion_freecad.shapes import part_surface
except ImportError:
    sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "freecad"))
    from qmotion_freecad.shapes import part_surface

POSES = "poses.json"  # a pose file (docs/formats.md), or a list of rows [t, x, y, z, qw, qx, qy, qz]
PROFILE = "circle:3"  # any qmotion profile: a .json/.step/.igs file, rect:w,h, segment:...


def qmotion_sweep(poses=POSES, profile=PROFILE, doc=None, **options):
    """Interpolates the poses (options as for qmotion.interpolate), sweeps the profile and
    adds one Part::Feature per profile edge to the document. Returns the surfaces."""
    motion = qmotion.interpolate(poses, **options)
    surfaces = [part_surface(s) for s in qmotion.sweep(motion, profile)]
    doc = doc or FreeCAD.ActiveDocument or FreeCAD.newDocument("qmotion")
    for i, bs in enumerate(surfaces):
        doc.addObject("Part::Feature", "qmotion_sweep_%d" % i).Shape = bs.toShape()
    doc.recompute()
    return surfaces


if __name__ == "__main__" and FreeCAD.GuiUp:
    qmotion_sweep()
