"""Robot programs through the Python module: the same poses as the command line, options
included, the same refusals, and skipped statements as Python warnings."""
import json
import os
import subprocess
import warnings

import pytest

import qmotion

EXE = os.environ["QMOTION_EXE"]
DATA = os.environ["QMOTION_TEST_DATA"]

CASES = [
    ("robot/cell.src", dict(robot_config="robot/config.dat", tool="1"),
     ["--robot-config", "robot/config.dat", "--tool", "1"]),
    ("robot/cell.src", dict(robot_config="robot/config.dat", tool="2", base="1"),
     ["--robot-config", "robot/config.dat", "--tool", "2", "--base", "1"]),
    ("robot/cell.mod", dict(tool="gun"), ["--tool", "gun"]),
    ("robot/pick.script", dict(), []),
    ("bad_poses/bad_urscript_call.script", dict(skip_unknown=True), ["--skip-unknown"]),
]


def absolute(args):
    return [os.path.join(DATA, a) if a.startswith(("robot/", "bad_poses/")) else a for a in args]


@pytest.mark.parametrize("program,kwargs,flags", CASES)
def test_programs_read_as_the_command_line_reads_them(program, kwargs, flags, tmp_path):
    out = tmp_path / "poses.json"
    r = subprocess.run([EXE, "poses", os.path.join(DATA, program), "-o", str(out)] +
                       absolute(flags), capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    kw = {k: (os.path.join(DATA, v) if k == "robot_config" else v) for k, v in kwargs.items()}
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        poses = qmotion.read_poses(os.path.join(DATA, program), **kw)
    assert poses.to_dict() == json.loads(out.read_text())
    assert len(caught) == r.stderr.count("qmotion: warning:")


def test_skipped_statements_are_warnings_naming_the_line():
    with pytest.warns(UserWarning, match=r"bad_urscript_call.script: line 3: 'open_gripper\(\)'"):
        qmotion.read_poses(os.path.join(DATA, "bad_poses/bad_urscript_call.script"),
                           skip_unknown=True)


def test_refusals_name_the_line():
    with pytest.raises(ValueError, match=r"cell.src: line 21: this move uses TOOL_DATA\[2\]"):
        qmotion.read_poses(os.path.join(DATA, "robot/cell.src"))
    with pytest.raises(ValueError, match=r"--tool and --base need --robot-config"):
        qmotion.read_poses(os.path.join(DATA, "robot/cell.src"), tool="1")
