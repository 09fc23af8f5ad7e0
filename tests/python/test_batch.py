"""examples/python/batch_dask.py on a Dask LocalCluster of two worker processes: the same
table of results as the serial run, refusals included (docs/library.md, "Batches on a
cluster"). The motions cross between processes pickled, so equal rows are also a check
that they arrive intact."""
import json
import os
import shutil
import subprocess
import sys

from testkit import data

EXAMPLE = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "examples",
                       "python", "batch_dask.py")
INPUTS = ("poses/five_positions.json", "poses/short_tilt.json", "robot/pick.script",
          "bad_poses/bad_decreasing_t.json")


def run(folder, out, *how):
    r = subprocess.run([sys.executable, EXAMPLE, folder, out, "--tol", "0.5",
                        "--body", "cutter:flat,6,20", *how],
                       capture_output=True, text=True, timeout=600)
    assert r.returncode == 0, r.stderr
    summary = json.loads(r.stdout.strip().splitlines()[-1])
    rows = json.load(open(os.path.join(out, "results.json")))
    return summary, rows


def test_the_cluster_gives_the_serial_table(tmp_path):
    folder = tmp_path / "in"
    folder.mkdir()
    for rel in INPUTS:
        shutil.copy(data(rel), folder)
    serial, a = run(str(folder), str(tmp_path / "serial"), "--serial")
    cluster, b = run(str(folder), str(tmp_path / "cluster"), "--workers", "2")
    assert serial["files"] == cluster["files"] == len(INPUTS)
    assert cluster["how"] == "2 local workers"
    strip = lambda rows: [{k: v for k, v in r.items() if k != "seconds"} for r in rows]
    assert strip(a) == strip(b)
    by_file = {r["file"]: r for r in a}
    refused = by_file["bad_decreasing_t.json"]
    assert refused["status"] == "refused" and refused["message"].startswith("ValueError: ")
    assert "bad_decreasing_t.json" in refused["message"]
    for name in ("five_positions.json", "short_tilt.json", "pick.script"):
        r = by_file[name]
        assert r["status"] == "done", r
        assert r["relative_deviation"] < 1e-12 and 0 < r["distance_bound"] <= 0.5
        assert 0 < r["volume_lower"] < r["volume_upper"] and r["volume_triangles"] > 0
        assert os.path.getsize(tmp_path / "cluster" / (os.path.splitext(name)[0] + ".step")) > 0
    assert by_file["pick.script"]["kind"] == "q-motion" and by_file["pick.script"]["degree"] >= 3
    header = open(tmp_path / "cluster" / "results.csv").readline().strip().split(",")
    assert header[:3] == ["file", "status", "message"]


def test_a_fitted_batch_on_the_cluster_is_the_serial_one(tmp_path):
    folder = tmp_path / "in"
    folder.mkdir()
    shutil.copy(data("fit/noisy_helix.json"), folder)
    _, a = run(str(folder), str(tmp_path / "serial"), "--serial", "--fit", "0.05")
    _, b = run(str(folder), str(tmp_path / "cluster"), "--workers", "2", "--fit", "0.05")
    assert [r.pop("seconds") >= 0 for r in a + b] == [True, True]
    assert a == b and a[0]["status"] == "done" and a[0]["segments"] > 1, a
