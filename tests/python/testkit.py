"""What the Python tests share: the command line and test data they are given (QMOTION_EXE,
QMOTION_TEST_DATA), and the pose arithmetic they write out for themselves, so that they do
not check qmotion with qmotion."""
import os
import subprocess

import numpy as np

EXE = os.environ["QMOTION_EXE"]
DATA = os.environ["QMOTION_TEST_DATA"]


def data(rel):
    return os.path.join(DATA, rel)


def cli(*args):
    return subprocess.run([EXE] + [str(a) for a in args], capture_output=True, text=True)


def rotation_of(rotation):
    """The rotation matrix of a pose file's quaternion or axis_angle, written out here."""
    if "quaternion" in rotation:
        w, x, y, z = np.array(rotation["quaternion"]) / np.linalg.norm(rotation["quaternion"])
    else:
        axis = np.array(rotation["axis_angle"]["axis"], dtype=float)
        half = np.radians(rotation["axis_angle"]["angle_deg"]) / 2
        w, (x, y, z) = np.cos(half), np.sin(half) * axis / np.linalg.norm(axis)
    return np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
                     [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
                     [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]])
