"""qmotion's parametric features: Part::FeaturePython objects whose execute() calls qmotion,
so that FreeCAD recomputes them when an input changes (a pose, the profile's sketch, the
point, the body). Each stores its certificate as read-only properties."""
import FreeCAD

import qmotion

from . import shapes

ROTATIONS = ["elliptic", "affine", "projective"]
FORMS = ["default", "bezier", "bspline", "c1"]
SCHEMES = ["q-motion", "kks", "quintic", "quartic"]


def _add(obj, kind, name, group, doc, value=None, read_only=False, hidden=False):
    if name not in obj.PropertiesList:
        obj.addProperty(kind, name, group, doc)
    mode = (1 if read_only else 0) | (2 if hidden else 0)
    if mode:
        obj.setEditorMode(name, mode)
    if value is not None:
        setattr(obj, name, value)


def _certificate(obj, kind, fields):
    """Read-only properties of the Certificate group: fields = ((name, doc), ...)."""
    for name, doc in fields:
        _add(obj, kind, name, "Certificate", doc, read_only=True)


def _certify(obj, values):
    """Writes the read-only certificate properties (FreeCAD lets execute() set them)."""
    for name, value in values.items():
        setattr(obj, name, value)


def motion_of(obj):
    """The qmotion.Motion a QMotion motion feature holds (from its stored motion file)."""
    if obj is None or "MotionFile" not in obj.PropertiesList:
        raise ValueError("expected a qmotion motion feature (make_motion)")
    if not obj.MotionFile:
        obj.recompute()
    return qmotion.loads(obj.MotionFile, obj.Label)


def _rows(placements, times):
    rows = []
    for i, p in enumerate(placements):
        x, y, z, w = p.Rotation.Q  # FreeCAD's quaternion order: x, y, z, w
        row = [p.Base.x, p.Base.y, p.Base.z, w, x, y, z]
        rows.append(([times[i]] if times else []) + row)
    return rows


class _Feature:
    """What every proxy shares: FreeCAD stores no Python state of ours (the properties hold
    everything), so documents reopen without qmotion having to pickle anything."""

    def __init__(self, obj):
        obj.Proxy = self
        self.setup(obj)

    def onDocumentRestored(self, obj):
        self.setup(obj)

    def __getstate__(self):
        return None

    def __setstate__(self, state):
        return None

    dumps, loads = __getstate__, __setstate__


class MotionFeature(_Feature):
    """A motion through poses: Placements (with Times, or none for the default spacing) or a
    PoseFile; interpolated as a Q-motion (exact) or a quaternion spline. Its shape is the
    trajectory of the moving origin."""

    def setup(self, obj):
        _add(obj, "App::PropertyPlacementList", "Placements", "Poses", "the poses, in order")
        _add(obj, "App::PropertyFloatList", "Times", "Poses",
             "the parameter of every pose (empty: qmotion's default)")
        _add(obj, "App::PropertyFile", "PoseFile", "Poses",
             "a pose file or robot program, used when Placements is empty")
        _add(obj, "App::PropertyEnumeration", "Scheme", "Motion", "q-motion or a spline")
        _add(obj, "App::PropertyEnumeration", "Rotation", "Motion", "a Q-motion's rotation")
        _add(obj, "App::PropertyEnumeration", "Form", "Motion", "a Q-motion's form")
        if not obj.getEnumerationsOfProperty("Scheme"):
            obj.Scheme, obj.Rotation, obj.Form = SCHEMES, ROTATIONS, FORMS
        _add(obj, "App::PropertyString", "MotionFile", "Certificate",
             "the motion file (qmotion.loads)", read_only=True, hidden=True)
        _certificate(obj, "App::PropertyString", (("Kind", "q-motion or quaternion-spline"),))
        _certificate(obj, "App::PropertyInteger",
                     (("Degree", "the Q-motion's degree (0 for a spline)"),
                      ("Segments", "pieces of the motion")))
        _certificate(obj, "App::PropertyFloat",
                     (("InterpolationResidual", "largest residual at the poses"),
                      ("PluckerResidual", "Pluecker residual of the motion")))

    def execute(self, obj):
        if obj.Placements:
            if obj.Times and len(obj.Times) != len(obj.Placements):
                raise ValueError("%s: %d times for %d placements" %
                                 (obj.Label, len(obj.Times), len(obj.Placements)))
            poses = _rows(obj.Placements, list(obj.Times))
        elif obj.PoseFile:
            poses = obj.PoseFile
        else:
            raise ValueError("%s: no poses (set Placements or PoseFile)" % obj.Label)
        if obj.Scheme == "q-motion":
            options = dict(rotation=obj.Rotation)
            if obj.Form != "default":
                options["form"] = obj.Form
            m = qmotion.interpolate(poses, **options)
        else:
            m = qmotion.qspline(poses, obj.Scheme)
        info = m.info()
        obj.MotionFile = m.dumps()
        _certify(obj, {"Kind": m.kind, "Degree": m.degree or 0, "Segments": m.segments,
                       "InterpolationResidual": max(info["interpolation_residual"]),
                       "PluckerResidual": float(info["plucker_residual"])})
        obj.Shape = shapes.part_curve(qmotion.trajectory(m, [0, 0, 0])).toShape()


class TrajectoryFeature(_Feature):
    """The trajectory of Point (moving space) under Motion: exact rational for a Q-motion,
    fitted within 1e-6 of its size for a quaternion spline."""

    def setup(self, obj):
        _add(obj, "App::PropertyLink", "Motion", "Trajectory", "a qmotion motion feature")
        _add(obj, "App::PropertyVector", "Point", "Trajectory", "a point of the moving space")
        _certificate(obj, "App::PropertyInteger", (("Degree", "the curve's degree"),))
        _certificate(obj, "App::PropertyBool",
                     (("Exact", "True: the exact trajectory; False: fitted"),))

    def execute(self, obj):
        m = motion_of(obj.Motion)
        c = qmotion.trajectory(m, [obj.Point.x, obj.Point.y, obj.Point.z])
        _certify(obj, {"Degree": c.degree, "Exact": m.rational})
        obj.Shape = shapes.part_curve(c).toShape()


class SweepFeature(_Feature):
    """The kinematic surface of Profile's edges under Motion: exact NURBS faces for a
    Q-motion, fitted within Tolerance for a quaternion spline."""

    def setup(self, obj):
        _add(obj, "App::PropertyLink", "Motion", "Sweep", "a qmotion motion feature")
        _add(obj, "App::PropertyLink", "Profile", "Sweep", "a Part object with edges")
        _add(obj, "App::PropertyFloat", "Tolerance", "Sweep",
             "a spline's fitting tolerance (0: 1e-6 of the size)")
        _certificate(obj, "App::PropertyInteger",
                     (("DegreeU", "degree along the motion"),
                      ("DegreeV", "degree along the profile"), ("Faces", "faces")))
        _certificate(obj, "App::PropertyBool",
                     (("Exact", "True: the exact surface; False: fitted within Tolerance"),))

    def execute(self, obj):
        m = motion_of(obj.Motion)
        if obj.Profile is None:
            raise ValueError("%s: no profile" % obj.Label)
        profile = shapes.profile_document(obj.Profile.Shape)
        surfaces = qmotion.sweep(m, profile, tol=obj.Tolerance if obj.Tolerance > 0 else -1.0)
        faces = [shapes.part_surface(s).toShape() for s in surfaces]
        _certify(obj, {"DegreeU": max(s.degree_u for s in surfaces),
                       "DegreeV": max(s.degree_v for s in surfaces), "Faces": len(faces),
                       "Exact": m.rational})
        obj.Shape = shapes.faces_shape(faces)


class SweptVolumeFeature(_Feature):
    """The space Body occupies under Motion, as qmotion's certified enclosing mesh made a
    solid: it contains the swept volume, every vertex within DistanceBound <= Tolerance."""

    def setup(self, obj):
        _add(obj, "App::PropertyLink", "Motion", "Volume", "a qmotion motion feature")
        _add(obj, "App::PropertyString", "Body", "Volume",
             "a body spec (cutter:ball,6,20, box:a,b,c, ...), used without BodyObject")
        _add(obj, "App::PropertyLink", "BodyObject", "Volume",
             "a closed Part object, tessellated within Tolerance / 4")
        _add(obj, "App::PropertyFloat", "Tolerance", "Volume", "0: 1e-3 of the volume's size")
        _certificate(obj, "App::PropertyFloat",
                     (("DistanceBound", "certified: every vertex within it of the volume"),
                      ("VolumeLower", "certified lower bound of the volume"),
                      ("VolumeUpper", "certified upper bound of the volume")))
        _certificate(obj, "App::PropertyInteger", (("Triangles", "of the mesh"),))

    def execute(self, obj):
        m = motion_of(obj.Motion)
        tol = obj.Tolerance if obj.Tolerance > 0 else None
        if obj.BodyObject is not None:
            body = shapes.mesh_arrays(obj.BodyObject.Shape, (tol or 0.1) / 4)
        elif obj.Body:
            body = obj.Body
        else:
            raise ValueError("%s: no body (set Body or BodyObject)" % obj.Label)
        v = qmotion.swept_volume(m, body, tol=tol)
        _certify(obj, {"DistanceBound": v["distance_bound"], "VolumeLower": v["volume_bounds"][0],
                       "VolumeUpper": v["volume_bounds"][1], "Triangles": len(v["triangles"])})
        obj.Shape = shapes.mesh_solid(v["vertices"], v["triangles"])


def _new(doc, name, proxy):
    obj = doc.addObject("Part::FeaturePython", name)
    proxy(obj)
    if FreeCAD.GuiUp:
        obj.ViewObject.Proxy = 0  # Part's own view provider
    return obj


def make_motion(doc, poses, times=None, scheme="q-motion", rotation="elliptic",
                form="default", name="Motion"):
    """A motion feature from a list of FreeCAD Placements (times optional) or a pose file."""
    obj = _new(doc, name, MotionFeature)
    if isinstance(poses, str):
        obj.PoseFile = poses
    else:
        obj.Placements = list(poses)
        obj.Times = list(times or [])
    obj.Scheme, obj.Rotation, obj.Form = scheme, rotation, form
    return obj


def make_trajectory(doc, motion, point, name="Trajectory"):
    obj = _new(doc, name, TrajectoryFeature)
    obj.Motion = motion
    obj.Point = FreeCAD.Vector(*point)
    return obj


def make_sweep(doc, motion, profile, tol=0.0, name="Sweep"):
    obj = _new(doc, name, SweepFeature)
    obj.Motion, obj.Profile, obj.Tolerance = motion, profile, tol
    return obj


def make_swept_volume(doc, motion, body, tol=0.0, name="SweptVolume"):
    """body: a spec string, or a closed Part object (tessellated within tol / 4)."""
    obj = _new(doc, name, SweptVolumeFeature)
    obj.Motion, obj.Tolerance = motion, tol
    if isinstance(body, str):
        obj.Body = body
    else:
        obj.BodyObject = body
    return obj
