// python/jobs.cpp: the job as calls on a Motion: trajectory, sweep, export, check, toolpath,
// and demo, compare and check_exact; verify, on a machining program.
#include "convert.hpp"

namespace qmotion::python {
namespace {

py::object toolpath_call(const Motion& motion, const std::string& path, const py::object& point,
                         const py::object& axis, double chord_tol, double angle_tol,
                         double max_step, double feed, bool arc_length, const std::string& rotary,
                         bool c_hold, const std::string& units, bool nurbs,
                         const std::string& machine, const std::string& feed_mode,
                         const std::map<std::string, double>& axis_limits,
                         const std::string& dialect, double controller_tol) {
  ToolpathOptions o;
  o.dialect = dialect;
  o.controller_tol = controller_tol;
  o.machine_file = machine;
  o.feed_mode = feed_mode;
  for (const auto& [word, v] : axis_limits) {
    if (word.size() != 1)
      throw Error(Errc::invalid_input,
                  "axis_limits: " + word + ": expected an axis word X, Y, Z, A, B or C");
    o.axis_limits[word[0]] = v;
  }
  o.nurbs = nurbs;
  o.units = units;
  o.output = path;
  o.point = vec3(point, "point");
  o.axis = vec3(axis, "axis");
  o.chord_tol = chord_tol;
  o.angle_tol_deg = angle_tol;
  o.max_step = max_step;
  o.feed = feed;
  o.arc_length = arc_length;
  o.rotary = rotary;
  o.c_hold = c_hold;
  return to_python(toolpath(motion, o).report());
}

/// trajectory, sweep, export, check and compare: the geometry a motion makes and its check.
void bind_geometry_jobs(py::module_& m) {
  m.def(
      "trajectory",
      [](const PyMotion& p, const py::object& point, int max_degree, double tol,
         const std::string& units) {
        return trajectory_nurbs(p.motion, vec3(point, "point"),
                                export_options("", max_degree, tol, units, false, false));
      },
      py::arg("motion"), py::arg("point"), py::arg("max_degree") = -1, py::arg("tol") = -1.0,
      py::arg("units") = "",
      "The trajectory of `point` (moving space) as a NurbsCurve parametrised by t. A Q-motion's "
      "is exact at its minimal degree with positive weights (above max_degree an approximation "
      "within tol, default 1e-6 of its size); a quaternion spline's is fitted within tol at "
      "degree max_degree (default 5). units converts (mm, cm, m, um, in, ft).");

  m.def(
      "sweep",
      [](const PyMotion& p, const py::object& profile, int max_degree, double tol,
         const std::string& units) {
        return sweep_nurbs(p.motion, to_profile(profile, p.motion.units()),
                           export_options("", max_degree, tol, units, false, false));
      },
      py::arg("motion"), py::arg("profile"), py::arg("max_degree") = -1, py::arg("tol") = -1.0,
      py::arg("units") = "",
      "The kinematic surface M(t) x(v) of each profile edge: a list of NurbsSurface, u = t, v "
      "the edge's parameter; poles M_i X_j for a Q-motion (exact, no fitting), fitted within "
      "tol at degree max_degree (default 5) for a quaternion spline. profile: a NurbsCurve; a "
      "nurbs_curve dict (docs/formats.md) or a list of them in order (a wire); or a "
      "spec as for the CLI: a .json/.step/.igs file, 'segment:x0,y0,z0:x1,y1,z1', "
      "'polyline:x,y,z:...', 'rect:w,h', 'circle:r', 'arc:r,a0,a1'.");

  m.def(
      "export",
      [](const PyMotion& p, const std::string& path, const py::object& profile,
         const py::object& point, int max_degree, double tol, const std::string& units,
         bool single_face, bool solid, double deflection, double angle, bool ascii) {
        auto opt = export_options(path, max_degree, tol, units, single_face, solid);
        opt.deflection = deflection;
        opt.angle_deg = angle;
        opt.ascii = ascii;
        return to_python(result_json(
            export_geometry(p.motion, to_geometry(p.motion.units(), profile, point), opt)));
      },
      py::arg("motion"), py::arg("path"), py::arg("profile") = py::none(),
      py::arg("point") = py::none(), py::arg("max_degree") = -1, py::arg("tol") = -1.0,
      py::arg("units") = "", py::arg("single_face") = false, py::arg("solid") = false,
      py::arg("deflection") = 0.0, py::arg("angle") = 20.0, py::arg("ascii") = false,
      "Writes the trajectory of `point` or the sweep of `profile` to path (.json, .step/.stp, "
      ".igs/.iges; sweeps also a .stl/.obj/.ply mesh within deflection, default 1e-3 of the "
      "size, angle in degrees, ascii STL/PLY), as `qmotion trajectory` / `qmotion sweep` do: "
      "STEP/IGES shells split at C0 knots (single_face: one face per edge), solid=True for a "
      "closed planar profile. Returns a dict: degrees, continuity, faces, poles, units, volume, "
      "for a mesh its triangles and measured max_deviation, for a fit its "
      "approximation_bound (proven), approximation_deviation (measured) and "
      "approximation_tolerance.");

  m.def(
      "demo", [](const std::string& dir) { return to_python(write_demo(dir)); },
      py::arg("dir") = "demo-out",
      "Runs `qmotion demo`: five embedded poses -> motion -> trajectories and the kinematic "
      "surface of a parabola as JSON/STEP/IGES, checked, with demo.svg and report.json, all "
      "written into dir or none of them. Returns the report as a dict.");

  m.def(
      "check",
      [](const std::string& path, const PyMotion& p, const py::object& profile,
         const py::object& point, int grid) {
        return to_python(
            check(path, p.motion, to_geometry(p.motion.units(), profile, point), grid));
      },
      py::arg("path"), py::arg("motion"), py::arg("profile") = py::none(),
      py::arg("point") = py::none(), py::arg("grid") = 41,
      "The exactness check of `qmotion check`: the file's NURBS (STEP/IGES read through "
      "OpenCASCADE) against the motion applied to the profile or point. A dict with "
      "max_deviation, relative_deviation, weights_positive, valid, faces, closed, volume, ... "
      "A quaternion spline is checked against the spline itself (exp and log), not the fit.");

  m.def(
      "compare",
      [](const py::object& poses, const std::string& param, const py::object& point,
         const std::string& profile, double tol, const std::string& units) {
        CompareOptions o;
        o.param = param;
        if (!point.is_none()) o.point = vec3(point, "point");
        o.profile = profile;
        o.rel_tol = tol;
        return to_python(to_json(compare_schemes(to_poses(poses, units), o)));
      },
      py::arg("poses"), py::arg("param") = "", py::arg("point") = py::none(),
      py::arg("profile") = "", py::arg("tol") = 1e-6, py::arg("units") = "mm",
      "`qmotion compare`: for elliptic bspline, c1, kks, quintic and quartic through the "
      "poses, a list of dicts: max_angular_velocity, max_angular_acceleration, "
      "trajectory_length (of point), sweep_poles (exact, or fitted within tol of the sweep's "
      "size), sweep_deviation, max_key_residual; or error.");
}

/// toolpath, animate, view, volume and check_exact: what a motion drives.
void bind_output_jobs(py::module_& m) {
  const char* toolpath_doc =
      "`qmotion toolpath`: cutter-location points along the trajectory of point with the tool "
      "axis R(t) axis, each chord within chord_tol of the exact trajectory and each axis within "
      "angle_tol degrees of the chord's blend (certified from control points), written to path "
      "(.apt/.cls, .csv, .nc/.ngc; rotary='ac' or 'bc' for a table-tilting machine, or machine= "
      "a machine file, the bounds then covering the machine's linear interpolation of its axes; "
      "feed_mode='inverse-time' for G93 with axis_limits={'X': 20000, 'C': 7200}; nurbs=True "
      "for G06.2 NURBS blocks of degree <= 3 with a certified deviation; dialect='linuxcnc', "
      "'fanuc' or 'siemens' for the controller's words and path mode, controller_tol for the "
      "part of chord_tol a 3-axis program leaves to its blending). Every bound holds for "
      "the numbers as written. Returns the report dict: points, path_length, "
      "machining_time_min, max_chord_deviation_bound, rounding_bound, ... (with a machine: "
      "machine, machine_interpolation_bound, ...; with nurbs: degree, control_points, spans, "
      "exact, max_deviation_bound, max_deviation_measured)";
  m.def(
      "toolpath",
      [](const PyMotion& p, const std::string& path, const py::object& point,
         const py::object& axis, double chord_tol, double angle_tol, double max_step, double feed,
         bool arc_length, const std::string& rotary, bool c_hold, const std::string& units,
         bool nurbs, const std::string& machine, const std::string& feed_mode,
         const std::map<std::string, double>& axis_limits, const std::string& dialect,
         double controller_tol) {
        return toolpath_call(p.motion, path, point, axis, chord_tol, angle_tol, max_step, feed,
                             arc_length, rotary, c_hold, units, nurbs, machine, feed_mode,
                             axis_limits, dialect, controller_tol);
      },
      py::arg("motion"), py::arg("path"), py::arg("point"),
      py::arg("axis") = std::vector<double>{0, 0, 1}, py::arg("chord_tol"),
      py::arg("angle_tol") = 0.5, py::arg("max_step") = 0.0, py::arg("feed") = 1000.0,
      py::arg("arc_length") = false, py::arg("rotary") = "", py::arg("c_hold") = false,
      py::arg("units") = "", py::arg("nurbs") = false, py::arg("machine") = "",
      py::arg("feed_mode") = "", py::arg("axis_limits") = std::map<std::string, double>{},
      py::arg("dialect") = "", py::arg("controller_tol") = 0.0, toolpath_doc);
  m.def(
      "animate",
      [](const PyMotion& p, const std::string& path, const std::string& body, const py::object& tol,
         double duration) {
        AnimateOptions o;
        o.output = path;
        o.body = body;
        if (!tol.is_none()) o.tol = tol.cast<double>();
        o.duration = duration;
        return to_python(animate(p.motion, o).report());
      },
      py::arg("motion"), py::arg("path"), py::arg("body") = "", py::arg("tol") = py::none(),
      py::arg("duration") = 0.0,
      "`qmotion animate`: the motion as a glTF 2.0 animation of body (sphere:r, box:a,b,c, "
      "cylinder:r,h, cutter:flat|ball,D,L, cutter:bull,D,rc,L or an .stl/.obj/.ply mesh; "
      "default a cube a tenth of the motion's extent) written to path (.glb or .gltf, metres), "
      "with keyframes that keep every point of the body within tol (motion units; default "
      "1e-3 of the swept space's diagonal) of the exact motion under glTF's and Blender's "
      "interpolation, certified. Returns the report dict: keyframes, distance_bound, "
      "measured_distance, tolerance, metres_per_unit, duration, ...");
  m.def(
      "view",
      [](const PyMotion& p, const std::string& path, const std::string& profile,
         const std::string& body, const py::object& points, bool volume,
         const py::object& body_tol) {
        ViewOptions o;
        o.output = path;
        o.profile = profile;
        o.body = body;
        o.volume = volume;
        if (!body_tol.is_none()) o.volume_tol = body_tol.cast<double>();
        if (!points.is_none())
          for (const auto& x : points) o.points.push_back(vec3(x, "points"));
        return to_python(view(p.motion, o).report());
      },
      py::arg("motion"), py::arg("path"), py::arg("profile") = "", py::arg("body") = "",
      py::arg("points") = py::none(), py::arg("volume") = false, py::arg("body_tol") = py::none(),
      "`qmotion view`: one self-contained HTML page (no network, no server) at path that "
      "animates the motion (either kind) with its key poses, the trajectories of points "
      "(default the origin), the exact sweep of profile and the moving body (volume=True: "
      "and its certified swept volume at body_tol, as `view --volume`); the kernel runs "
      "in the page (WebAssembly) and interpolates again when a pose is edited. Returns the "
      "report dict: bytes, wasm_bytes, poses, editable, method, ...");
  m.def(
      "volume",
      [](const PyMotion& p, const std::string& path, const std::string& body, const py::object& tol,
         const std::string& units, bool ascii) {
        VolumeOptions o;
        o.output = path;
        o.body = body;
        if (!tol.is_none()) o.tol = tol.cast<double>();
        o.units = units;
        o.ascii = ascii;
        return to_python(volume(p.motion, o).report());
      },
      py::arg("motion"), py::arg("path"), py::arg("body"), py::arg("tol") = py::none(),
      py::arg("units") = "", py::arg("ascii") = false,
      "`qmotion volume`: a closed, outward, self-intersection-free mesh at path (.stl, .obj, "
      ".ply, or .json with the report) that encloses for certain the space body (sphere:r, "
      "box:a,b,c, cylinder:r,h, cutter:flat|ball,D,L, cutter:bull,D,rc,L or a closed "
      ".stl/.obj/.ply mesh) occupies under the motion (either kind), every vertex within tol "
      "(output units; default 1e-3 of the volume's diagonal). For sphere:r and cutter:ball "
      "under a rational motion, .step, .igs and .json hold the exact faces instead (the pipe "
      "and its caps). Returns the report dict: volume_bounds, distance_bound, "
      "measured_distance, triangles (exact: faces, degree, volume), ...");
#ifdef QMOTION_WITH_CGAL
  m.def(
      "check_exact",
      [](const std::string& motion_path, const py::object& point) {
        std::optional<Eigen::Vector3d> x;
        if (!point.is_none()) x = vec3(point, "point");
        return to_python(check_exact(motion_path, x));
      },
      py::arg("motion_path"), py::arg("point") = py::none(),
      "`qmotion check --exact`: the motion file recomputed in exact rationals from the poses "
      "it records; a dict with the exact Plucker and interpolation residuals (plucker, "
      "interpolation), file_deviation, the trajectory order of point by an exact gcd beside "
      "the degree trajectory writes (order), and verified.");
#endif
}

/// verify: what a machining program does to a part.
void bind_cam_jobs(py::module_& m) {
  m.def(
      "verify",
      [](const std::string& program, const std::string& tool, const std::string& part,
         const py::object& tol, const std::string& output, const std::string& stock,
         const std::string& map, const std::string& holder,
         const std::vector<std::string>& fixtures) {
        VerifyOptions o;
        o.program = program;
        o.tool = tool;
        o.part = part;
        if (!tol.is_none()) o.tol = tol.cast<double>();
        o.output = output;
        o.stock = stock;
        o.map = map;
        o.holder = holder;
        o.fixtures = fixtures;
        return to_python(verify(o).report());
      },
      py::arg("program"), py::arg("tool"), py::arg("part"), py::arg("tol") = py::none(),
      py::arg("output") = "", py::arg("stock") = "", py::arg("map") = "", py::arg("holder") = "",
      py::arg("fixtures") = std::vector<std::string>{},
      "`qmotion verify`: whether a 3-axis G-code program (.ngc, .nc, .gcode, .tap, .cnc) "
      "gouges part (a closed .stl/.obj/.ply mesh or a STEP/IGES solid, meshed within tol/4; "
      "mm) with tool (cutter:flat|ball,D,L or cutter:bull,D,rc,L), certified at every "
      "instant of every move to within tol (mm, default 0.01); output: a .json file for the "
      "report too; stock (box:x0,y0,z0,x1,y1,z1, a closed mesh or a solid): also the stock "
      "left on the part; map (.ply, .svg, .png): the part "
      "coloured by it; holder (cylinder:r,h above the cutter's length, or holder:r1,h1,r2,h2,... "
      "stacked from it): where it first enters "
      "the stock as cut so far or the part; fixtures (each as a stock): where the cutter or the "
      "holder first touches them. Returns the report dict: gouge (depth [lower, upper], "
      "within_tolerance, never_touches, deepest, moves), collisions (rapids_through_part, "
      "holder), "
      "stock_left (max, mean, where), moves, tolerance, ...");
}

}  // namespace

void bind_jobs(py::module_& m) {
  bind_geometry_jobs(m);
  bind_output_jobs(m);
  bind_cam_jobs(m);
}

}  // namespace qmotion::python
