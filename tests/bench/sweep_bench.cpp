// tests/bench/sweep_bench.cpp: motion file -> exact surface -> STEP, side by side with
// OpenCASCADE fitting the same surface from exact points (GeomAPI_PointsToBSplineSurface,
// an approximation: the peer the contract names).
#include <benchmark/benchmark.h>

#include <filesystem>
#include <fstream>
#include <qmotion/api/evaluate.hpp>
#include <qmotion/api/export.hpp>
#include <qmotion/api/interpolate.hpp>
#include <qmotion/api/self_intersection.hpp>
#include <qmotion/io/json_number.hpp>
#include <qmotion/io/motion_json.hpp>
#include <qmotion/io/occt.hpp>
#include <qmotion/io/poses.hpp>
#include <qmotion/io/profiles.hpp>
#include <qmotion/io/qspline_file.hpp>
#include <qmotion/kernel/interpolation.hpp>
#include <qmotion/kernel/parametrization.hpp>
#include <qmotion/sweep/self_intersection.hpp>
#include <qmotion/sweep/shell.hpp>
#include <qmotion/sweep/surface.hpp>

// OpenCASCADE after CGAL: its `Handle` macro breaks CGAL headers included after it.
// clang-format off
#include <BRepBuilderAPI_MakeFace.hxx>
#include <BRepBuilderAPI_Sewing.hxx>
#include <GeomAPI_PointsToBSplineSurface.hxx>
#include <GeomAPI_ProjectPointOnSurf.hxx>
#include <Message.hxx>
#include <Message_Messenger.hxx>
#include <Message_PrinterOStream.hxx>
#include <TColgp_Array2OfPnt.hxx>
#include <TopoDS_Face.hxx>
#include <TopoDS_Shape.hxx>

#include "occt_convert.hpp"
// clang-format on

namespace {
using namespace qmotion;
namespace fs = std::filesystem;

const sweep::NurbsCurve<double> kParabola{
    2, {0, 0, 0, 1, 1, 1}, {{-10, 0, 10}, {0, 0, -10}, {10, 0, 10}}, {1, 1, 1}};

/// Writes a motion file like `qmotion interpolate` does (with its factors) and returns its path.
std::string motion_file(const std::string& poses, int count, kernel::TranslationMethod tr,
                        const std::string& name) {
  io::PoseSet set = io::read_poses(poses);
  set.poses.resize(static_cast<std::size_t>(count));
  const auto P = io::to_poses_double(set);
  kernel::InterpolationOptions o;
  o.translation = tr;
  const auto r = kernel::interpolate_bezier(P, kernel::parametrize(P, kernel::ParamRule::given), o);
  const std::string path = (fs::temp_directory_path() / name).string();
  io::save_motion(r, path);
  return path;
}

std::string test_data(const std::string& rel) { return std::string(QMOTION_TEST_DATA) + "/" + rel; }

sweep::NurbsSurface<double> surface_from_file(const std::string& path) {
  return sweep::to_nurbs(sweep::kinematic_surface(io::load_motion(path).rational(), kParabola));
}

void BM_DemoMotionFileToStep(benchmark::State& st) {  // five poses, elliptic + TR: 12 x 2
  const std::string path = motion_file(test_data("poses/five_positions.json"), 5,
                                       kernel::TranslationMethod::tr, "bench_demo.json");
  const std::string out = (fs::temp_directory_path() / "bench_demo.step").string();
  for (auto _ : st) io::write_step(out, surface_from_file(path), {});
}
BENCHMARK(BM_DemoMotionFileToStep)->Unit(benchmark::kMillisecond);

void BM_Degree16x2MotionFileToStep(benchmark::State& st) {  // nine poses, minimal order: 2m = 16
  const std::string path = motion_file(test_data("poses/helix_40.json"), 9,
                                       kernel::TranslationMethod::minimal, "bench_16.json");
  const std::string out = (fs::temp_directory_path() / "bench_16.step").string();
  st.SetLabel("degree " + std::to_string(surface_from_file(path).degree_u) + " x 2");
  for (auto _ : st) io::write_step(out, surface_from_file(path), {});
}
BENCHMARK(BM_Degree16x2MotionFileToStep)->Unit(benchmark::kMillisecond);

void BM_Degree16x2SurfaceBuildOnly(benchmark::State& st) {
  const std::string path = motion_file(test_data("poses/helix_40.json"), 9,
                                       kernel::TranslationMethod::minimal, "bench_16b.json");
  const kernel::Motion<double> m = io::load_motion(path).rational();
  for (auto _ : st) benchmark::DoNotOptimize(sweep::kinematic_nurbs(m, kParabola));
}
BENCHMARK(BM_Degree16x2SurfaceBuildOnly)->Unit(benchmark::kMicrosecond);

/// Peer: OpenCASCADE fits a B-spline surface to a grid of exact points of the same
/// surface (what a sweep without exact rational motions has to do). Reports its deviation.
void BM_Peer_OcctFitDegree16x2Surface(benchmark::State& st) {
  const std::string path = motion_file(test_data("poses/helix_40.json"), 9,
                                       kernel::TranslationMethod::minimal, "bench_16c.json");
  const auto f = io::read_motion(path);
  const auto m = io::to_motion_double(f);
  const int nu = 60, nv = 15;
  TColgp_Array2OfPnt grid(1, nu, 1, nv);
  for (int i = 1; i <= nu; ++i)
    for (int j = 1; j <= nv; ++j) {
      const auto p =
          kernel::apply_point(kernel::evaluate(m, m.a() + (m.b() - m.a()) * (i - 1) / (nu - 1)),
                              sweep::evaluate(kParabola, (j - 1) / double(nv - 1)));
      grid.SetValue(i, j, gp_Pnt(p.x(), p.y(), p.z()));
    }
  double dev = 0;
  for (auto _ : st) {
    GeomAPI_PointsToBSplineSurface fit(grid, 3, 8, GeomAbs_C2, 1e-6);
    benchmark::DoNotOptimize(fit.Surface());
    st.PauseTiming();
    const auto s = fit.Surface();
    dev = 0;
    // Distance of exact points midway between the fitted ones to the fitted surface (its
    // parametrisation differs from t, so distance, not parameter-wise difference).
    for (int i = 0; i <= 40; ++i)
      for (int j = 0; j <= 10; ++j) {
        const double a = (i + 0.5) / 41.0, b = (j + 0.5) / 11.0;
        const auto p = kernel::apply_point(kernel::evaluate(m, m.a() + (m.b() - m.a()) * a),
                                           sweep::evaluate(kParabola, b));
        GeomAPI_ProjectPointOnSurf proj(gp_Pnt(p.x(), p.y(), p.z()), s);
        if (proj.NbPoints() > 0) dev = std::max(dev, proj.LowerDistance());
      }
    st.ResumeTiming();
  }
  st.counters["max_deviation_mm"] = dev;
}
BENCHMARK(BM_Peer_OcctFitDegree16x2Surface)->Unit(benchmark::kMillisecond);

/// The exact sweep of the demo's parabola along the 9-pose minimal-order motion (degree 16
/// x 2) and a 1000 x 100 grid on it: our batch evaluator, serial and on every core, against
/// OpenCASCADE's Geom_BSplineSurface::D0 point by point on the same surface and grid.
struct GridCase {
  sweep::NurbsSurface<double> s;
  std::vector<double> us, vs;
  GridCase() {
    s = surface_from_file(motion_file(test_data("poses/helix_40.json"), 9,
                                      kernel::TranslationMethod::minimal, "bench_grid.json"));
    for (int i = 0; i < 1000; ++i)
      us.push_back(s.knots_u.front() + (s.knots_u.back() - s.knots_u.front()) * i / 999);
    for (int j = 0; j < 100; ++j)
      vs.push_back(s.knots_v.front() + (s.knots_v.back() - s.knots_v.front()) * j / 99);
  }
};
const GridCase& grid_case() {
  static const GridCase g;
  return g;
}

void BM_GridOurs(benchmark::State& st) {
  const auto& g = grid_case();
  for (auto _ : st)
    benchmark::DoNotOptimize(qmotion::evaluate_grid(g.s, g.us, g.vs, st.range(0) != 0));
  st.SetItemsProcessed(st.iterations() * static_cast<std::int64_t>(g.us.size() * g.vs.size()));
  st.SetLabel(st.range(0) ? "all cores (oneTBB)" : "one core");
}
BENCHMARK(BM_GridOurs)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_Peer_GridOcctD0(benchmark::State& st) {
  const auto& g = grid_case();
  const Handle(Geom_BSplineSurface) occt = bench::to_occt(g.s);
  // The two agree (checked once, outside the timing).
  const auto ours = qmotion::evaluate_grid(g.s, g.us, g.vs, false);
  double diff = 0;
  for (std::size_t i = 0; i < g.us.size(); i += 10)
    for (std::size_t j = 0; j < g.vs.size(); j += 10) {
      gp_Pnt p;
      occt->D0(g.us[i], g.vs[j], p);
      diff =
          std::max(diff, (ours[i * g.vs.size() + j] - Eigen::Vector3d(p.X(), p.Y(), p.Z())).norm());
    }
  std::vector<gp_Pnt> out(g.us.size() * g.vs.size());
  for (auto _ : st) {
    for (std::size_t i = 0; i < g.us.size(); ++i)
      for (std::size_t j = 0; j < g.vs.size(); ++j)
        occt->D0(g.us[i], g.vs[j], out[i * g.vs.size() + j]);
    benchmark::DoNotOptimize(out.data());
  }
  st.SetItemsProcessed(st.iterations() * static_cast<std::int64_t>(g.us.size() * g.vs.size()));
  st.counters["max_difference_from_ours"] = diff;
  st.SetLabel("one core, degree " + std::to_string(g.s.degree_u) + " x " +
              std::to_string(g.s.degree_v));
}
BENCHMARK(BM_Peer_GridOcctD0)->Unit(benchmark::kMillisecond)->UseRealTime();

/// The exact surfaces of a tube of radius 3 along a coil of radius 10 and pitch 20 with
/// st.range(0) turns (12 poses a turn, as tests/data/self_intersection/coil.py makes them).
std::vector<sweep::NurbsSurface<double>> coil_tube(int turns) {
  const fs::path path =
      fs::temp_directory_path() / ("qmotion_bench_coil_" + std::to_string(turns) + ".json");
  {
    std::ofstream f(path);
    f.precision(17);
    f << "{\"units\":\"mm\",\"poses\":[";
    const int n = 12 * turns + 1;
    for (int k = 0; k < n; ++k) {
      const double th = 2 * M_PI * k / 12, pitch = 20, r = 10;
      Eigen::Vector3d t(-r * std::sin(th), r * std::cos(th), pitch / (2 * M_PI));
      t.normalize();
      const Eigen::Vector3d x(-std::cos(th), -std::sin(th), 0), y = t.cross(x);
      f << (k ? "," : "") << "{\"t\":" << static_cast<double>(k) / (n - 1) << ",\"position\":["
        << r * std::cos(th) << "," << r * std::sin(th) << "," << pitch * th / (2 * M_PI)
        << "],\"rotation\":{\"matrix\":[";
      for (int i = 0; i < 3; ++i)
        f << (i ? "," : "") << "[" << x(i) << "," << y(i) << "," << t(i) << "]";
      f << "]}}";
    }
    f << "]}";
  }
  const auto m = qmotion::interpolate(io::read_poses(path.string()), {}).motion;
  fs::remove(path);
  ExportOptions opt;
  opt.self_intersection_check = false;
  return qmotion::sweep_nurbs(m, io::read_profile("circle:3"), opt);
}

/// The proof that the capped tube is free of self-intersection (what --solid runs), as the
/// coil grows: its growth with the number of patches.
void BM_ProveTubeFree(benchmark::State& st) {
  const auto faces = coil_tube(static_cast<int>(st.range(0)));
  sweep::SelfIntersectionProof p;
  for (auto _ : st) p = sweep::prove_no_self_intersection(faces, true, true);
  if (!p.proven()) st.SkipWithError(p.describe().c_str());
  st.counters["patches"] = static_cast<double>(p.patches);
  st.counters["pairs"] = static_cast<double>(p.pairs);
  st.counters["depth"] = p.depth;
}
BENCHMARK(BM_ProveTubeFree)->Arg(2)->Arg(8)->Arg(32)->Unit(benchmark::kMillisecond);

/// The 2000-pose helix of tests/bench/memory.sh at 2000 poses (radius 50 mm, pitch 50 mm, 10
/// turns, the rotation following the tangent with a small roll), interpolated once.
const Motion& helix_2000() {
  static const Motion m = [] {
    const fs::path path = fs::temp_directory_path() / "qmotion_bench_helix_2000.json";
    {
      std::ofstream f(path);
      f.precision(17);
      f << "{\"units\":\"mm\",\"poses\":[";
      const int n = 2000;
      for (int i = 0; i < n; ++i) {
        const double a = 20 * M_PI * i / (n - 1), h = (a + M_PI / 2) / 2,
                     r = 0.1 * std::sin(3 * a) / 2;
        f << (i ? "," : "") << "{\"t\":" << static_cast<double>(i) / (n - 1) << ",\"position\":["
          << 50 * std::cos(a) << "," << 50 * std::sin(a) << "," << 50 * a / (2 * M_PI)
          << "],\"rotation\":{\"quaternion\":[" << std::cos(h) * std::cos(r) << ","
          << std::cos(h) * std::sin(r) << "," << std::sin(h) * std::sin(r) << ","
          << std::sin(h) * std::cos(r) << "]}}";
      }
      f << "]}";
    }
    auto motion = qmotion::interpolate(io::read_poses(path.string()), {}).motion;
    fs::remove(path);
    return motion;
  }();
  return m;
}

/// A 2000-pose circle sweep written as `qmotion sweep` writes it, st.range(0): 0 JSON, 1 STEP;
/// st.range(1): 1 with the default self-intersection check, 0 without. With the check alone
/// (below), where the time goes before OpenCASCADE starts (issue 56, item 4).
void BM_CircleSweep2000(benchmark::State& st) {
  const bool step = st.range(0) != 0, check = st.range(1) != 0;
  ExportOptions o;
  o.output =
      (fs::temp_directory_path() / (step ? "bench_circle.step" : "bench_circle.json")).string();
  o.self_intersection_check = check;
  const auto circle = io::read_profile("circle:5");
  const Motion& m = helix_2000();
  for (auto _ : st) export_geometry(m, Geometry::sweep(circle), o);
  fs::remove(o.output);
  st.SetLabel(std::string(step ? "STEP" : "JSON") +
              (check ? ", default self-intersection check" : ", no check"));
}
BENCHMARK(BM_CircleSweep2000)
    ->Args({0, 1})
    ->Args({0, 0})
    ->Args({1, 1})
    ->Args({1, 0})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

/// The default self-intersection check of that sweep alone (sweep_self_intersections: a
/// tessellation and CGAL's self_intersections).
void BM_CircleSweep2000SelfIntersectionCheck(benchmark::State& st) {
  const auto circle = io::read_profile("circle:5");
  const Motion& m = helix_2000();
  SelfIntersection si;
  for (auto _ : st) si = sweep_self_intersections(m, circle);
  st.counters["samples_t"] = si.samples_t;
  st.counters["samples_v"] = si.samples_v;
  st.counters["crossing_pairs"] = static_cast<double>(si.pairs);
}
BENCHMARK(BM_CircleSweep2000SelfIntersectionCheck)->Unit(benchmark::kMillisecond)->UseRealTime();

/// Peer: OpenCASCADE's STEP writer alone on that sweep's surface (built by the library and
/// handed over as geometry), printing 17 significant digits as qmotion does. st.range(0): 0,
/// the surface as one face, C0 across the circle's four arcs (OpenCASCADE's fewest bytes); 1,
/// the shell qmotion writes, one C1 face between C0 knots, sewn as qmotion sews it.
void BM_Peer_OcctWriteCircleSweep2000(benchmark::State& st) {
  Message::DefaultMessenger()->RemovePrinters(STANDARD_TYPE(Message_PrinterOStream));
  const auto surfaces = sweep_nurbs(helix_2000(), io::read_profile("circle:5"), ExportOptions{});
  sweep::NurbsShell<double> shell;
  shell.faces = st.range(0) ? sweep::split_c0(surfaces.front()) : surfaces;
  std::vector<Handle(Geom_BSplineSurface)> faces;
  for (const auto& f : shell.faces) faces.push_back(bench::to_occt(f));
  const std::string path = (fs::temp_directory_path() / "bench_circle_occt.step").string();
  for (auto _ : st) {
    TopoDS_Shape shape;
    if (faces.size() == 1) {
      shape = BRepBuilderAPI_MakeFace(faces.front(), 1e-9).Face();
    } else {
      BRepBuilderAPI_Sewing sewing(std::max(1e-7, 1e-9 * sweep::diagonal(shell)));
      for (const auto& f : faces) sewing.Add(BRepBuilderAPI_MakeFace(f, 1e-9).Face());
      sewing.Perform();
      shape = sewing.SewedShape();
    }
    STEPControl_Writer w;
    if (w.Transfer(shape, STEPControl_AsIs) != IFSelect_RetDone) st.SkipWithError("transfer");
    if (!bench::print_step17(w, path)) st.SkipWithError("print");
  }
  st.counters["faces"] = static_cast<double>(faces.size());
  st.counters["file_MB"] = static_cast<double>(fs::file_size(path)) / 1e6;
  fs::remove(path);
  st.SetLabel(st.range(0) ? "the same shell of C1 faces, sewn" : "one C0 face");
}
BENCHMARK(BM_Peer_OcctWriteCircleSweep2000)
    ->Arg(0)
    ->Arg(1)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
