// io/cli/geometry.cpp
#include "io/cli/geometry.hpp"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <random>
#include <sstream>

#include "io/atomic_file.hpp"
#include "io/json_number.hpp"
#include "io/nurbs_json.hpp"
#include "io/occt.hpp"
#include "kernel/error.hpp"
#include "sweep/approximate.hpp"
#include "sweep/surface.hpp"

namespace qmotion::cli {
namespace {

using json = nlohmann::json;

enum class Format { json, step, iges, stl };

std::string lower_ext(const std::string& path) {
  std::string e = std::filesystem::path(path).extension().string();
  for (auto& c : e) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return e;
}

Format output_format(const std::string& path, bool allow_stl) {
  const std::string e = lower_ext(path);
  if (e == ".json") return Format::json;
  if (e == ".step" || e == ".stp") return Format::step;
  if (e == ".igs" || e == ".iges") return Format::iges;
  if (allow_stl && e == ".stl") return Format::stl;
  throw Error(Errc::invalid_input, "-o " + path +
                                       ": expected a .json, .step, .stp, .igs or .iges file name" +
                                       std::string(allow_stl ? " (or .stl)" : ""));
}

std::string fmt(double x) {
  std::ostringstream os;
  os.precision(3);
  os << x;
  return os.str();
}

void refuse_poles(const LoadedMotion& lm) {
  const auto poles = kernel::find_poles(lm.motion);
  if (poles.empty()) return;
  std::ostringstream os;
  os.precision(12);
  for (double p : poles) os << " " << p;
  throw Error(Errc::numerical_failure,
              lm.file.source + ": the motion has a pole (zero rotational part) at t =" + os.str() +
                  ": its trajectories run to infinity there and cannot be exported");
}

/// Refuses degrees above what the target stores, unless an approximation was asked for.
void check_degree(int degree, const std::string& what, Format f, const GeometryOptions& opt) {
  const int limit = io::occt_max_degree();
  if ((f == Format::step || f == Format::iges) && degree > limit && opt.max_degree < 0)
    throw Error(Errc::numerical_failure,
                what + " has degree " + std::to_string(degree) + ", above the " +
                    std::to_string(limit) +
                    " that OpenCASCADE (and so STEP/IGES export) stores; many CAD systems accept "
                    "less (Rhino 11, AutoCAD 10). "
                    "Use a spline motion (interpolate --form bspline) to keep degrees low, or "
                    "--max-degree D for an approximation "
                    "within --tol");
}

double diagonal(const std::vector<Eigen::Vector3d>& pts) {
  Eigen::Vector3d lo = pts.front(), hi = pts.front();
  for (const auto& p : pts) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  return (hi - lo).norm();
}

std::vector<Eigen::Vector3d> curve_samples(const kernel::BSpline<Eigen::Vector4d>& h, int n) {
  std::vector<Eigen::Vector3d> s;
  for (int i = 0; i <= n; ++i) {
    const Eigen::Vector4d y = kernel::evaluate(h, h.a() + (h.b() - h.a()) * i / n);
    s.push_back(y.tail<3>() / y(0));
  }
  return s;
}

io::ExportInfo export_info(const LoadedMotion& lm, const GeometryOptions& opt,
                           const std::string& what) {
  io::ExportInfo info;
  info.units = opt.units.empty() ? lm.file.units : opt.units;
  info.product = "qmotion " + what;
  info.description =
      what + " of motion " + std::filesystem::path(lm.file.source).filename().string();
  return info;
}

double min_weight(const std::vector<double>& w) { return *std::min_element(w.begin(), w.end()); }

void write_stl(const std::string& path, const sweep::NurbsSurface<double>& s, int n) {
  const double u0 = s.knots_u.front(), u1 = s.knots_u.back(), v0 = s.knots_v.front(),
               v1 = s.knots_v.back();
  std::vector<std::vector<Eigen::Vector3d>> g(static_cast<std::size_t>(n + 1));
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= n; ++j)
      g[static_cast<std::size_t>(i)].push_back(
          sweep::evaluate(s, u0 + (u1 - u0) * i / n, v0 + (v1 - v0) * j / n));
  std::ostringstream os;
  os.precision(17);
  os << "solid qmotion\n";
  auto tri = [&](const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
    Eigen::Vector3d nrm = (b - a).cross(c - a);
    if (nrm.norm() > 0) nrm.normalize();
    os << " facet normal " << nrm.x() << " " << nrm.y() << " " << nrm.z() << "\n  outer loop\n";
    for (const auto* p : {&a, &b, &c})
      os << "   vertex " << p->x() << " " << p->y() << " " << p->z() << "\n";
    os << "  endloop\n endfacet\n";
  };
  for (std::size_t i = 0; i < static_cast<std::size_t>(n); ++i)
    for (std::size_t j = 0; j < static_cast<std::size_t>(n); ++j) {
      tri(g[i][j], g[i + 1][j], g[i + 1][j + 1]);
      tri(g[i][j], g[i + 1][j + 1], g[i][j + 1]);
    }
  os << "endsolid qmotion\n";
  io::write_file_atomic(path, os.str());
}

/// Writes a curve or surface in the chosen format (JSON records units and any approximation).
template <typename Geometry>
void write_geometry(Format f, const GeometryOptions& opt, const Geometry& g,
                    const io::ExportInfo& info, const ExportResult& r) {
  constexpr bool is_surface = std::is_same_v<Geometry, sweep::NurbsSurface<double>>;
  switch (f) {
    case Format::json: {
      json doc;
      if constexpr (is_surface) {
        doc = io::surface_to_json(g);
      } else {
        doc = io::curve_to_json(g);
      }
      doc["units"] = info.units;
      if (r.approx_deviation)
        doc["approximation"] = {{"max_degree", opt.max_degree},
                                {"max_deviation", *r.approx_deviation}};
      io::write_file_atomic(opt.output, doc.dump(1) + "\n");
      break;
    }
    case Format::step:
      io::write_step(opt.output, g, info);
      break;
    case Format::iges:
      io::write_iges(opt.output, g, info);
      break;
    case Format::stl:
      if constexpr (is_surface) write_stl(opt.output, g, 64);
      break;
  }
}

}  // namespace

Eigen::Vector3d parse_point(const std::string& text, const std::string& flag) {
  std::vector<double> v;
  std::stringstream ss(text);
  std::string cell;
  while (std::getline(ss, cell, ',')) v.push_back(io::parse_number_text(cell, flag).value);
  if (v.size() != 3)
    throw Error(Errc::invalid_input, flag + ": expected three numbers x,y,z, found '" + text + "'");
  return Eigen::Vector3d(v[0], v[1], v[2]);
}

LoadedMotion load_motion(const io::MotionFile& file) {
  LoadedMotion lm{file, io::to_motion_double(file), std::nullopt};
  lm.factors = io::factors_double(file, lm.motion);
  return lm;
}

LoadedMotion load_motion(const std::string& path) { return load_motion(io::read_motion(path)); }

ExportResult export_trajectory(const LoadedMotion& lm, const Eigen::Vector3d& point,
                               const GeometryOptions& opt) {
  const Format f = output_format(opt.output, false);
  refuse_poles(lm);
  const auto h0 = lm.factors
                      ? sweep::trajectory_from_factors(
                            *lm.factors, sweep::Vec4<double>(1, point(0), point(1), point(2)))
                      : sweep::trajectory_from_motion(
                            lm.motion, sweep::Vec4<double>(1, point(0), point(1), point(2)));
  ExportResult r;
  r.path = opt.output;
  auto h = h0;
  if (opt.max_degree > 0 && h.degree() > opt.max_degree) {
    const double tol =
        opt.tol > 0 ? opt.tol : 1e-6 * std::max(diagonal(curve_samples(h0, 200)), 1e-300);
    const auto approx = sweep::approximate_homogeneous({h0}, opt.max_degree, tol);
    h = approx.curves.front();
    r.approx_deviation = approx.max_deviation;
  } else {
    check_degree(h.degree(), "the trajectory", f, opt);
    const auto extra = sweep::knots_for_positive_weights(h);
    r.inserted_knots = static_cast<int>(extra.size());
    h = sweep::insert_knots(h, extra);
  }
  const sweep::NurbsCurve<double> c = sweep::to_nurbs(h);
  r.degree_u = c.degree;
  r.min_weight = min_weight(c.weights);
  const auto info = export_info(
      lm, opt, "trajectory of (" + fmt(point(0)) + "," + fmt(point(1)) + "," + fmt(point(2)) + ")");
  write_geometry(f, opt, c, info, r);
  return r;
}

ExportResult export_surface(const LoadedMotion& lm, const sweep::NurbsCurve<double>& profile,
                            const std::string& profile_name, const GeometryOptions& opt) {
  const Format f = output_format(opt.output, true);
  refuse_poles(lm);
  ExportResult r;
  r.path = opt.output;
  if (f == Format::step || f == Format::iges)
    check_degree(profile.degree, "the profile", f, GeometryOptions{});
  sweep::NurbsSurface<double> s;
  if (opt.max_degree > 0) {
    std::vector<sweep::Vec4<double>> X;
    for (std::size_t j = 0; j < profile.points.size(); ++j)
      X.emplace_back(profile.weights[j], profile.weights[j] * profile.points[j](0),
                     profile.weights[j] * profile.points[j](1),
                     profile.weights[j] * profile.points[j](2));
    const auto cols = sweep::trajectories(lm.motion, lm.factors, X);
    if (cols.front().degree() > opt.max_degree) {
      double diag = 0;
      for (const auto& c : cols) diag = std::max(diag, diagonal(curve_samples(c, 100)));
      const double tol = opt.tol > 0 ? opt.tol : 1e-6 * diag;
      const auto approx = sweep::approximate_homogeneous(cols, opt.max_degree, tol);
      sweep::HomogeneousSurface<double> hs{approx.curves.front().degree(),
                                           profile.degree,
                                           approx.curves.front().knots(),
                                           profile.knots,
                                           {}};
      hs.poles.assign(approx.curves.front().ctrl().size(),
                      std::vector<sweep::Vec4<double>>(cols.size()));
      for (std::size_t j = 0; j < cols.size(); ++j)
        for (std::size_t i = 0; i < hs.poles.size(); ++i)
          hs.poles[i][j] = approx.curves[j].ctrl()[i];
      s = sweep::to_nurbs(hs);
      // The surface's own deviation, measured.
      double dev = 0;
      for (int i = 0; i <= 40; ++i)
        for (int j = 0; j <= 40; ++j) {
          const double u = lm.motion.a() + (lm.motion.b() - lm.motion.a()) * i / 40.0;
          const double v =
              profile.knots.front() + (profile.knots.back() - profile.knots.front()) * j / 40.0;
          const auto exact =
              kernel::apply_point(kernel::evaluate(lm.motion, u), sweep::evaluate(profile, v));
          dev = std::max(dev, (sweep::evaluate(s, u, v) - exact).norm());
        }
      r.approx_deviation = dev;
    }
  }
  if (!r.approx_deviation) {
    const auto hs = sweep::kinematic_surface(lm.motion, lm.factors, profile);
    check_degree(hs.degree_u, "the surface (along the motion)", f, opt);
    s = sweep::to_nurbs(hs);
  }
  r.degree_u = s.degree_u;
  r.degree_v = s.degree_v;
  r.min_weight = 1.0;
  for (const auto& row : s.weights) r.min_weight = std::min(r.min_weight, min_weight(row));
  const auto info = export_info(lm, opt, "kinematic surface of " + profile_name);
  write_geometry(f, opt, s, info, r);
  return r;
}

json check_geometry(const std::string& file, const LoadedMotion& lm,
                    const std::optional<sweep::NurbsCurve<double>>& profile,
                    const std::optional<Eigen::Vector3d>& point, int grid) {
  const bool surface = profile.has_value();
  const std::string e = lower_ext(file);
  std::function<Eigen::Vector3d(double, double)> value;
  double u0 = 0, u1 = 0;
  bool weights_positive = true;
  int degree_u = 0, degree_v = 0;
  json out{{"file", file}, {"kind", surface ? "surface" : "curve"}};
  if (e == ".json") {
    const json doc = io::read_json_file(file);
    if (surface) {
      const auto s = io::surface_from_json(doc, file);
      value = [s](double u, double v) { return sweep::evaluate(s, u, v); };
      u0 = s.knots_u.front();
      u1 = s.knots_u.back();
      degree_u = s.degree_u;
      degree_v = s.degree_v;
      for (const auto& row : s.weights)
        for (double w : row) weights_positive = weights_positive && w > 0;
    } else {
      const auto c = io::curve_from_json(doc, file);
      value = [c](double t, double) { return sweep::evaluate(c, t); };
      u0 = c.knots.front();
      u1 = c.knots.back();
      degree_u = c.degree;
    }
    out["reader"] = "qmotion JSON";
  } else {
    const io::CadGeometry g = io::read_cad(file, surface, lm.file.units);
    value = g.value;
    if (surface) {
      u0 = g.surface.knots_u.front();
      u1 = g.surface.knots_u.back();
      degree_u = g.surface.degree_u;
      degree_v = g.surface.degree_v;
      for (const auto& row : g.surface.weights)
        for (double w : row) weights_positive = weights_positive && w > 0;
    } else {
      u0 = g.curve.knots.front();
      u1 = g.curve.knots.back();
      degree_u = g.curve.degree;
      for (double w : g.curve.weights) weights_positive = weights_positive && w > 0;
    }
    out["reader"] = "OpenCASCADE " + std::string(e == ".igs" || e == ".iges" ? "IGES" : "STEP");
    out["valid"] = g.valid;
    out["faces"] = g.faces;
    out["edges"] = g.edges;
    out["file_units"] = g.file_units;
  }
  const double a = lm.motion.a(), b = lm.motion.b();
  std::vector<std::pair<double, double>> params;
  const double v0 = surface ? profile->knots.front() : 0.0,
               v1 = surface ? profile->knots.back() : 0.0;
  for (int i = 0; i <= grid; ++i)
    for (int j = 0; j <= (surface ? grid : 0); ++j)
      params.emplace_back(a + (b - a) * i / grid, v0 + (v1 - v0) * j / std::max(grid, 1));
  std::mt19937 g(20261122);
  std::uniform_real_distribution<double> uu(a, b), vv(v0, surface ? v1 : v0 + 1);
  for (int k = 0; k < 400; ++k) params.emplace_back(uu(g), surface ? vv(g) : 0.0);
  double dev = 0;
  std::vector<Eigen::Vector3d> ref;
  for (const auto& [u, v] : params) {
    const auto q = kernel::evaluate(lm.motion, u);
    const Eigen::Vector3d exact =
        kernel::apply_point(q, surface ? sweep::evaluate(*profile, v) : *point);
    ref.push_back(exact);
    dev = std::max(dev, (value(u, v) - exact).norm());
  }
  const double diag = diagonal(ref);
  out["samples"] = params.size();
  out["max_deviation"] = dev;
  out["bbox_diagonal"] = diag;
  out["relative_deviation"] = diag > 0 ? dev / diag : dev;
  out["units"] = lm.file.units;
  out["degree_u"] = degree_u;
  if (surface) out["degree_v"] = degree_v;
  out["weights_positive"] = weights_positive;
  out["param_range"] = {u0, u1};
  out["param_range_matches_motion"] =
      std::abs(u0 - a) <= 1e-12 * (b - a) && std::abs(u1 - b) <= 1e-12 * (b - a);
  return out;
}

}  // namespace qmotion::cli
