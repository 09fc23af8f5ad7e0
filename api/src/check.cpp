// api/src/check.cpp: the exactness check (docs/guide/commands.md): a written file's NURBS, read
// back (STEP/IGES through OpenCASCADE), against the motion itself applied to the profile or
// the point.
#include <cmath>
#include <functional>
#include <qmotion/api/export.hpp>
#include <qmotion/io/atomic_file.hpp>
#include <qmotion/io/json_number.hpp>
#include <qmotion/io/nurbs_json.hpp>
#include <qmotion/io/occt.hpp>
#include <qmotion/io/units.hpp>
#include <qmotion/kernel/error.hpp>
#include <random>

#include "export_detail.hpp"

namespace qmotion {
using namespace io;  // NOLINT: the formats this call reads
using detail::diagonal;
using json = nlohmann::json;
namespace {

/// Our name of the unit a STEP/IGES reader reports ("" or an unknown name: `fallback`).
std::string cad_unit(const std::string& name, const std::string& fallback) {
  if (name == "mm" || name == "millimetre" || name == "millimeter") return "mm";
  if (name == "cm" || name == "centimetre" || name == "centimeter") return "cm";
  if (name == "m" || name == "metre" || name == "meter") return "m";
  if (name == "in" || name == "inch") return "in";
  if (name == "ft" || name == "foot") return "ft";
  if (name == "um" || name == "micrometre" || name == "micrometer" || name == "micron") return "um";
  return fallback;
}

/// A face to check: its parameter box, how OpenCASCADE or our reader evaluates it, and
/// whether its weights are positive.
struct CheckFace {
  double u0, u1, v0, v1;
  std::function<Eigen::Vector3d(double, double)> value;
  bool weights_positive = true;
  int degree_u = 0, degree_v = 0;
};

CheckFace check_face(sweep::NurbsSurface<double> s,
                     std::function<Eigen::Vector3d(double, double)> value) {
  CheckFace c{s.knots_u.front(), s.knots_u.back(), s.knots_v.front(), s.knots_v.back(),
              std::move(value)};
  for (const auto& row : s.weights)
    for (double w : row) c.weights_positive = c.weights_positive && w > 0;
  c.degree_u = s.degree_u;
  c.degree_v = s.degree_v;
  // The surface moves into its evaluator: a file near the size limit is held once.
  if (!c.value)
    c.value = [s = std::move(s)](double u, double v) { return sweep::evaluate(s, u, v); };
  return c;
}

/// A curve to check, as a face of one parameter.
CheckFace check_curve(const sweep::NurbsCurve<double>& c,
                      std::function<Eigen::Vector3d(double, double)> value) {
  CheckFace f{c.knots.front(), c.knots.back(), 0, 0, std::move(value)};
  for (double w : c.weights) f.weights_positive = f.weights_positive && w > 0;
  f.degree_u = c.degree;
  return f;
}

json check_motion(const std::string& file, const Motion& lm,
                  const std::optional<sweep::Profile<double>>& profile,
                  const std::optional<Eigen::Vector3d>& point, int grid) {
  const bool surface = profile.has_value();
  const std::string e = lower_extension(file);
  std::vector<CheckFace> faces;
  int planar_faces = 0;
  std::string file_units = lm.units();
  json out{{"file", file}, {"kind", surface ? "surface" : "curve"}};
  if (e == ".json") {
    NurbsFile doc = read_nurbs_file(file, surface);
    if (!doc.units.empty()) file_units = canonical_unit(doc.units, file + ": units");
    if (surface) {
      for (auto& s : doc.faces) faces.push_back(check_face(std::move(s), nullptr));
    } else {
      const auto& c = doc.curve;
      faces.push_back(check_curve(c, [c](double t, double) { return sweep::evaluate(c, t); }));
    }
    out["reader"] = "qmotion JSON";
  } else {
    // Read in the motion's unit (OpenCASCADE converts); deviations are reported in the
    // unit the file declares.
    const CadGeometry g = read_cad(file, surface, lm.units());
    if (surface) {
      for (const auto& cf : g.face_list) {
        if (cf.is_plane) {
          ++planar_faces;
          continue;
        }
        faces.push_back(check_face(cf.surface, cf.value));
      }
    } else {
      faces.push_back(check_curve(g.curve, g.value));
    }
    out["reader"] = "OpenCASCADE " + std::string(e == ".igs" || e == ".iges" ? "IGES" : "STEP");
    out["valid"] = g.valid;
    out["faces"] = g.faces;
    out["edges"] = g.edges;
    out["shells"] = g.shells;
    out["solids"] = g.solids;
    out["closed"] = g.closed;
    out["file_units"] = g.file_units;
    file_units = cad_unit(g.file_units, lm.units());
    if (g.solids > 0) out["volume"] = g.volume * std::pow(unit_factor(lm.units(), file_units), 3);
  }
  // The file's numbers are in file_units; the motion's in lm.units(). For STEP/IGES the
  // reader already converted into the motion's unit: scale only the reported deviation.
  const bool cad = e != ".json";
  const double k = unit_factor(lm.units(), file_units);
  const double a = lm.a(), b = lm.b();
  std::mt19937 rng(20261122);
  double dev = 0, u_lo = faces.front().u0, u_hi = faces.front().u1;
  bool weights_positive = true;
  std::vector<Eigen::Vector3d> ref;
  std::size_t samples = 0;
  const std::vector<sweep::NurbsCurve<double>> edges =
      surface ? profile->edges : std::vector<sweep::NurbsCurve<double>>{};
  std::vector<double> covered(edges.size(), 0.0);  // parameter area matched per edge
  for (const auto& face : faces) {
    weights_positive = weights_positive && face.weights_positive;
    u_lo = std::min(u_lo, face.u0);
    u_hi = std::max(u_hi, face.u1);
    std::vector<std::pair<double, double>> params;
    for (int i = 0; i <= grid; ++i)
      for (int j = 0; j <= (surface ? grid : 0); ++j)
        params.emplace_back(face.u0 + (face.u1 - face.u0) * i / grid,
                            face.v0 + (face.v1 - face.v0) * j / std::max(grid, 1));
    std::uniform_real_distribution<double> uu(face.u0, face.u1),
        vv(face.v0, surface ? face.v1 : face.v0 + 1);
    for (int s = 0; s < 400; ++s) params.emplace_back(uu(rng), surface ? vv(rng) : face.v0);
    samples += params.size();
    std::vector<Eigen::Vector3d> got;
    for (const auto& [u, v] : params) got.push_back(face.value(u, v) * (cad ? 1.0 : 1.0 / k));
    // The profile edge this face sweeps: the one it matches best.
    double best = std::numeric_limits<double>::infinity();
    std::size_t best_edge = 0;
    std::vector<Eigen::Vector3d> best_ref;
    for (std::size_t ed = 0; ed < (surface ? edges.size() : 1); ++ed) {
      if (surface && (face.v0 < edges[ed].knots.front() || face.v1 > edges[ed].knots.back()))
        continue;
      double worst = 0;
      std::vector<Eigen::Vector3d> r_ed;
      for (std::size_t s = 0; s < params.size(); ++s) {
        const double u = std::clamp(params[s].first, a, b);
        const Eigen::Vector3d exact =
            lm.place(u, surface ? sweep::evaluate(edges[ed], params[s].second) : *point);
        r_ed.push_back(exact);
        worst = std::max(worst, (got[s] - exact).norm());
        if (!(worst < best)) break;  // cannot beat the best edge
      }
      if (worst < best) {
        best = worst;
        best_edge = ed;
        best_ref = std::move(r_ed);
      }
    }
    if (best_ref.empty())
      throw Error(Errc::invalid_input, file + ": a face's v range [" + std::to_string(face.v0) +
                                           ", " + std::to_string(face.v1) +
                                           "] lies in no profile edge's parameter range");
    dev = std::max(dev, best);
    ref.insert(ref.end(), best_ref.begin(), best_ref.end());
    if (surface) covered[best_edge] += (face.u1 - face.u0) * (face.v1 - face.v0);
  }
  const double diag = diagonal(ref);
  out["samples"] = samples;
  out["max_deviation"] = dev * k;
  out["bbox_diagonal"] = diag * k;
  out["relative_deviation"] = diag > 0 ? dev / diag : dev;
  out["units"] = file_units;
  out["degree_u"] = faces.front().degree_u;
  if (surface) {
    out["degree_v"] = faces.front().degree_v;
    out["checked_faces"] = faces.size();
    out["planar_faces"] = planar_faces;
    bool cover = true;
    for (std::size_t ed = 0; ed < edges.size(); ++ed) {
      const double want = (b - a) * (edges[ed].knots.back() - edges[ed].knots.front());
      cover = cover && std::abs(covered[ed] - want) <= 1e-9 * want;
    }
    out["faces_cover_profile"] = cover;
  }
  out["weights_positive"] = weights_positive;
  out["param_range"] = {u_lo, u_hi};
  out["param_range_matches_motion"] =
      std::abs(u_lo - a) <= 1e-12 * (b - a) && std::abs(u_hi - b) <= 1e-12 * (b - a);
  return out;
}

}  // namespace

json check_geometry(const std::string& file, const Motion& m,
                    const std::optional<sweep::Profile<double>>& profile,
                    const std::optional<Eigen::Vector3d>& point, int grid) {
  json out = check_motion(file, m, profile, point, grid);
  out["motion"] = m.is_rational()
                      ? std::string("q-motion (rational, evaluated exactly in double)")
                      : std::string("quaternion-spline ") + kernel::to_string(m.spline().scheme) +
                            " (the motion itself: exp and log of its quaternions, not the fit)";
  return out;
}

}  // namespace qmotion
