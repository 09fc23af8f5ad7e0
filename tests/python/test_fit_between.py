"""`fit --between` through the Python module and the command line: the same proven bounds,
within the tolerances, with the sampled check below them."""
import os
import re
import subprocess

import qmotion

EXE = os.environ["QMOTION_EXE"]
DATA = os.environ["QMOTION_TEST_DATA"]


def test_between_bounds_agree_and_hold(tmp_path):
    stream = os.path.join(DATA, "fit/noisy_helix.json")
    _, report = qmotion.fit(stream, tol=0.01, angle_tol=0.05, between=True)
    b = report["between"]
    assert b["position_sampled"] <= b["position_bound"] <= 0.01
    assert b["angle_sampled_deg"] <= b["angle_bound_deg"] <= 0.05
    _, plain = qmotion.fit(stream, tol=0.01, angle_tol=0.05)
    assert plain["between"] is None
    r = subprocess.run([EXE, "fit", stream, "--tol", "0.01", "--angle-tol", "0.05", "--between",
                        "-o", str(tmp_path / "m.json")], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    printed = float(re.search(r"between poses, position: at most (\S+) mm", r.stdout).group(1))
    assert abs(printed - b["position_bound"]) <= 1e-5 * b["position_bound"]


def test_the_docs_show_what_the_command_prints(tmp_path):
    """docs/fitting.md's two outputs of `fit` on noisy_helix.json are this build's."""
    docs = open(os.path.join(DATA, "..", "..", "docs", "fitting.md"), encoding="utf-8").read()
    blocks, block, lang = [], None, None
    for line in docs.splitlines():  # fenced blocks without a language, in order
        if line.startswith("```"):
            if block is None:
                block, lang = [], line[3:]
            else:
                if not lang:
                    blocks.append("\n".join(block))
                block = None
        elif block is not None:
            block.append(line)
    stream = os.path.join(DATA, "fit/noisy_helix.json")
    for flags, first in (([], "poses: 400"), (["--between"], "between poses, position:")):
        out = subprocess.run([EXE, "fit", stream, "--tol", "0.01", "--angle-tol", "0.05",
                              "-o", str(tmp_path / "m.json")] + flags,
                             capture_output=True, text=True).stdout
        shown = [b for b in blocks if b.startswith(first)]
        assert shown, first
        for line in shown[0].splitlines():
            assert line in out.splitlines(), line
