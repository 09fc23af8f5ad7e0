"""The Python module against the qmotion command line: same motions bit for bit, same
sweep poles, same errors (class and message). Run by CTest (python.pytest) with the built
module on PYTHONPATH; QMOTION_EXE and QMOTION_TEST_DATA name the CLI and tests/data."""
import json
from fractions import Fraction

import numpy as np
import pytest

import qmotion
from testkit import cli, data, rotation_of


FORMS = [
    ("poses/five_positions.json", dict(rotation="elliptic", translation="tr"), []),
    ("poses/five_positions.json", dict(rotation="affine", translation="tr"), ["--rotation", "affine"]),
    ("poses/five_positions.json", dict(rotation="projective", translation="tr"), ["--rotation", "projective"]),
    ("poses/five_positions.json", dict(translation="trt"), ["--translation", "trt"]),
    ("poses/five_positions.json", dict(translation="trt", trt_degrees=(2, 1)),
     ["--translation", "trt", "--trt-degrees", "2,1"]),
    ("poses/five_positions.json", dict(translation="minimal"), ["--translation", "minimal"]),
    ("poses/three_positions_no_t.json", dict(param="chordal"), ["--param", "chordal"]),
    ("poses/helix_40.json", dict(), []),
    ("poses/helix_40.json", dict(form="bspline", degree=4, translation_degree=2),
     ["--form", "bspline", "--degree", "4", "--translation-degree", "2"]),
    ("poses/helix_40.json", dict(translation="minimal"), ["--translation", "minimal"]),
    ("poses/helix_40.json", dict(form="c1"), ["--form", "c1"]),
    ("poses/rational_exact.json", dict(exact=True), ["--exact"]),
    ("poses/rational_exact.json", dict(exact=True, form="bspline"), ["--exact", "--form", "bspline"]),
]


@pytest.mark.parametrize("poses,kwargs,flags", FORMS)
def test_interpolate_gives_the_clis_motion_bit_for_bit(tmp_path, poses, kwargs, flags):
    cli_file, py_file = tmp_path / "cli.json", tmp_path / "py.json"
    r = cli("interpolate", data(poses), "-o", cli_file, *flags)
    assert r.returncode == 0, r.stderr
    m = qmotion.interpolate(data(poses), **kwargs)
    m.save(str(py_file))
    assert py_file.read_bytes() == cli_file.read_bytes()
    # load() reads it back to the same motion, and save() writes it unchanged
    back = qmotion.load(str(cli_file))
    assert back.info() == m.info()
    back.save(str(py_file))
    assert py_file.read_bytes() == cli_file.read_bytes()
    info = m.info()
    assert max(info["interpolation_residual"]) <= 1e-9
    assert info["plucker_residual"] <= 1e-12
    # The motion value knows how it was made: what the CLI's file records, read back.
    method = json.loads(cli_file.read_text())["method"]
    for mo in (m, back):
        p = mo.provenance
        assert mo.has_factors and p is not None
        for key in ("form", "rotation", "translation", "param", "rotation_degree"):
            assert p[key] == method[key], key
        assert np.allclose(p["parameters"], [float(Fraction(str(x))) for x in method["parameters"]],
                           rtol=0, atol=1e-15)
        assert len(p["poses"]["poses"]) == len(p["parameters"]) == len(p["residuals"])
        assert max(p["residuals"]) <= 1e-9


def test_hand_written_motion_has_no_provenance(tmp_path):
    f = tmp_path / "slide.json"
    f.write_text(json.dumps({"type": "q-motion", "basis": "bezier", "degree": 1,
                             "param_range": [0, 1], "units": "mm",
                             "control_points": [[1, 0, 0, 0, 0, 0, 0, 0],
                                                [1, 0, 0, 0, 0, 10, 0, 0]]}))
    m = qmotion.load(str(f))
    assert m.provenance is None and not m.has_factors
    c = qmotion.trajectory(m, [0, 0, 0])
    assert np.allclose(c(0.5), [10, 0, 0], atol=1e-12)  # (1 + eps d) translates by 2 d


def test_poses_from_numpy_rows_interpolate_each_pose():
    # Rows t, x, y, z, qw, qx, qy, qz of a screw motion, as a numpy array.
    rows = []
    for k, t in enumerate(np.linspace(0, 1, 5)):
        half = np.radians(20 * k) / 2
        rows.append([t, 5 * np.cos(t), 5 * np.sin(t), 10 * t, np.cos(half), 0, 0, np.sin(half)])
    m = qmotion.interpolate(np.array(rows))
    assert m.degree == 8
    for row in rows:
        e = m.eval(row[0])
        assert np.allclose(e["position"], row[1:4], atol=1e-9)
        q = np.array(row[4:8])
        assert min(np.linalg.norm(q - e["quaternion"]), np.linalg.norm(q + e["quaternion"])) <= 1e-9
    with pytest.raises(ValueError, match="rows of 8 numbers"):
        qmotion.interpolate(np.zeros((3, 5)))


def test_sweep_and_trajectory_poles_equal_the_clis_json(tmp_path):
    motion = tmp_path / "m.json"
    assert cli("interpolate", data("poses/helix_40.json"), "-o", motion).returncode == 0
    m = qmotion.load(str(motion))
    for profile in (data("profiles/parabola.json"), "circle:3", "rect:4,2"):
        out = tmp_path / "s.json"
        r = cli("sweep", motion, "--profile", profile, "-o", out)
        assert r.returncode == 0, r.stderr
        doc = json.load(open(out))
        faces = doc["faces"] if doc["type"] == "nurbs_shell" else [doc]
        surfaces = qmotion.sweep(m, profile)
        assert len(surfaces) == len(faces)
        for s, f in zip(surfaces, faces):
            assert np.array_equal(s.poles, np.array(f["control_points"]))
            assert np.array_equal(s.weights, np.array(f["weights"]))
            assert np.array_equal(s.knots_u, np.array(f["knots_u"]))
            assert np.array_equal(s.knots_v, np.array(f["knots_v"]))
            assert (s.degree_u, s.degree_v) == (f["degree_u"], f["degree_v"])
    out = tmp_path / "c.json"
    assert cli("trajectory", motion, "--point", "1,2,3", "-o", out).returncode == 0
    doc = json.load(open(out))
    c = qmotion.trajectory(m, [1, 2, 3])
    assert np.array_equal(c.poles, np.array(doc["control_points"]))
    assert np.array_equal(c.weights, np.array(doc["weights"]))
    assert np.array_equal(c.knots, np.array(doc["knots"]))
    # The curve is the point's path: compare with eval.
    for t in np.linspace(0, 1, 11):
        assert np.allclose(c(t), m.eval(t, [1, 2, 3])["point"], atol=1e-9)


def test_export_and_check_do_the_main_job(tmp_path):
    m = qmotion.interpolate(data("poses/screw_three.json"))
    for ext in (".step", ".igs", ".json"):
        path = str(tmp_path / ("tube" + ext))
        r = qmotion.export(m, path, profile="circle:3", solid=True)
        assert r["volume"] > 0
        proof = r["self_intersection_proof"]
        assert proof["proven"] and proof["status"] == "none" and proof["patches"] > 0
        k = qmotion.check(path, m, profile="circle:3")
        assert k["relative_deviation"] <= 1e-11
        if ext == ".step":
            assert k["valid"] and k["closed"] and k["solids"] == 1
            assert abs(k["volume"] - r["volume"]) <= 1e-6 * r["volume"]


def test_check_exact_is_the_clis(tmp_path):
    path = str(tmp_path / "m.json")
    qmotion.interpolate(data("poses/five_positions.json")).save(path)
    report = qmotion.check_exact(path, point=[1, 2, 3])
    r = cli("check", "--exact", "--motion", path, "--point", "1,2,3")
    assert r.returncode == 0, r.stderr
    assert report == json.loads(r.stdout)
    assert report["verified"] and report["plucker"]["exact_zero"]
    assert report["order"]["gcd"] == report["order"]["trajectory_degree"]


def cli_message(args):
    r = cli(*args)
    assert r.returncode in (2, 3), r.stderr
    prefix = "qmotion: error: "
    assert r.stderr.startswith(prefix), r.stderr
    return r.returncode, r.stderr[len(prefix):].strip()


def test_errors_have_the_clis_class_and_message(tmp_path):
    five = data("poses/five_positions.json")
    motion = tmp_path / "m.json"
    assert cli("interpolate", five, "-o", motion).returncode == 0
    m = qmotion.load(str(motion))
    pole = tmp_path / "pole.json"
    json.dump({"type": "q-motion", "basis": "bezier", "degree": 1, "param_range": [0, 1],
               "control_points": [[2, 0, 0, 0, 0, 0, 0, 0], [-2, 0, 0, 0, 0, 0, 0, 0]]}, open(pole, "w"))
    cases = [
        (lambda: qmotion.interpolate(data("bad_poses/bad_nan.json")), ["interpolate", data("bad_poses/bad_nan.json"), "-o", tmp_path / "x.json"]),
        (lambda: qmotion.interpolate(five, rotation="slerp"), ["interpolate", five, "-o", tmp_path / "x.json", "--rotation", "slerp"]),
        (lambda: qmotion.interpolate(data("poses/helix_40.json"), form="bezier"),
         ["interpolate", data("poses/helix_40.json"), "-o", tmp_path / "x.json", "--form", "bezier"]),
        (lambda: qmotion.export(m, str(tmp_path / "x.step"), profile="circle:0"),
         ["sweep", motion, "--profile", "circle:0", "-o", tmp_path / "x.step"]),
        (lambda: qmotion.export(qmotion.load(str(pole)), str(tmp_path / "x.step"), point=[1, 2, 3]),
         ["trajectory", pole, "--point", "1,2,3", "-o", tmp_path / "x.step"]),
        (lambda: qmotion.export(m, str(tmp_path / "x.step"), profile="circle:3", solid=True),
         ["sweep", motion, "--profile", "circle:3", "--solid", "-o", tmp_path / "x.step"]),
    ]
    for call, args in cases:
        status, message = cli_message(args)
        expected = ValueError if status == 2 else ArithmeticError
        with pytest.raises(expected) as info:
            call()
        assert str(info.value) == message
    with pytest.raises(ValueError, match="outside"):
        m.eval(2.0)
    for call in (lambda: qmotion.export(m, str(tmp_path / "x.step")),
                 lambda: qmotion.export(m, str(tmp_path / "x.step"), profile="circle:3", point=[0, 0, 0]),
                 lambda: qmotion.check(str(tmp_path / "x.step"), m)):
        with pytest.raises(ValueError, match="exactly one of profile and point"):
            call()
    assert not (tmp_path / "x.step").exists()


@pytest.mark.parametrize("scheme,tension,flags", [
    ("kks", None, []), ("quintic", [0.2, 0.5, 0.5, 0.9, 0.5, 0.5, 0.5, 0.5, 0.5, 1.0],
                        ["--tension", "0.2,0.5,0.5,0.9,0.5,0.5,0.5,0.5,0.5,1"]),
    ("quartic", None, [])])
def test_qspline_is_the_clis_and_does_the_whole_job(tmp_path, scheme, tension, flags):
    path = tmp_path / "q.json"
    r = cli("qspline", data("helix_10.json"), "-o", path, "--scheme", scheme, *flags)
    assert r.returncode == 0, r.stderr
    q = qmotion.qspline(data("helix_10.json"), scheme, tension=tension)
    assert q.scheme == scheme
    assert q.to_dict() == json.load(open(path))
    loaded = qmotion.load(str(path))
    assert type(loaded) is qmotion.Motion and np.array_equal(loaded.knots, q.knots)
    assert (loaded.kind, loaded.scheme, loaded.degree) == ("quaternion-spline", scheme, None)
    info = q.info()
    assert max(info["interpolation_residual"]) <= 1e-10
    assert len(q.eval(q.param_range[0], point=[1, 0, 0])["angular_velocity"]) == 3
    with pytest.raises(ValueError, match="not rational"):
        q.control_points
    # The geometry is fitted within the tolerance and checked against the spline itself.
    curve = qmotion.trajectory(q, [1, 2, 3], tol=1e-6)
    assert curve.degree == 5
    step = str(tmp_path / "s.step")
    e = qmotion.export(q, step, profile="rect:2,1", tol=1e-5)
    assert e["approximation_deviation"] <= e["approximation_bound"]
    assert e["approximation_bound"] <= e["approximation_tolerance"] == 1e-5
    k = qmotion.check(step, q, profile="rect:2,1")
    assert k["max_deviation"] <= e["approximation_bound"] * (1 + 1e-9) and k["valid"]
    assert len(qmotion.sweep(q, "rect:2,1", tol=1e-5)) == 4


def test_compare_lists_every_scheme_like_the_cli():
    figures = qmotion.compare(data("helix_10.json"), point=[1, 0, 0])
    r = cli("compare", data("helix_10.json"), "--point", "1,0,0", "--json")
    assert r.returncode == 0, r.stderr
    assert figures == json.loads(r.stdout)
    assert [f["scheme"] for f in figures] == ["elliptic bspline", "c1", "kks", "quintic", "quartic"]
    for f in figures:
        assert f["sweep_poles"] > 0 and f["trajectory_length"] > 0
        assert f["sweep_exact"] == f["rational"]
        assert f["max_key_residual"] <= 1e-10


def save_q(q, tmp_path):
    path = tmp_path / "q.json"
    q.save(str(path))
    return path


def test_animate_is_the_clis(tmp_path):
    m = qmotion.interpolate(data("helix_10.json"))
    motion = tmp_path / "m.json"
    m.save(str(motion))
    ours = qmotion.animate(m, str(tmp_path / "a.glb"), body="cutter:ball,6,30", tol=0.01)
    r = cli("animate", motion, "--body", "cutter:ball,6,30", "--tol", "0.01", "-o", tmp_path / "b.glb")
    assert r.returncode == 0, r.stderr
    theirs = json.loads(r.stdout)
    skip = ("output", "seconds")
    assert {k: v for k, v in ours.items() if k not in skip} == {k: v for k, v in theirs.items() if k not in skip}
    assert ours["distance_bound"] <= 0.01 and ours["measured_distance"] <= ours["distance_bound"]
    assert ours["metres_per_unit"] == 0.001
    # The same keyframes and mesh: the binary chunks are equal byte for byte.
    def binary_chunk(path):
        f = open(path, "rb").read()
        n = int.from_bytes(f[12:16], "little")
        return f[28 + n:]
    assert binary_chunk(tmp_path / "a.glb") == binary_chunk(tmp_path / "b.glb")
    with pytest.raises(ValueError, match="tolerance must be a positive"):
        qmotion.animate(m, str(tmp_path / "c.glb"), tol=0)
    assert not (tmp_path / "c.glb").exists()


def test_view_is_the_clis(tmp_path):
    m = qmotion.interpolate(data("helix_10.json"))
    motion = tmp_path / "m.json"
    m.save(str(motion))
    ours = qmotion.view(m, str(tmp_path / "a.html"), profile="circle:2", body="sphere:1",
                        points=[[1, 0, 0], [0, 2, 0]])
    r = cli("view", motion, "--profile", "circle:2", "--body", "sphere:1", "--point", "1,0,0",
            "--point", "0,2,0", "-o", tmp_path / "b.html")
    assert r.returncode == 0, r.stderr
    theirs = json.loads(r.stdout)
    skip = ("output", "bytes")  # the name differs: "motion" against the file's
    assert {k: v for k, v in ours.items() if k not in skip} == {k: v for k, v in theirs.items() if k not in skip}
    assert ours["editable"] and ours["poses"] == 10 and ours["points"] == 2
    # The pages differ only in the motion's name (the file's name twice in the title, its
    # path in the data): "interpolate()" for a motion made in memory.
    a = open(tmp_path / "a.html").read()
    b = open(tmp_path / "b.html").read()
    def unnamed(page, title, name):
        return page.replace(">%s<" % title, "><").replace('"name":"%s"' % name, '"name":""')
    assert unnamed(a, "interpolate()", "interpolate()") == unnamed(b, "m.json", str(motion))
    assert ours["bytes"] == len(a.encode()) and theirs["bytes"] == len(b.encode())
    with pytest.raises(ValueError, match="view writes an .html page"):
        qmotion.view(m, str(tmp_path / "c.txt"))
    assert not (tmp_path / "c.txt").exists()
    # With the swept volume: the CLI's report, the mesh `volume` makes at that tolerance.
    ours = qmotion.view(m, str(tmp_path / "d.html"), body="sphere:1", volume=True, body_tol=1.0)
    r = cli("view", motion, "--body", "sphere:1", "--volume", "--body-tol", "1", "-o", tmp_path / "e.html")
    assert r.returncode == 0, r.stderr
    theirs = json.loads(r.stdout)
    assert {k: v for k, v in ours.items() if k not in skip} == {k: v for k, v in theirs.items() if k not in skip}
    mesh = qmotion.swept_volume(m, "sphere:1", tol=1.0)
    assert ours["volume_triangles"] == len(mesh["triangles"]) > 0
    assert ours["volume_distance_bound"] == mesh["distance_bound"] <= 1.0
    with pytest.raises(ValueError, match="give --body"):
        qmotion.view(m, str(tmp_path / "f.html"), volume=True)
    assert not (tmp_path / "f.html").exists()


def test_volume_is_the_clis(tmp_path):
    m = qmotion.interpolate(data("poses/five_positions.json"))
    motion = tmp_path / "m.json"
    m.save(str(motion))
    ours = qmotion.volume(m, str(tmp_path / "a.stl"), "cutter:ball,6,20", tol=2.0)
    r = cli("volume", motion, "--body", "cutter:ball,6,20", "--tol", "2", "-o", tmp_path / "b.stl")
    assert r.returncode == 0, r.stderr
    theirs = json.loads(r.stdout)
    skip = ("output", "seconds")
    assert {k: v for k, v in ours.items() if k not in skip} == {k: v for k, v in theirs.items() if k not in skip}
    assert ours["distance_bound"] <= 2.0 and ours["closed"]
    lower, upper = ours["volume_bounds"]
    assert 0 < lower < upper
    # Binary STL: 84 bytes of header and count, 50 a triangle; the same bytes both ways.
    a = open(tmp_path / "a.stl", "rb").read()
    assert len(a) == 84 + 50 * ours["triangles"] and a == open(tmp_path / "b.stl", "rb").read()
    # In inches: the same mesh scaled, the volume by 25.4^3 (the flat cutter: a ball cutter's
    # JSON holds its ball's exact faces, below). PLY holds doubles, as JSON does; a binary
    # STL's mesh is made to allow for its float32 rounding, so it is not the same mesh.
    assert ours["float32_rounding"] > 0
    flat = qmotion.volume(m, str(tmp_path / "c.ply"), "cutter:flat,6,20", tol=2.0)
    assert flat["float32_rounding"] == 0
    inch = qmotion.volume(m, str(tmp_path / "c.json"), "cutter:flat,6,20", tol=2.0 / 25.4, units="in")
    assert inch["triangles"] == flat["triangles"]
    top = flat["volume_bounds"][1]
    assert abs(inch["volume_bounds"][1] * 25.4 ** 3 - top) < 1e-9 * top
    doc = json.load(open(tmp_path / "c.json"))
    assert doc["units"] == "in" and len(doc["triangles"]) == flat["triangles"]
    ball = qmotion.volume(m, str(tmp_path / "ball.json"), "cutter:ball,6,20")
    assert ball["exact"] and "shank" in ball["exact_part"]
    assert json.load(open(tmp_path / "ball.json"))["type"] == "nurbs_shell"
    with pytest.raises(ValueError, match="exact STEP/IGES faces exist for sphere:r and cutter:ball"):
        qmotion.volume(m, str(tmp_path / "d.step"), "box:1,2,3")
    assert not (tmp_path / "d.step").exists()
    # A sphere's exact faces: STEP from both, the same report; the JSON shell holds them.
    ours_exact = qmotion.volume(m, str(tmp_path / "e.step"), "sphere:2", tol=2.0)
    r = cli("volume", motion, "--body", "sphere:2", "--tol", "2", "-o", tmp_path / "f.step")
    assert r.returncode == 0, r.stderr
    theirs = json.loads(r.stdout)
    assert {k: v for k, v in ours_exact.items() if k not in skip} == {k: v for k, v in theirs.items() if k not in skip}
    assert ours_exact["exact"] and ours_exact["faces"] == ours_exact["pipe_faces"] + 8
    assert ours_exact["degree"] <= 25
    lower, upper = ours_exact["volume_bounds"]
    assert lower <= ours_exact["volume"] <= upper
    shell = qmotion.volume(m, str(tmp_path / "g.json"), "sphere:2", tol=2.0)
    doc = json.load(open(tmp_path / "g.json"))
    assert doc["type"] == "nurbs_shell" and doc["closed"] and len(doc["faces"]) == shell["faces"]
    # `check --body` by its own sampling: the STL and the JSON (in inches) enclose the cutter's
    # volume, vertices within the tolerance; a bigger cutter's volume is not enclosed (exit 3).
    for f, body, made in (("a.stl", "cutter:ball,6,20", ours), ("c.json", "cutter:flat,6,20", flat)):
        r = cli("check", tmp_path / f, "--motion", motion, "--body", body)
        assert r.returncode == 0, r.stderr
        c = json.loads(r.stdout)
        assert c["encloses"] and c["outside"] == 0 and c["samples"] == 20000
        assert 0.3 * 2.0 < c["vertex_distance"] <= made["distance_bound"] * (1 + 1e-6)
        assert c["triangles"] == made["triangles"]
    r = cli("check", tmp_path / "a.stl", "--motion", motion, "--body", "cutter:ball,10,20")
    assert r.returncode == 3 and "lie outside the mesh" in r.stderr
    assert json.loads(r.stdout)["outside"] > 0


def test_toolpath_is_the_clis(tmp_path):
    m = qmotion.interpolate(data("poses/helix_40.json"))
    motion = tmp_path / "m.json"
    m.save(str(motion))
    ours = qmotion.toolpath(m, str(tmp_path / "a.ngc"), point=[1, 0, 2], axis=[1, 0, 1], chord_tol=0.01,
                            rotary="ac")
    r = cli("toolpath", motion, "--point", "1,0,2", "--axis", "1,0,1", "--chord-tol", "0.01",
            "--rotary", "ac", "-o", tmp_path / "b.ngc")
    assert r.returncode == 0, r.stderr
    theirs = json.loads(r.stdout)
    assert {k: v for k, v in ours.items() if k != "path"} == {k: v for k, v in theirs.items() if k != "path"}
    assert open(tmp_path / "a.ngc").read() == open(tmp_path / "b.ngc").read()
    q = qmotion.qspline(data("helix_10.json"), "kks")
    report = qmotion.toolpath(q, str(tmp_path / "q.csv"), point=[0, 0, 0], chord_tol=0.001)
    assert report["max_chord_deviation_bound"] <= 0.001
    nurbs = qmotion.toolpath(q, str(tmp_path / "n.ngc"), point=[1, 0, 2], chord_tol=0.001, nurbs=True)
    r = cli("toolpath", save_q(q, tmp_path), "--point", "1,0,2",
            "--chord-tol", "0.001", "--nurbs", "-o", tmp_path / "n2.ngc")
    assert r.returncode == 0, r.stderr
    # The saved spline reads back within rounding: the same blocks, the same figures to 1e-9.
    theirs = json.loads(r.stdout)
    assert nurbs.keys() == theirs.keys()
    for k in nurbs:
        if k != "path":
            assert nurbs[k] == pytest.approx(theirs[k], rel=1e-9), k
    assert len(open(tmp_path / "n.ngc").readlines()) == len(open(tmp_path / "n2.ngc").readlines())
    assert nurbs["degree"] <= 3 and nurbs["max_deviation_bound"] <= 0.001
    # A machine file and inverse-time feed, as the CLI's options.
    tilt = qmotion.interpolate(data("poses/tilt_150.json"), form="bspline")
    tilt.save(str(tmp_path / "tilt.json"))
    machine = data("machines/head_table.json")
    ours = qmotion.toolpath(tilt, str(tmp_path / "t1.ngc"), point=[0, 0, 0], chord_tol=0.01,
                            machine=machine, feed_mode="inverse-time", axis_limits={"C": 2000})
    r = cli("toolpath", tmp_path / "tilt.json", "--point", "0,0,0", "--chord-tol", "0.01",
            "--machine", machine, "--feed-mode", "inverse-time", "--axis-limits", "C=2000",
            "-o", tmp_path / "t2.ngc")
    assert r.returncode == 0, r.stderr
    theirs = json.loads(r.stdout)
    assert {k: v for k, v in ours.items() if k != "path"} == {k: v for k, v in theirs.items() if k != "path"}
    assert open(tmp_path / "t1.ngc").read() == open(tmp_path / "t2.ngc").read()
    assert ours["machine"]["name"] == "head B, table C" and ours["axis_limits"]["C"] == 2000
    # The controller's words and the part of the tolerance left to it, as the CLI's.
    sie = qmotion.toolpath(m, str(tmp_path / "s1.ngc"), point=[1, 0, 2], chord_tol=0.01,
                           dialect="siemens", controller_tol=0.004)
    r = cli("toolpath", motion, "--point", "1,0,2", "--chord-tol", "0.01", "--dialect", "siemens",
            "--controller-tol", "0.004", "-o", tmp_path / "s2.ngc")
    assert r.returncode == 0, r.stderr
    assert open(tmp_path / "s1.ngc").read() == open(tmp_path / "s2.ngc").read()
    assert sie["path_mode"] == "G642 CTOL=0.004000" and sie["max_path_deviation_bound"] <= 0.01
    assert ours["machining_time_with_acceleration_min"] > ours["machining_time_min"]
    with pytest.raises(ValueError, match="--controller-tol"):
        qmotion.toolpath(m, str(tmp_path / "s3.ngc"), point=[1, 0, 2], chord_tol=0.01,
                         dialect="fanuc", controller_tol=0.004)
    with pytest.raises(ValueError, match="axis_limits"):
        qmotion.toolpath(tilt, str(tmp_path / "t3.ngc"), point=[0, 0, 0], chord_tol=0.01,
                         feed_mode="inverse-time", axis_limits={"XY": 5})
    with pytest.raises(ValueError, match="--axis"):
        qmotion.toolpath(m, str(tmp_path / "z.csv"), point=[0, 0, 0], axis=[0, 0, 0], chord_tol=0.1)


def test_surface_grid_matches_pointwise_evaluation():
    m = qmotion.interpolate(data("self_intersection/coil_open.json"))
    s = qmotion.sweep(m, "circle:3")[0]
    us = np.linspace(s.knots_u[0], s.knots_u[-1], 50)
    vs = np.linspace(s.knots_v[0], s.knots_v[-1], 9)
    g = s.grid(us, vs)
    assert g.shape == (50, 9, 3)
    for i in (0, 17, 49):
        for j in (0, 4, 8):
            assert np.allclose(g[i, j], s(us[i], vs[j]), rtol=0, atol=1e-11)
    with pytest.raises(ValueError, match="outside"):
        s.grid([s.knots_u[-1] + 1], vs)


def test_mesh_export_reports_its_deviation(tmp_path):
    m = qmotion.interpolate(data("self_intersection/coil_open.json"))
    r = qmotion.export(m, str(tmp_path / "tube.ply"), profile="circle:3", solid=True, deflection=0.1)
    assert r["mesh"]["max_deviation"] <= 0.1
    assert r["mesh"]["closed"] and r["mesh"]["oriented"]
    with pytest.raises(ValueError, match="--deflection"):
        qmotion.export(m, str(tmp_path / "x.stl"), profile="circle:3", deflection=-1)


def test_solid_refuses_what_the_proof_finds(tmp_path):
    # The turns overlap by about 1e-5: finer than the mesh check, found by the proof.
    m = qmotion.interpolate(data("self_intersection/coil_touching.json"))
    r = qmotion.export(m, str(tmp_path / "tube.step"), profile="circle:3")
    assert not r["self_intersecting"] and "self_intersection_proof" not in r
    with pytest.raises(ArithmeticError, match="bounds no solid") as e:
        qmotion.export(m, str(tmp_path / "solid.step"), profile="circle:3", solid=True)
    assert "itself within" in str(e.value)
    assert not (tmp_path / "solid.step").exists()


def test_demo_does_the_main_job(tmp_path):
    report = qmotion.demo(str(tmp_path / "demo"))
    assert len(report["exactness"]) == 9
    assert max(c["relative_deviation"] for c in report["exactness"]) <= 1e-11
    assert (tmp_path / "demo" / "report.json").exists()


def test_every_function_is_documented():
    for name in ("interpolate", "trajectory", "sweep", "export", "check", "load", "poses", "read_poses",
                 "demo", "qspline", "compare", "toolpath"):
        doc = getattr(qmotion, name).__doc__
        assert doc and len(doc) > 80, name
    assert "kinematic surface" in qmotion.sweep.__doc__
    assert "ValueError" in qmotion.__doc__


@pytest.mark.parametrize("make", [
    lambda p: qmotion.interpolate(p, form="bezier"),
    lambda p: qmotion.interpolate(p, form="bspline"),
    lambda p: qmotion.interpolate(p, form="c1"),
    lambda p: qmotion.qspline(p, "kks"),
    lambda p: qmotion.qspline(p, "quintic"),
    lambda p: qmotion.qspline(p, "quartic")], ids=["bezier", "bspline", "c1", "kks", "quintic",
                                                    "quartic"])
def test_one_motion_class_answers_the_same_calls_for_both_kinds(make):
    poses = json.load(open(data("poses/five_positions.json")))["poses"]
    m = make(data("poses/five_positions.json"))
    assert type(m) is qmotion.Motion
    keys = m.key_parameters
    assert len(keys) == len(poses) and keys[0] == m.param_range[0] and keys[-1] == m.param_range[1]
    x = np.array([3.0, -2.0, 5.0])
    for t, pose in zip(keys, poses):  # interpolation at every pose, through frame and place
        F = m.frame(t)
        assert F.shape == (4, 4) and F[0, 0] == 1 and not F[0, 1:].any()
        R = rotation_of(pose["rotation"])
        assert np.allclose(F[1:, 1:], R, atol=1e-9)
        assert np.allclose(F[1:, 0], pose["position"], atol=1e-9)
        assert np.allclose(m.place(t, x), R @ x + pose["position"], atol=1e-9)
    a, b = m.param_range
    assert m.breakpoints[0] == a and m.breakpoints[-1] == b
    assert len(m.continuity) == len(m.breakpoints) - 2
    h = 1e-6 * (b - a)
    for t in np.linspace(a + 0.013 * (b - a), b - 0.017 * (b - a), 7):
        # Velocities against central differences of the placement and of the frame.
        fd = (np.array(m.place(t + h, x)) - np.array(m.place(t - h, x))) / (2 * h)
        assert np.allclose(m.point_velocity(t, x), fd, rtol=1e-5, atol=1e-6 * np.abs(fd).max())
        R0, R1, Rt = m.frame(t - h)[1:, 1:], m.frame(t + h)[1:, 1:], m.frame(t)[1:, 1:]
        W = (R1 - R0) / (2 * h) @ Rt.T  # skew(omega)
        w = np.array([W[2, 1], W[0, 2], W[1, 0]])
        assert np.allclose(m.angular_velocity(t), w, rtol=1e-5, atol=1e-7 * max(1, np.abs(w).max()))
    if m.rational:
        doc = m.to_dict()
        assert m.control_points.shape == (len(doc["control_points"]), 8)
        assert np.array_equal(m.control_points, np.array(doc["control_points"]))
        assert m.degree == doc["degree"] and m.kind == "q-motion" and m.scheme is None
    else:
        assert m.degree is None and m.kind == "quaternion-spline"


def test_fit_is_the_clis_and_reports_what_the_motion_does(tmp_path):
    poses = data("fit/noisy_helix.json")
    motion, report = qmotion.fit(poses, tol=0.01, angle_tol=0.05)
    out = tmp_path / "cli.json"
    r = cli("fit", poses, "-o", out, "--tol", 0.01, "--angle-tol", 0.05)
    assert r.returncode == 0, r.stderr
    assert motion.to_dict() == json.loads(out.read_text())
    assert motion.info()["method"]["form"] == "fit"
    assert report["control_points"] * 10 <= report["poses"] == 400
    # The worst deviations, measured here through frame() from the poses as read.
    doc = json.loads(open(poses).read())
    worst_pos = worst_ang = 0.0
    for p in doc["poses"]:
        F = motion.frame(p["t"])
        worst_pos = max(worst_pos, float(np.linalg.norm(F[1:, 0] - np.array(p["position"]))))
        w, x, y, z = np.array(p["rotation"]["quaternion"]) / np.linalg.norm(p["rotation"]["quaternion"])
        R = np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
                      [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
                      [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]])
        c = (np.trace(R.T @ F[1:, 1:]) - 1) / 2
        worst_ang = max(worst_ang, float(np.degrees(np.arccos(min(1.0, max(-1.0, c))))))
    assert worst_pos <= 0.01 and worst_ang <= 0.05
    assert report["worst_position"] == pytest.approx(worst_pos, rel=1e-9)
    assert report["worst_angle_deg"] == pytest.approx(worst_ang, rel=1e-5, abs=1e-9)
    assert max(report["position_deviation"]) == report["worst_position"]
    with pytest.raises(ArithmeticError, match="cannot be met"):
        qmotion.fit(poses, tol=1e-4)


def test_verify_is_the_clis(tmp_path):
    # One G1 through the ridge of bump.obj between ends that clear it (docs/guide/verify.md).
    program, part = data("verify/dip.ngc"), data("verify/bump.obj")
    ours = qmotion.verify(program, "cutter:ball,6,30", part, tol=0.01, output=str(tmp_path / "a.json"))
    r = cli("verify", program, "--tool", "cutter:ball,6,30", "--part", part, "--tol", "0.01")
    assert r.returncode == 0, r.stderr
    theirs = json.loads(r.stdout)
    assert {k: v for k, v in ours.items() if k != "seconds"} == {k: v for k, v in theirs.items() if k != "seconds"}
    assert json.load(open(tmp_path / "a.json"))["gouge"] == ours["gouge"]
    lower, upper = ours["gouge"]["depth"]
    assert lower <= 0.5 <= upper and upper - lower <= 0.01
    assert [m["line"] for m in ours["gouge"]["moves"]] == [7]
    with pytest.raises(ValueError, match="line 4: M3 is not read by verify"):
        qmotion.verify(data("verify/bad_word.ngc"), "cutter:ball,6,30", part, output=str(tmp_path / "b.json"))
    assert not (tmp_path / "b.json").exists()


def test_verify_stock_is_the_clis(tmp_path):
    # offsets.ngc's passes over plate.obj under a 1 mm stock: the stock left and its map.
    program, part = data("verify/offsets.ngc"), data("verify/plate.obj")
    stock = "box:-30,-30,-20,30,30,1"
    ours = qmotion.verify(program, "cutter:ball,6,30", part, stock=stock, map=str(tmp_path / "m.ply"),
                          holder="cylinder:10,20")
    r = cli("verify", program, "--tool", "cutter:ball,6,30", "--part", part, "--stock", stock,
            "--holder", "cylinder:10,20")
    assert r.returncode == 0, r.stderr
    theirs = json.loads(r.stdout)
    assert ours["stock_left"] == theirs["stock_left"]
    assert ours["collisions"]["holder"] == theirs["collisions"]["holder"]
    assert ours["collisions"]["holder"]["clear"]  # 30 mm above the tip, over 1 mm of stock
    lower, upper = ours["stock_left"]["max"]
    assert 0 <= lower <= upper <= 1 + 1e-9  # at most the stock's 1 mm over the part
    assert (tmp_path / "m.ply").read_bytes().startswith(b"ply\n")
    with pytest.raises(ValueError, match="give the raw stock with --stock"):
        qmotion.verify(program, "cutter:ball,6,30", part, map=str(tmp_path / "n.ply"))
    assert not (tmp_path / "n.ply").exists()
