// api/src/compare.cpp
#include <cmath>
#include <iomanip>
#include <qmotion/api/compare.hpp>
#include <qmotion/api/export.hpp>
#include <qmotion/api/interpolate.hpp>
#include <qmotion/api/qspline.hpp>
#include <qmotion/io/profiles.hpp>
#include <qmotion/kernel/error.hpp>
#include <qmotion/kernel/pose.hpp>
#include <sstream>

namespace qmotion {
using namespace io;  // NOLINT: the formats this call reads and writes
namespace {

void measure(const Motion& m, const CompareOptions& o, SchemeFigures& f) {
  const int n = std::max(o.samples, 10);
  const double h = (m.b() - m.a()) / n;
  const double dh = 1e-4 * h;  // the step of the central differences of omega
  double len = 0;
  Eigen::Vector3d last = m.place(m.a(), o.point);
  for (int i = 0; i <= n; ++i) {
    const double t = i == n ? m.b() : m.a() + h * i;
    const Eigen::Vector3d w = m.angular_velocity(t);
    f.max_angular_velocity = std::max(f.max_angular_velocity, w.norm());
    const double t0 = std::max(m.a(), t - dh), t1 = std::min(m.b(), t + dh);
    f.max_angular_acceleration =
        std::max(f.max_angular_acceleration,
                 ((m.angular_velocity(t1) - m.angular_velocity(t0)) / (t1 - t0)).norm());
    if (i > 0) {  // the polygon of 32 steps per sample: the length to about 1e-9
      for (int k = 1; k <= 32; ++k) {
        const Eigen::Vector3d y = m.place(t - h + h * k / 32, o.point);
        len += (y - last).norm();
        last = y;
      }
    }
  }
  f.trajectory_length = len;
}

/// The default profile: a segment from the origin along x, a tenth of the poses' extent.
sweep::Profile<double> default_profile(const std::vector<kernel::Pose<double>>& poses,
                                       const std::string& units) {
  Eigen::Vector3d lo = poses.front().position, hi = lo;
  for (const auto& p : poses) {
    lo = lo.cwiseMin(p.position);
    hi = hi.cwiseMax(p.position);
  }
  const double l = (hi - lo).norm() > 0 ? 0.1 * (hi - lo).norm() : 1.0;
  std::ostringstream os;
  os.precision(17);
  os << "segment:0,0,0:" << l << ",0,0";
  return read_profile(os.str(), units);
}

/// The sweep's size: the bounding-box diagonal of the profile's control points' trajectories.
double sweep_size(const Motion& m, const sweep::Profile<double>& profile) {
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(HUGE_VAL), hi = -lo;
  for (int i = 0; i <= 400; ++i)
    for (const auto& e : profile.edges)
      for (const auto& x : e.points) {
        const Eigen::Vector3d y = m.place(m.a() + (m.b() - m.a()) * i / 400, x);
        lo = lo.cwiseMin(y);
        hi = hi.cwiseMax(y);
      }
  return (hi - lo).norm();
}

}  // namespace

std::vector<SchemeFigures> compare_schemes(const PoseSet& poses, const CompareOptions& o) {
  if (!(o.rel_tol > 0) || !(o.rel_tol < 1))
    throw Error(Errc::invalid_input, "--tol: expected a relative tolerance in (0, 1)");
  const auto P = to_poses_double(poses);
  const sweep::Profile<double> profile =
      o.profile.empty() ? default_profile(P, poses.units) : read_profile(o.profile, poses.units);
  param_rule(poses, o.param);  // a bad rule is the caller's error, not a scheme's
  std::vector<SchemeFigures> out;
  for (const char* name : {"elliptic bspline", "c1"}) {
    SchemeFigures f;
    f.scheme = name;
    f.rational = true;
    try {
      InterpolateOptions io;
      io.param = o.param;
      io.form = f.scheme == "c1" ? "c1" : "bspline";
      const auto r = interpolate(poses, io);
      const kernel::Motion<double>& m = r.motion.rational();
      measure(r.motion, o, f);
      ExportResult er;
      sweep_nurbs(r.motion, profile, ExportOptions{}, &er);
      f.sweep_poles = er.poles;
      f.sweep_degree_u = er.degree_u;
      f.max_key_residual = m.provenance ? m.provenance->max_residual() : 0.0;
    } catch (const Error& e) {
      f.error = e.what();
    }
    out.push_back(std::move(f));
  }
  for (const char* name : {"kks", "quintic", "quartic"}) {
    SchemeFigures f;
    f.scheme = name;
    try {
      QSplineOptions qo;
      qo.scheme = name;
      qo.param = o.param;
      const Motion q = qspline(poses, qo).motion;
      const kernel::QuaternionSpline& s = q.spline();
      measure(q, o, f);
      ExportOptions eo;
      eo.tol = o.rel_tol * std::max(sweep_size(q, profile), 1e-300);
      eo.self_intersection_check = false;
      ExportResult er;
      sweep_nurbs(q, profile, eo, &er);
      f.sweep_poles = er.poles;
      f.sweep_degree_u = er.degree_u;
      f.sweep_deviation = er.approx_deviation.value_or(0.0);
      for (double r : qspline_key_residuals(s))
        f.max_key_residual = std::max(f.max_key_residual, r);
    } catch (const Error& e) {
      f.error = e.what();
    }
    out.push_back(std::move(f));
  }
  return out;
}

nlohmann::json to_json(const std::vector<SchemeFigures>& figures) {
  nlohmann::json out = nlohmann::json::array();
  for (const auto& f : figures) {
    nlohmann::json j{{"scheme", f.scheme}, {"rational", f.rational}};
    if (f.error) {
      j["error"] = *f.error;
    } else {
      j["max_angular_velocity"] = f.max_angular_velocity;
      j["max_angular_acceleration"] = f.max_angular_acceleration;
      j["trajectory_length"] = f.trajectory_length;
      j["sweep_poles"] = f.sweep_poles;
      j["sweep_degree_u"] = f.sweep_degree_u;
      j["sweep_exact"] = f.rational;
      j["sweep_deviation"] = f.sweep_deviation;
      j["max_key_residual"] = f.max_key_residual;
    }
    out.push_back(j);
  }
  return out;
}

namespace {
std::string sci(double x) {
  std::ostringstream os;
  os << std::scientific << std::setprecision(2) << x;
  return os.str();
}
}  // namespace

std::string to_table(const std::vector<SchemeFigures>& figures) {
  std::ostringstream os;
  os << std::left << std::setw(18) << "scheme" << std::right << std::setw(12) << "max |w|"
     << std::setw(12) << "max |w'|" << std::setw(14) << "length" << std::setw(8) << "poles"
     << std::setw(8) << "deg u" << std::setw(12) << "sweep dev" << std::setw(12) << "key res"
     << "\n";
  for (const auto& f : figures) {
    os << std::left << std::setw(18) << f.scheme << std::right;
    if (f.error) {
      os << "  refused: " << *f.error << "\n";
      continue;
    }
    os << std::setprecision(5) << std::setw(12) << f.max_angular_velocity << std::setw(12)
       << f.max_angular_acceleration << std::setprecision(8) << std::setw(14) << f.trajectory_length
       << std::setw(8) << f.sweep_poles << std::setw(8) << f.sweep_degree_u << std::setw(12)
       << (f.rational ? std::string("exact") : sci(f.sweep_deviation)) << std::setw(12)
       << sci(f.max_key_residual) << "\n";
  }
  return os.str();
}

}  // namespace qmotion
