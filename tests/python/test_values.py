"""Values that travel (docs/library.md, "Arrays in and out", "Motions in other processes"):
Motion pickles bit for bit, in this process and in another one; frames and points come out
for many times in one call; a swept volume's mesh comes out as views of the library's arrays
and a closed mesh goes in as arrays."""
import json
import pickle
import subprocess
import sys

import numpy as np
import pytest

import qmotion
from testkit import data

FIVE = "poses/five_positions.json"

MAKERS = {
    "elliptic": lambda: qmotion.interpolate(data(FIVE)),
    "bspline": lambda: qmotion.interpolate(data("poses/helix_40.json"), form="bspline", degree=4,
                                           translation_degree=2),
    "exact": lambda: qmotion.interpolate(data("poses/rational_exact.json"), exact=True),
    "fit": lambda: qmotion.fit(data("poses/helix_40.json"), tol=1.0, angle_tol=1.0)[0],
    "kks": lambda: qmotion.qspline(data(FIVE), "kks"),
    "quintic": lambda: qmotion.qspline(data(FIVE), "quintic", tension=[0.3, 0.5, 0.7, 0.5, 0.4]),
    "quartic": lambda: qmotion.qspline(data(FIVE), "quartic"),
}


def sample(m, n=101):
    a, b = m.param_range
    return np.linspace(a, b, n)


def figures(m):
    """What a motion answers, as exact bytes: frames, points, velocities and eval dicts."""
    x = (3.0, -2.0, 5.0)
    ts = sample(m)
    return (m.frames(ts).tobytes(), m.places(ts, x).tobytes(),
            [m.angular_velocity(t) for t in ts[1:-1]], [m.point_velocity(t, x) for t in ts[1:-1]],
            json.dumps([m.eval(t, x) for t in ts[::10]]), m.save.__doc__ and None)


@pytest.mark.parametrize("kind", sorted(MAKERS))
def test_motion_pickles_bit_for_bit(kind, tmp_path):
    m = MAKERS[kind]()
    for protocol in (2, pickle.HIGHEST_PROTOCOL):
        r = pickle.loads(pickle.dumps(m, protocol=protocol))
        assert type(r) is qmotion.Motion and r.kind == m.kind and r.scheme == m.scheme
        assert figures(r) == figures(m)
        assert np.array_equal(r.knots, m.knots) and r.to_dict() == m.to_dict()
        m.save(str(tmp_path / "a.json"))
        r.save(str(tmp_path / "b.json"))
        assert (tmp_path / "a.json").read_bytes() == (tmp_path / "b.json").read_bytes()
    t = qmotion.loads(m.dumps(), "copy")
    assert figures(t) == figures(m) and t.dumps() == m.dumps()
    if m.rational:
        assert np.array_equal(r.control_points, m.control_points)
        assert r.info(exact=True) == m.info(exact=True)


def test_a_pickled_motion_evaluates_the_same_in_another_process():
    motions = [MAKERS[k]() for k in ("elliptic", "kks", "quintic")]
    program = (
        "import pickle, sys, numpy as np\n"
        "motions = pickle.load(sys.stdin.buffer)\n"
        "out = [m.frames(np.linspace(*m.param_range, 101)).tobytes() for m in motions]\n"
        "pickle.dump(out, sys.stdout.buffer)\n")
    r = subprocess.run([sys.executable, "-c", program], input=pickle.dumps(motions),
                       capture_output=True, check=True)
    theirs = pickle.loads(r.stdout)
    assert theirs == [m.frames(sample(m)).tobytes() for m in motions]


@pytest.mark.parametrize("state", [("{}", True), ("not json", False), ("only one",)])
def test_a_bad_pickle_state_is_refused_by_name(state):
    m = qmotion.Motion.__new__(qmotion.Motion)
    with pytest.raises((ValueError, TypeError)):
        m.__setstate__(state)


def test_loads_names_the_text_it_refuses():
    with pytest.raises(ValueError, match="^my motion: "):
        qmotion.loads('{"type": "q-motion"}', "my motion")


@pytest.mark.parametrize("kind", ["elliptic", "kks"])
def test_frames_and_places_are_frame_and_place_at_every_time(kind):
    m = MAKERS[kind]()
    ts = sample(m, 37)
    F = m.frames(ts)
    assert F.shape == (37, 4, 4) and F.dtype == np.float64
    x = np.array([1.5, 2.0, -4.0])
    P = m.places(ts, x)
    assert P.shape == (37, 3)
    for i, t in enumerate(ts):
        assert np.array_equal(F[i], m.frame(t))
        assert np.array_equal(P[i], m.place(t, x))
        R = F[i, 1:, 1:]  # a rigid map: R orthogonal, the point is p + R x
        assert np.allclose(R.T @ R, np.eye(3), atol=1e-12)
        assert np.allclose(P[i], F[i, 1:, 0] + R @ x, atol=1e-9)
    assert m.frames(float(ts[3])).shape == (1, 4, 4)
    assert np.array_equal(m.frames([ts[3]]), F[3:4])  # a list is converted
    with pytest.raises(ValueError):
        m.frames(np.zeros((2, 2)))
    with pytest.raises(ValueError):
        m.frames([ts[-1] + 1.0])


def read_obj(path):
    v, f = [], []
    for line in open(path):
        w = line.split()
        if w and w[0] == "v":
            v.append([float(c) for c in w[1:4]])
        elif w and w[0] == "f":
            f.append([int(c) - 1 for c in w[1:4]])
    return np.array(v), np.array(f)


def edges_closed(tri):
    """Every directed edge once and its reverse once: closed, oriented, 2-manifold."""
    directed = {}
    for a, b, c in tri.tolist():
        for e in ((a, b), (b, c), (c, a)):
            directed[e] = directed.get(e, 0) + 1
    return all(n == 1 and directed.get((e[1], e[0])) == 1 for e, n in directed.items())


def test_the_swept_volume_comes_out_as_views_of_the_librarys_mesh(tmp_path):
    m = qmotion.interpolate(data(FIVE))
    v = qmotion.swept_volume(m, "cutter:flat,6,20", tol=2.0)
    V, T = v["vertices"], v["triangles"]
    assert V.shape[1] == 3 and T.shape[1] == 3 and V.dtype == np.float64 and T.dtype == np.int32
    assert not V.flags.owndata and not T.flags.owndata and V.base is not None  # views
    assert v["distance_bound"] <= 2.0 and v["closed"] and edges_closed(T)
    assert T.min() == 0 and T.max() == len(V) - 1
    # The same mesh as `volume` writes as JSON (doubles, the motion's unit).
    written = qmotion.volume(m, str(tmp_path / "v.json"), "cutter:flat,6,20", tol=2.0)
    doc = json.load(open(tmp_path / "v.json"))
    assert np.array_equal(np.array(doc["vertices"]), V)
    assert np.array_equal(np.array(doc["triangles"]), T)
    assert written["volume_bounds"] == list(v["volume_bounds"])
    # The views keep the mesh alive after the dict is gone.
    del v
    copy = V.copy()
    _ = [qmotion.interpolate(data(FIVE)) for _ in range(3)]
    assert np.array_equal(V, copy) and edges_closed(T)


def test_a_closed_mesh_goes_in_as_arrays():
    m = qmotion.interpolate(data(FIVE))
    path = data("bodies/tetra.obj")
    V, F = read_obj(path)
    a = qmotion.swept_volume(m, (V, F), tol=2.0)
    b = qmotion.swept_volume(m, path, tol=2.0)
    assert np.array_equal(a["vertices"], b["vertices"])
    assert np.array_equal(a["triangles"], b["triangles"])
    assert a["distance_bound"] == b["distance_bound"]
    # Every pose's image of every body vertex lies inside the bounds of the volume's box.
    lo, hi = a["vertices"].min(axis=0), a["vertices"].max(axis=0)
    for t in m.key_parameters:
        for x in V:
            assert np.all(lo - 1e-9 <= m.place(t, x)) and np.all(m.place(t, x) <= hi + 1e-9)


@pytest.mark.parametrize("change,message", [
    (lambda V, F: (V, F[:-1]), "open"),
    (lambda V, F: (V, np.vstack([F[:-1], [[0, 1, 7]]])), "triangle 3 .counted from 0. names vertex 7"),
    (lambda V, F: (V, F.astype(float)), "array of integers"),
    (lambda V, F: (np.where(V == 20, np.nan, V), F), "vertex 1 .counted from 0. is not finite"),
    (lambda V, F: (V[:, :2], F), "n x 3 array"),
    (lambda V, F: (V, F[:, ::-1].copy()), "inside out or flat: its signed volume is -250"),
])
def test_a_bad_mesh_is_refused_by_name(change, message):
    m = qmotion.interpolate(data(FIVE))
    V, F = read_obj(data("bodies/tetra.obj"))
    with pytest.raises(ValueError, match=message):
        qmotion.swept_volume(m, change(V, F), tol=2.0)
