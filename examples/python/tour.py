# The README's Python tour. Usage: python3 tour.py POSES.json OUT_DIR
import sys

import qmotion

poses, out = sys.argv[1], sys.argv[2]
motion = qmotion.interpolate(poses, form="bspline", degree=3)  # the CLI's options
print(motion.info()["order"], motion.eval(0.5)["position"])
qmotion.export(motion, out + "/tour_tube.step", profile="circle:3")
report = qmotion.check(out + "/tour_tube.step", motion, profile="circle:3")
assert report["relative_deviation"] < 1e-12, report
