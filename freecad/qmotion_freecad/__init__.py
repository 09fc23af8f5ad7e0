"""qmotion in FreeCAD's feature tree (docs/freecad.md): motions, trajectories, sweeps and
swept volumes as parametric Part::FeaturePython objects that recompute when their inputs
change.

    import qmotion_freecad as qf
    m = qf.make_motion(doc, [placement0, placement1, placement2])   # or a pose file
    s = qf.make_sweep(doc, m, doc.getObject("Sketch"))
    t = qf.make_trajectory(doc, m, (0, 0, 20))
    v = qf.make_swept_volume(doc, m, "cutter:ball,6,20", tol=0.05)
    doc.recompute()
"""
from .features import (MotionFeature, SweepFeature, SweptVolumeFeature, TrajectoryFeature,
                       make_motion, make_sweep, make_swept_volume, make_trajectory, motion_of)

__all__ = ["make_motion", "make_sweep", "make_swept_volume", "make_trajectory", "motion_of",
           "MotionFeature", "SweepFeature", "SweptVolumeFeature", "TrajectoryFeature"]
