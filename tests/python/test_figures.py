"""Figures through the command line and the Python module: the SVG of `render` against this
test's own projection of the key poses, `plot`'s marks and series, and both as calls. Run by
CTest (python.pytest) like test_qmotion.py."""
import json

import numpy as np
import pytest

import qmotion
from testkit import cli, data, rotation_of


def test_render_svg_is_well_formed_and_key_cube_corners_land_where_projected(tmp_path):
    """The SVG parses as XML and holds one trajectory per --point, one marker per instant and
    per key pose; the corner of each key pose's cube nearest the viewer, projected by this
    test's own orthographic projection, is a vertex of a drawn key face within a pixel."""
    import xml.etree.ElementTree as ET
    motion, svg = tmp_path / "m.json", tmp_path / "fig.svg"
    poses_file = data("poses/five_positions.json")
    assert cli("interpolate", poses_file, "-o", motion).returncode == 0
    r = cli("render", motion, "-o", svg, "--point", "0,0,0", "--point", "5,5,0",
            "--point", "0,0,30", "--frames", "6", "--view", "iso", "--object-size", "8")
    assert r.returncode == 0, r.stderr
    root = ET.parse(svg).getroot()
    ns = "{http://www.w3.org/2000/svg}"
    by_class = {}
    for e in root.iter():
        c = e.get("class")
        if c:
            by_class.setdefault(c, []).append(e)
    poses = json.load(open(poses_file))["poses"]
    assert len(by_class["trajectory"]) == 3
    assert all(e.tag == ns + "polyline" for e in by_class["trajectory"])
    assert len(by_class["object-pose"]) == 6
    assert len(by_class["key-marker"]) == len(poses)
    # The projection, computed here: iso looks from (1,1,1), z up on the page.
    d = np.ones(3) / np.sqrt(3)
    right = np.cross([0, 0, 1], d)
    right /= np.linalg.norm(right)
    up = np.cross(d, right)
    scale = float(root.get("data-scale"))
    origin = np.array([float(v) for v in root.get("data-origin").split(",")])
    assert float(root.get("data-object-size")) == 8
    vertices = []
    for e in by_class["key-face"]:
        for pair in e.get("points").split():
            vertices.append([float(v) for v in pair.split(",")])
    vertices = np.array(vertices)
    for pose in poses:
        rot = pose["rotation"]
        R = rotation_of(rot)
        p = np.asarray(pose["position"], float)
        corners = [R @ (4.0 * np.array([sx, sy, sz])) + p
                   for sx in (-1, 1) for sy in (-1, 1) for sz in (-1, 1)]
        nearest = max(corners, key=lambda c: c @ d)
        px = origin + scale * np.array([nearest @ right, -(nearest @ up)])
        assert np.min(np.linalg.norm(vertices - px, axis=1)) <= 1.0, (pose, px)


def test_plot_svg_marks_every_key_and_draws_every_motion(tmp_path):
    import xml.etree.ElementTree as ET
    a, b, svg = tmp_path / "a.json", tmp_path / "b.json", tmp_path / "plot.svg"
    poses_file = data("poses/five_positions.json")
    assert cli("interpolate", poses_file, "-o", a).returncode == 0
    assert cli("interpolate", poses_file, "-o", b, "--rotation", "affine").returncode == 0
    r = cli("plot", a, "--compare", b, "-o", svg, "--quantity", "curvature", "--point", "0,0,10")
    assert r.returncode == 0, r.stderr
    root = ET.parse(svg).getroot()
    classes = [e.get("class") for e in root.iter() if e.get("class")]
    assert classes.count("key-line") == 2 * 5
    assert classes.count("series") >= 2


def test_render_and_plot_as_calls(tmp_path):
    m = qmotion.interpolate(data("poses/five_positions.json"))
    r = qmotion.render(m, str(tmp_path / "f.png"), points=[[0, 0, 0], [0, 0, 20]],
                       profile="segment:0,0,0:0,0,10", size=(400, 300), frames=3)
    assert (r["width"], r["height"], r["trajectories"], r["object_poses"], r["key_poses"]) == \
        (400, 300, 2, 3, 5)
    assert (tmp_path / "f.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    q = qmotion.qspline(data("poses/five_positions.json"), scheme="quartic")
    series = qmotion.plot([m, q], str(tmp_path / "p.svg"), quantity="angular-speed")
    assert len(series) == 2
    for s in series:
        assert len(s["t"]) == len(s["value"]) >= 600
        assert s["min"] <= s["max"] == pytest.approx(np.nanmax(s["value"]))
    with pytest.raises(ValueError, match="--view sideways"):
        qmotion.render(m, str(tmp_path / "g.svg"), view="sideways")
    assert not (tmp_path / "g.svg").exists()
