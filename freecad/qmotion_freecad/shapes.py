"""Conversions between FreeCAD's geometry and qmotion's: edges to nurbs_curve documents,
qmotion's NURBS to Part curves and surfaces, a closed mesh to a Part solid. No document
objects here (features.py has them)."""
import FreeCAD
import Part


def _full_knots(curve):
    knots = []
    for k, m in zip(curve.getKnots(), curve.getMultiplicities()):
        knots += [float(k)] * m
    return knots


def edge_document(edge):
    """One edge as a nurbs_curve document (docs/formats.md), exactly: FreeCAD's own NURBS
    conversion (lines, conics and B-splines are exact), clamped, trimmed to the edge and
    turned the way the edge runs."""
    e = edge.toNurbs().Edges[0]
    c = e.Curve.copy()
    if c.isPeriodic():
        c.setNotPeriodic()
    c.segment(e.FirstParameter, e.LastParameter)  # trims, and clamps both ends
    knots = _full_knots(c)
    poles = [[p.x, p.y, p.z] for p in c.getPoles()]
    weights = [float(w) for w in c.getWeights()]
    if edge.Orientation == "Reversed":
        lo, hi = knots[0], knots[-1]
        knots = [lo + hi - k for k in reversed(knots)]
        poles.reverse()
        weights.reverse()
    return {"type": "nurbs_curve", "degree": c.Degree, "knots": knots,
            "control_points": poles, "weights": weights}


def _reversed(doc):
    lo, hi = doc["knots"][0], doc["knots"][-1]
    return dict(doc, knots=[lo + hi - k for k in reversed(doc["knots"])],
                control_points=doc["control_points"][::-1], weights=doc["weights"][::-1])


def _near(p, q, tol):
    return sum((a - b) ** 2 for a, b in zip(p, q)) <= tol * tol


def profile_document(shape):
    """The edges of a shape (a sketch, a circle, a wire) as one profile: a list of
    nurbs_curve documents in order, each turned to start where the one before ends."""
    edges = shape.Edges
    if not edges:
        raise ValueError("the profile has no edges")
    if len(edges) > 1:
        edges = Part.__sortEdges__(edges)
    docs = [edge_document(e) for e in edges]
    tol = 1e-7 * max(shape.BoundBox.DiagonalLength, 1e-300)
    for i in range(1, len(docs)):
        end = docs[i - 1]["control_points"][-1]
        first, last = docs[i]["control_points"][0], docs[i]["control_points"][-1]
        if not _near(end, first, tol) and _near(end, last, tol):
            docs[i] = _reversed(docs[i])
        elif i == 1 and not _near(end, first, tol):
            start = docs[0]["control_points"][0]
            if _near(start, first, tol) or _near(start, last, tol):
                docs[0] = _reversed(docs[0])
                if not _near(start, first, tol):
                    docs[1] = _reversed(docs[1])
    return docs


def _distinct(knots):
    values, mults = [], []
    for k in knots:
        if values and values[-1] == k:
            mults[-1] += 1
        else:
            values.append(float(k))
            mults.append(1)
    return values, mults


def part_curve(c):
    """A qmotion.NurbsCurve as a Part.BSplineCurve: the same poles, weights and knots."""
    k, m = _distinct(c.knots)
    bs = Part.BSplineCurve()
    bs.buildFromPolesMultsKnots([FreeCAD.Vector(*p) for p in c.poles.tolist()], m, k, False,
                                c.degree, c.weights.tolist())
    return bs


def part_surface(s):
    """A qmotion.NurbsSurface as a Part.BSplineSurface (u = t, v the profile's parameter)."""
    uk, um = _distinct(s.knots_u)
    vk, vm = _distinct(s.knots_v)
    poles = [[FreeCAD.Vector(*p) for p in row] for row in s.poles.tolist()]
    bs = Part.BSplineSurface()
    bs.buildFromPolesMultsKnots(poles, um, vm, uk, vk, False, False, s.degree_u, s.degree_v,
                                s.weights.tolist())
    return bs


def faces_shape(faces):
    """Faces as one shape: a sewn shell when FreeCAD sews them into a valid one (a profile of
    several edges), the face itself when there is one, else their compound."""
    if len(faces) == 1:
        return faces[0]
    shell = Part.Shell(faces)
    shell.sewShape()
    return shell if shell.isValid() else Part.makeCompound(faces)


def mesh_arrays(shape, tol):
    """A closed Part shape tessellated within tol, as (vertices, triangles) lists."""
    points, triangles = shape.tessellate(tol)
    return [[p.x, p.y, p.z] for p in points], [list(t) for t in triangles]


def mesh_solid(vertices, triangles):
    """A closed, outward triangle mesh as a Part solid of planar faces."""
    shape = Part.Shape()
    shape.makeShapeFromMesh(([FreeCAD.Vector(*p) for p in vertices.tolist()],
                             [tuple(t) for t in triangles.tolist()]), 1e-9)
    # A closed mesh comes back as one sewn shell; building another from its faces would sew
    # them again (several times slower).
    shell = shape if shape.ShapeType == "Shell" else Part.Shell(shape.Faces)
    return Part.Solid(shell)
