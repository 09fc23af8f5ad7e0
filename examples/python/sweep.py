#!/usr/bin/env python3
"""The main job from Python: poses -> motion -> exact sweep of a circle -> STEP shell and
solid -> read back and checked. Usage: sweep.py POSES.json [OUT_DIR]"""
import os
import sys

import qmotion


def main(poses, out):
    os.makedirs(out, exist_ok=True)
    motion = qmotion.interpolate(poses)  # elliptic + TR (Bezier up to six poses, B-spline beyond)
    info = motion.info()
    print("motion: %s of degree %d, order %d, max residual %.2g"
          % (info["basis"], info["degree"], info["order"], max(info["interpolation_residual"])))
    surface = qmotion.sweep(motion, "circle:3")[0]
    print("surface: degrees %d x %d, %d x %d poles" % ((surface.degree_u, surface.degree_v) + surface.weights.shape))
    for name, solid in (("tube.step", False), ("tube_solid.step", True)):
        path = os.path.join(out, name)
        try:
            written = qmotion.export(motion, path, profile="circle:3", solid=solid)
        except ArithmeticError as e:  # e.g. the region sweeps back over itself
            print("%s: not written: %s" % (name, e))
            continue
        check = qmotion.check(path, motion, profile="circle:3")
        print("%s: %d faces, relative deviation %.1e, valid %s, closed %s"
              % (name, written["faces"], check["relative_deviation"], check["valid"], check["closed"]))
    return 0


if __name__ == "__main__":
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    sys.exit(main(sys.argv[1], sys.argv[2] if len(sys.argv) > 2 else "sweep-out"))
