// tests/bench/occt_peers.cpp: qmotion's exact kinematic sweep side by side with the
// routes an OpenCASCADE user has to the same surface (issue 13, item 6):
//   1. qmotion: the exact rational surface (sweep::kinematic_nurbs), written by io::write_step;
//   2. GeomFill_Sweep with a location law that evaluates our motion exactly (value and
//      first and second derivatives of the rational frame), at several Tol3d and MaxDegree;
//   3. BRepOffsetAPI_MakePipeShell along the origin's exact trajectory, in the default mode
//      and with an auxiliary spine (the trajectory of a second body point);
//   4. GeomAPI_PointsToBSplineSurface fitted to a grid of exact points;
//   5. BRepOffsetAPI_ThruSections lofted through exact sections M(t_i) c.
// For each: construction time (median of repeats), poles, degrees, STEP size, write and
// read-back time, and the true maximum deviation of the surface read back from STEP from
// the exact motion-applied profile, measured by our own dense evaluation both ways (each
// sample's nearest point found from a k-d tree of dense samples of the other surface, then
// Gauss-Newton), never by OpenCASCADE's projection. Prints a Markdown table.
//
//   build/tests/bench/occt_peers [--smoke] [--repeats N] [--out FILE]
//   build/tests/bench/occt_peers --write-alone MOTION (trajectory X,Y,Z | sweep PROFILE) OUT
//
// --write-alone builds what `qmotion trajectory` or `qmotion sweep` builds from the motion
// file (the library's trajectory_nurbs and sweep_nurbs) and writes it with OpenCASCADE's
// STEP writer alone, at the 17 digits qmotion writes: tests/bench/memory.sh puts its peak
// memory beside the command's, the floor a STEP file written through OpenCASCADE has.
//
// Every route runs under the malloc settings of the qmotion executable (fixed thresholds).
// --smoke (CTest) runs one motion and one profile. The exit status is 1 when the exact
// route's deviation exceeds 1e-12 of the bounding-box diagonal or it fails.
#include <malloc.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <memory>
#include <numeric>
#include <optional>
#include <qmotion/api/export.hpp>
#include <qmotion/api/interpolate.hpp>
#include <qmotion/io/occt.hpp>
#include <qmotion/io/poses.hpp>
#include <qmotion/io/profiles.hpp>
#include <qmotion/io/qspline_file.hpp>
#include <qmotion/kernel/interpolation.hpp>
#include <qmotion/kernel/parametrization.hpp>
#include <qmotion/kernel/spline_interpolation.hpp>
#include <qmotion/sweep/profiles.hpp>
#include <qmotion/sweep/surface.hpp>
#include <qmotion/sweep/surface_eval.hpp>
#include <sstream>
#include <string>
#include <vector>

// OpenCASCADE after qmotion's headers: its `Handle` macro breaks the CGAL headers they
// include.
// clang-format off
#include <BRepBuilderAPI_MakeEdge.hxx>
#include <BRepBuilderAPI_MakeFace.hxx>
#include <BRepBuilderAPI_MakeWire.hxx>
#include <BRepOffsetAPI_MakePipeShell.hxx>
#include <BRepOffsetAPI_ThruSections.hxx>
#include <BRepTools.hxx>
#include <BRep_Tool.hxx>
#include <GeomAPI_PointsToBSplineSurface.hxx>
#include <GeomConvert.hxx>
#include <GeomFill_Sweep.hxx>
#include <GeomFill_UniformSection.hxx>
#include <Geom_BSplineCurve.hxx>
#include <Geom_BSplineSurface.hxx>
#include <IFSelect_ReturnStatus.hxx>
#include <IGESControl_Controller.hxx>
#include <IGESControl_Writer.hxx>
#include <IGESData_IGESWriter.hxx>
#include <IGESSelect_WorkLibrary.hxx>
#include <STEPControl_Reader.hxx>
#include <STEPControl_Writer.hxx>
#include <Standard_Failure.hxx>
#include <StepData_Protocol.hxx>
#include <StepData_StepWriter.hxx>
#include <TColStd_Array1OfReal.hxx>
#include <TColgp_Array2OfPnt.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Face.hxx>
#include <TopoDS_Shape.hxx>
#include <TopoDS_Wire.hxx>
#include <XSControl_WorkSession.hxx>
#include "occt_convert.hpp"
#include "occt_peers_case.hpp"
#include "occt_peers_deviation.hpp"
#include "occt_peers_law.hpp"
// clang-format on

namespace {
using namespace qmotion;
using namespace qmotion::bench;
namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

double ms_since(Clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0 : v[v.size() / 2];
}

// ---- OpenCASCADE geometry from ours ---------------------------------------------------

TopoDS_Wire wire_of(const Handle(Geom_Curve) & c) {
  return BRepBuilderAPI_MakeWire(BRepBuilderAPI_MakeEdge(c)).Wire();
}

std::string fmt(double x, int prec = 3) {
  std::ostringstream o;
  o.precision(prec);
  o << x;
  return o.str();
}

// ---- one route, measured ------------------------------------------------------------------

struct Row {
  std::string motion, profile, route, settings;
  bool ok = false;
  std::string why;
  double build_ms = 0, write_ms = 0, read_ms = 0, dev = 0, rel = 0;
  long poles = 0;
  std::string degrees;
  std::uintmax_t step_bytes = 0;
};

void describe(const TopoDS_Shape& shape, Row& r) {
  int pu = 0, pv = 0;
  for (const auto& f : faces_of(shape)) {
    Handle(Geom_BSplineSurface) bs = Handle(Geom_BSplineSurface)::DownCast(f.s);
    if (bs.IsNull()) {
      try {
        bs = GeomConvert::SurfaceToBSplineSurface(f.s);
      } catch (const Standard_Failure&) {
        continue;
      }
    }
    r.poles += static_cast<long>(bs->NbUPoles()) * bs->NbVPoles();
    pu = std::max(pu, bs->UDegree());
    pv = std::max(pv, bs->VDegree());
  }
  r.degrees = std::to_string(pu) + "×" + std::to_string(pv);
}

std::string temp_step(const std::string& tag) {
  return (fs::temp_directory_path() / ("occt_peers_" + tag + ".step")).string();
}

/// Writes the shape with OpenCASCADE's STEP writer alone; the time of Transfer + Write.
/// With `digits17`, the model is printed as STEPControl_Writer::Write prints it
/// (StepData_StepWriter) but with the 17 significant digits io::write_step writes
/// ("%.17E"; the default prints about 12): the same numbers as ours, OpenCASCADE alone.
double occt_write_step(const TopoDS_Shape& shape, const std::string& path, bool digits17 = false) {
  const auto t0 = Clock::now();
  STEPControl_Writer w;
  if (w.Transfer(shape, STEPControl_AsIs) != IFSelect_RetDone)
    throw std::runtime_error("STEP writer failed");
  if (!digits17) {
    if (w.Write(path.c_str()) != IFSelect_RetDone) throw std::runtime_error("STEP writer failed");
    return ms_since(t0);
  }
  if (!bench::print_step17(w, path)) throw std::runtime_error("STEP writer failed");
  return ms_since(t0);
}

/// OpenCASCADE's IGES writer alone on the face; with `digits17`, its IGESData_IGESWriter
/// printing 17 significant digits (%.17E) as io::write_iges does.
void occt_write_iges(const TopoDS_Shape& face, const std::string& path, bool digits17 = false) {
  IGESControl_Controller::Init();
  IGESControl_Writer w("MM", 1);
  w.AddShape(face);
  w.ComputeModel();
  if (!digits17) {
    if (!w.Write(path.c_str())) throw std::runtime_error("IGES writer failed");
    return;
  }
  IGESData_IGESWriter iw(w.Model());
  iw.FloatWriter().SetFormat("%.17E");
  iw.SendModel(IGESSelect_WorkLibrary::DefineProtocol());
  std::ofstream f(path, std::ios::binary);
  if (!f || !iw.Print(f)) throw std::runtime_error("IGES writer failed");
}

TopoDS_Shape read_step(const std::string& path, double& ms) {
  const auto t0 = Clock::now();
  STEPControl_Reader r;
  if (r.ReadFile(path.c_str()) != IFSelect_RetDone) throw std::runtime_error("STEP reader failed");
  r.TransferRoots();
  TopoDS_Shape s = r.OneShape();
  ms = ms_since(t0);
  return s;
}

/// The median wall time (ms) of `repeats` calls of f, after one untimed call when warm_up;
/// a call over 2 s ends the repeats (one run of a slow route says enough).
double median_ms(int repeats, const std::function<void()>& f, bool warm_up = false) {
  if (warm_up) f();
  std::vector<double> t;
  for (int i = 0; i < repeats; ++i) {
    const auto t0 = Clock::now();
    f();
    t.push_back(ms_since(t0));
    if (t.back() > 2000) break;
  }
  return median(t);
}

/// One row of the table: fill(r) measures the route; an exception it throws marks the row
/// failed with its message. Prints the row's progress line on stderr.
Row table_row(const Case& c, const std::string& route, const std::string& settings,
              const std::function<void(Row&)>& fill) {
  Row r;
  r.motion = c.motion_name;
  r.profile = c.profile_name;
  r.route = route;
  r.settings = settings;
  try {
    fill(r);
    r.ok = true;
  } catch (const Standard_Failure& e) {
    r.why =
        std::string("OpenCASCADE: ") + (e.GetMessageString() ? e.GetMessageString() : "failure");
  } catch (const std::exception& e) {
    r.why = e.what();
  }
  std::cerr << "  " << r.route << " [" << r.settings << "]: "
            << (r.ok ? fmt(r.build_ms) + " ms, deviation " + fmt(r.dev, 2) : "failed: " + r.why)
            << "\n";
  return r;
}

/// Runs build() `repeats` times (the median is its time), then writes the shape to STEP,
/// reads it back and measures the deviation of what was read.
Row measure(const Case& c, const std::string& route, const std::string& settings, int repeats,
            int resolution, const std::function<TopoDS_Shape()>& build) {
  return table_row(c, route, settings, [&](Row& r) {
    TopoDS_Shape shape;
    r.build_ms = median_ms(repeats, [&] { shape = build(); });
    describe(shape, r);
    const std::string path = temp_step("peer");
    r.write_ms = occt_write_step(shape, path);
    r.step_bytes = fs::file_size(path);
    const auto faces = faces_of(read_step(path, r.read_ms));
    fs::remove(path);
    if (faces.empty()) throw std::runtime_error("no face read back");
    r.dev = deviation(c, faces, resolution);
    r.rel = r.dev / c.diagonal;
  });
}

struct WriteTimes {  // route 1's export against OpenCASCADE's writers alone, same face
  double step_ours = 0, step_occt = 0, step_occt17 = 0, iges_ours = 0, iges_occt = 0,
         iges_occt17 = 0;
};

/// Route 1: qmotion builds the exact surface and writes it with io::write_step. Also times
/// io::write_step / write_iges against OpenCASCADE's writers alone on the same face.
Row exact_route(const Case& c, int repeats, WriteTimes& wt) {
  return table_row(c, "1 qmotion exact", "—", [&](Row& r) {
    sweep::NurbsSurface<double> s;
    r.build_ms = median_ms(repeats, [&] { s = sweep::kinematic_nurbs(c.motion, c.profile); });
    r.poles = static_cast<long>(s.points.size() * s.points.front().size());
    r.degrees = std::to_string(s.degree_u) + "×" + std::to_string(s.degree_v);
    const std::string path = temp_step("exact");
    io::write_step(path, s, {});
    r.step_bytes = fs::file_size(path);
    const auto faces = faces_of(read_step(path, r.read_ms));
    if (faces.size() != 1) throw std::runtime_error("expected one face back");
    r.dev = parametric_deviation(c, faces.front());
    r.rel = r.dev / c.diagonal;
    // Writing: ours against OpenCASCADE's writers alone on the same face (built once,
    // outside the timing). Each writer is warmed up once; then they take turns, a round at a
    // time and each round starting with the next writer, so a busy spell of the shared
    // machine falls on all of them and none always comes first; medians of ten.
    const TopoDS_Face face = BRepBuilderAPI_MakeFace(to_occt(s), 1e-7).Face();
    const std::string igs = (fs::temp_directory_path() / "occt_peers_exact.igs").string();
    const std::vector<std::function<void()>> writers = {
        [&] { io::write_step(path, s, {}); },       [&] { occt_write_step(face, path); },
        [&] { occt_write_step(face, path, true); }, [&] { io::write_iges(igs, s, {}); },
        [&] { occt_write_iges(face, igs); },        [&] { occt_write_iges(face, igs, true); }};
    std::vector<std::vector<double>> t(writers.size());
    for (const auto& w : writers) w();
    for (int round = 0; round < std::max(10, repeats); ++round)
      for (std::size_t i = 0; i < writers.size(); ++i) {
        const std::size_t k = (i + static_cast<std::size_t>(round)) % writers.size();
        const auto t0 = Clock::now();
        writers[k]();
        t[k].push_back(ms_since(t0));
      }
    r.write_ms = wt.step_ours = median(t[0]);
    wt.step_occt = median(t[1]);
    wt.step_occt17 = median(t[2]);
    wt.iges_ours = median(t[3]);
    wt.iges_occt = median(t[4]);
    wt.iges_occt17 = median(t[5]);
    fs::remove(path);
    fs::remove(igs);
  });
}

/// Route 1 under `--max-degree D --tol T`: qmotion::sweep_nurbs approximates on a common knot
/// vector (what a user whose CAD system caps the degree gets from qmotion). Timed without
/// the self-intersection check that every CLI sweep runs: construction only.
void capped_routes(const Case& c, bool smoke, int repeats, int resolution, std::vector<Row>& rows) {
  if (smoke) return;
  for (const int deg : {7, 5})
    for (const double tol : {1e-5, 1e-7}) {
      if (c.exact.degree_u <= deg) continue;

      std::ostringstream set;
      set << "--max-degree " << deg << " --tol " << tol;
      rows.push_back(measure(c, "1 qmotion, degree capped", set.str(), repeats, resolution, [&] {
        qmotion::ExportOptions o;
        o.max_degree = deg;
        o.tol = tol;
        o.self_intersection_check = false;  // construction only, as for the other routes
        const auto s = qmotion::sweep_nurbs(c.motion, sweep::single_edge(c.profile), o);
        return TopoDS_Shape(BRepBuilderAPI_MakeFace(to_occt(s.front()), 1e-7).Face());
      }));
    }
}

// ---- the peers ------------------------------------------------------------------------------

void peers(const Case& c, bool smoke, int repeats, int resolution, std::vector<Row>& rows) {
  const std::vector<double> tols =
      smoke ? std::vector<double>{1e-3} : std::vector<double>{1e-3, 1e-5, 1e-7};
  const std::vector<int> degs = smoke ? std::vector<int>{10} : std::vector<int>{14, 10, 7, 5};
  const Handle(Geom_BSplineCurve) prof = to_occt(c.profile);
  const int segmax = std::max(30, 8 * c.spans() + 30);
  for (double tol : tols)
    for (int deg : degs) {
      std::ostringstream set;
      set << "Tol3d " << tol << ", MaxDegree " << deg;
      rows.push_back(measure(c, "2 GeomFill_Sweep, exact law", set.str(), repeats, resolution, [&] {
        // The law's matrix splines are built inside the timing: the exact route builds its
        // own from the motion too.
        Handle(GeomFill_LocationLaw) law = new MotionLaw(std::make_shared<const Frames>(c.motion));
        Handle(GeomFill_SectionLaw) sec =
            new GeomFill_UniformSection(prof, prof->FirstParameter(), prof->LastParameter());
        GeomFill_Sweep sw(law, Standard_False);
        sw.SetTolerance(tol, tol, 1e-5, 1e-2);
        sw.Build(sec, GeomFill_Location, GeomAbs_C2, deg, segmax);
        if (!sw.IsDone()) throw std::runtime_error("not done");
        return TopoDS_Shape(BRepBuilderAPI_MakeFace(sw.Surface(), 1e-7).Face());
      }));
    }
  const TopoDS_Wire spine = wire_of(to_occt(sweep::trajectory_curve(c.motion, V3(0, 0, 0))));
  double size = 0;
  for (const auto& p : c.profile.points) size = std::max(size, p.norm());
  const TopoDS_Wire aux =
      wire_of(to_occt(sweep::trajectory_curve(c.motion, V3(0, 0, std::max(size, 1.0)))));
  const TopoDS_Wire start = wire_of(to_occt(placed(c, c.motion.a())));
  for (int mode = 0; mode < 2; ++mode)
    rows.push_back(
        measure(c, "3 MakePipeShell on the origin's path",
                mode ? "auxiliary spine: path of (0, 0, r)" : "default (corrected Frenet)", repeats,
                resolution, [&] {
                  BRepOffsetAPI_MakePipeShell ps(spine);
                  if (mode) ps.SetMode(aux, Standard_True);
                  ps.Add(start, Standard_False, Standard_False);
                  ps.Build();
                  if (!ps.IsDone()) throw std::runtime_error("not done");
                  return ps.Shape();
                }));
  const int nu = std::min(24 * c.spans() + 64, 400), nv = 48;
  TColgp_Array2OfPnt grid(1, nu, 1, nv);
  for (int i = 1; i <= nu; ++i)
    for (int j = 1; j <= nv; ++j) {
      const V3 p = c.point(c.motion.a() + (c.motion.b() - c.motion.a()) * (i - 1) / (nu - 1),
                           (j - 1) / double(nv - 1));
      grid.SetValue(i, j, gp_Pnt(p.x(), p.y(), p.z()));
    }
  for (double tol : tols) {
    std::ostringstream set;
    set << nu << "×" << nv << " points, Tol3d " << tol << ", degree 3–8, C2";
    rows.push_back(measure(c, "4 PointsToBSplineSurface", set.str(), repeats, resolution, [&] {
      GeomAPI_PointsToBSplineSurface fit(grid, 3, 8, GeomAbs_C2, tol);
      if (!fit.IsDone()) throw std::runtime_error("not done");
      return TopoDS_Shape(BRepBuilderAPI_MakeFace(fit.Surface(), 1e-7).Face());
    }));
  }
  const int sections = std::clamp(4 * c.spans() + 1, 9, 101);
  std::vector<TopoDS_Wire> wires;
  for (int i = 0; i < sections; ++i)
    wires.push_back(wire_of(
        to_occt(placed(c, c.motion.a() + (c.motion.b() - c.motion.a()) * i / (sections - 1)))));
  rows.push_back(measure(c, "5 ThruSections", std::to_string(sections) + " exact sections", repeats,
                         resolution, [&] {
                           BRepOffsetAPI_ThruSections loft(Standard_False, Standard_False, 1e-6);
                           loft.CheckCompatibility(Standard_False);
                           for (const auto& w : wires) loft.AddWire(w);
                           loft.Build();
                           if (!loft.IsDone()) throw std::runtime_error("not done");
                           return loft.Shape();
                         }));
}

// ---- the cases ------------------------------------------------------------------------------

kernel::Pose<double> pose(double angle_deg, const V3& axis, const V3& position) {
  const double h = angle_deg * M_PI / 360;
  const V3 a = axis.normalized() * std::sin(h);
  return kernel::Pose<double>{std::nullopt, position,
                              kernel::Quaternion<double>(std::cos(h), a.x(), a.y(), a.z())};
}

kernel::Motion<double> demo_motion(const std::string& data) {
  qmotion::InterpolateOptions o;
  o.form = "bezier";
  return qmotion::interpolate(io::read_poses(data + "/poses/five_positions.json"), o)
      .motion.rational();
}

/// Four poses turning 140 degrees in all about a tilted axis: elliptic (cubic) rotation,
/// TR with a cubic translation.
kernel::Motion<double> turn140_motion() {
  std::vector<kernel::Pose<double>> P;
  for (int i = 0; i <= 3; ++i)
    P.push_back(
        pose(140.0 * i / 3, V3(0.3, 0.2, 1), V3(40 * i, 25 * std::sin(i), 10 * i * i / 3.0)));
  return kernel::interpolate_bezier(P, kernel::parametrize(P, kernel::ParamRule::chordal), {});
}

/// 200 poses along a helix (radius 50 mm, 3 turns), turning with the tangent and rolling:
/// the default cubic B-spline motion, chordal parameters.
kernel::Motion<double> helix_motion(int n) {
  std::vector<kernel::Pose<double>> P;
  for (int i = 0; i < n; ++i) {
    const double a = 6 * M_PI * i / (n - 1);
    P.push_back(pose(a * 180 / M_PI + 20 * std::sin(3 * a), V3(0.1 * std::cos(a), 0.1, 1),
                     V3(50 * std::cos(a), 50 * std::sin(a), 8 * a)));
  }
  return kernel::interpolate_bspline(P, kernel::parametrize(P, kernel::ParamRule::chordal),
                                     kernel::SplineOptions{});
}

sweep::NurbsCurve<double> cubic_profile() {  // open cubic NURBS, uneven weights, 6 poles
  return sweep::NurbsCurve<double>{
      3,
      {0, 0, 0, 0, 0.3, 0.6, 1, 1, 1, 1},
      {{-8, 0, 0}, {-5, 0, 6}, {-1, 2, 3}, {2, -1, 7}, {5, 0, 2}, {8, 0, 5}},
      {1, 0.8, 1.3, 0.7, 1.1, 1}};
}

}  // namespace

/// --write-alone: the geometry of `qmotion trajectory` or `qmotion sweep`, written by
/// OpenCASCADE's STEP writer alone at 17 digits (an edge, or a shell of the faces).
int write_alone(const std::string& motion, const std::string& kind, const std::string& arg,
                const std::string& out) {
  const auto m = io::load_motion(motion);
  ExportOptions opt;
  TopoDS_Shape shape;
  if (kind == "trajectory") {
    V3 x;
    if (std::sscanf(arg.c_str(), "%lf,%lf,%lf", &x.x(), &x.y(), &x.z()) != 3) return 2;
    shape = BRepBuilderAPI_MakeEdge(to_occt(trajectory_nurbs(m, x, opt))).Edge();
  } else if (kind == "sweep") {
    const auto faces = sweep_nurbs(m, io::read_profile(arg, m.units()), opt);
    if (faces.size() != 1) return 2;
    shape = BRepBuilderAPI_MakeFace(to_occt(faces.front()), 1e-7).Face();
  } else {
    return 2;
  }
  occt_write_step(shape, out, /*digits17=*/true);
  return 0;
}

int main(int argc, char** argv) {
  // malloc as the qmotion executable sets it (cli/huge_pages.cpp), for every route alike:
  // with glibc's sliding defaults a route's time depended on the heap the routes before it
  // left (the same exact build took 0.8 or 1.9 ms as blocks were unmapped and trimmed
  // between repeats and touched afresh).
  mallopt(M_TOP_PAD, 16 << 20);
  mallopt(M_TRIM_THRESHOLD, 8 << 20);
  mallopt(M_MMAP_THRESHOLD, 32 << 20);
  if (argc == 6 && std::string(argv[1]) == "--write-alone")
    return write_alone(argv[2], argv[3], argv[4], argv[5]);
  bool smoke = false;
  int repeats = 3, resolution = 0;
  std::string out;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--smoke") {
      smoke = true;
    } else if (a == "--repeats" && i + 1 < argc) {
      repeats = std::max(1, std::atoi(argv[++i]));
    } else if (a == "--resolution" && i + 1 < argc) {
      resolution = std::max(10, std::atoi(argv[++i]));
    } else if (a == "--out" && i + 1 < argc) {
      out = argv[++i];
    } else {
      std::cerr << "usage: occt_peers [--smoke] [--repeats N] [--resolution N] [--out FILE]\n";
      return 2;
    }
  }
  if (smoke) {
    repeats = 1;
    if (!resolution) resolution = 60;
  }
  if (!resolution) resolution = 300;
  const std::string data = QMOTION_TEST_DATA;
  std::vector<std::pair<std::string, kernel::Motion<double>>> motions;
  motions.emplace_back("demo (5 poses)", demo_motion(data));
  if (!smoke) {
    motions.emplace_back("cubic × cubic, 140°", turn140_motion());
    motions.emplace_back("B-spline, 200 poses", helix_motion(200));
  }
  std::vector<std::pair<std::string, sweep::NurbsCurve<double>>> profiles;
  profiles.emplace_back("segment", sweep::segment(V3(-10, 0, 0), V3(10, 0, 5)));
  if (!smoke) {
    profiles.emplace_back("half-circle", sweep::arc(10, 0, 180));
    profiles.emplace_back("cubic NURBS", cubic_profile());
  }
  std::vector<Row> rows;
  std::vector<std::pair<std::string, WriteTimes>> writes;
  bool exact_ok = true;
  for (const auto& [mn, m] : motions)
    for (const auto& [pn, p] : profiles) {
      const Case c(mn, pn, m, p);
      std::cerr << mn << " / " << pn << " ...\n";
      WriteTimes wt;
      rows.push_back(exact_route(c, repeats, wt));
      const Row& ex = rows.back();
      if (!ex.ok || !(ex.rel <= 1e-12)) exact_ok = false;
      writes.emplace_back(mn + " / " + pn, wt);
      capped_routes(c, smoke, repeats, resolution, rows);
      peers(c, smoke, repeats, resolution, rows);
    }
  std::ostringstream md;
  md << "| motion | profile | route | settings | result | build (ms) | poles | degrees | STEP (kB) "
        "| write (ms) | read (ms) | max deviation (mm) | / diagonal |\n"
        "|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const auto& r : rows) {
    md << "| " << r.motion << " | " << r.profile << " | " << r.route << " | " << r.settings
       << " | ";
    if (!r.ok) {
      md << "failed: " << r.why << " | | | | | | | | |\n";
      continue;
    }
    md << "ok | " << fmt(r.build_ms) << " | " << r.poles << " | " << r.degrees << " | "
       << fmt(double(r.step_bytes) / 1000.0) << " | " << fmt(r.write_ms) << " | " << fmt(r.read_ms)
       << " | " << fmt(r.dev, 2) << " | " << fmt(r.rel, 2) << " |\n";
  }
  md << "\n| exact surface of | io::write_step (ms) | STEPControl_Writer alone (ms) | ratio "
        "| STEPControl_Writer alone, 17 digits as ours (ms) | ratio "
        "| io::write_iges (ms) | IGESControl_Writer alone (ms) | ratio "
        "| IGESControl_Writer alone, 17 digits as ours (ms) | ratio |\n"
        "|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const auto& [name, w] : writes)
    md << "| " << name << " | " << fmt(w.step_ours) << " | " << fmt(w.step_occt) << " | "
       << fmt(w.step_ours / w.step_occt) << " | " << fmt(w.step_occt17) << " | "
       << fmt(w.step_ours / w.step_occt17) << " | " << fmt(w.iges_ours) << " | " << fmt(w.iges_occt)
       << " | " << fmt(w.iges_ours / w.iges_occt) << " | " << fmt(w.iges_occt17) << " | "
       << fmt(w.iges_ours / w.iges_occt17) << " |\n";
  std::cout << md.str();
  if (!out.empty()) std::ofstream(out) << md.str();
  if (!exact_ok) {
    std::cerr << "occt_peers: the exact route failed or deviates by more than 1e-12 of the "
                 "diagonal\n";
    return 1;
  }
  return 0;
}
