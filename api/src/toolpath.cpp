// api/src/toolpath.cpp
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <qmotion/api/toolpath.hpp>
#include <qmotion/cam/cam_nurbs.hpp>
#include <qmotion/cam/tool_trajectories.hpp>
#include <qmotion/io/atomic_file.hpp>
#include <qmotion/io/progress.hpp>
#include <qmotion/io/units.hpp>
#include <qmotion/kernel/error.hpp>
#include <qmotion/sweep/fit.hpp>
#include <qmotion/sweep/solid.hpp>
#include <qmotion/sweep/surface.hpp>
#include <sstream>

namespace qmotion {
using namespace io;  // NOLINT: the formats this call reads and writes
namespace {

using json = nlohmann::json;
constexpr double kPi = 3.14159265358979323846;

enum class CamFormat { apt, csv, gcode };

CamFormat cam_format(const std::string& path) {
  const std::string e = lower_extension(path);
  if (e == ".apt" || e == ".cls") return CamFormat::apt;
  if (e == ".csv") return CamFormat::csv;
  if (e == ".nc" || e == ".ngc") return CamFormat::gcode;
  throw Error(Errc::invalid_input,
              "-o " + path + ": expected a .apt, .cls, .csv, .nc or .ngc file name");
}

void check_options(const ToolpathOptions& o, CamFormat f) {
  if (!o.axis.allFinite() || !(o.axis.norm() > 1e-12))
    throw Error(Errc::invalid_input, "--axis: expected a non-zero direction i,j,k");
  if (!o.point.allFinite()) throw Error(Errc::invalid_input, "--point: expected finite numbers");
  if (!(o.chord_tol > 0) || !(o.chord_tol <= 1e6))
    throw Error(Errc::invalid_input,
                "--chord-tol: expected a positive length up to 1e6 (a kilometre in mm)");
  if (!(o.angle_tol_deg > 0) || !(o.angle_tol_deg < 90))
    throw Error(Errc::invalid_input, "--angle-tol: expected degrees in (0, 90)");
  if (!(o.max_step >= 0) || !std::isfinite(o.max_step))
    throw Error(Errc::invalid_input, "--max-step: expected a length >= 0 (0: no cap)");
  if (!(o.feed > 0) || !std::isfinite(o.feed))
    throw Error(Errc::invalid_input, "--feed: expected a positive feed rate");
  if (!o.rotary.empty() && o.rotary != "ac")
    throw Error(Errc::invalid_input, "--rotary " + o.rotary + ": expected ac");
  if (!o.rotary.empty() && f != CamFormat::gcode)
    throw Error(Errc::invalid_input, "--rotary is for G-code output (.nc, .ngc)");
  if (o.c_hold && o.rotary.empty()) throw Error(Errc::invalid_input, "--c-hold is for --rotary ac");
  if (o.nurbs && f != CamFormat::gcode)
    throw Error(Errc::invalid_input, "--nurbs is for G-code output (.nc, .ngc)");
  if (o.nurbs && !o.rotary.empty())
    throw Error(Errc::invalid_input,
                "--nurbs writes 3-axis G06.2 blocks; it does not combine with --rotary");
  if (o.nurbs && o.max_step > 0)
    throw Error(Errc::invalid_input, "--max-step caps linear moves; it does not apply to --nurbs");
  if (o.arc_length && f != CamFormat::csv)
    throw Error(Errc::invalid_input, "--arc-length is for CSV output (.csv)");
}

/// The table-tilting A/C angles (degrees) that bring the tool axis k onto machine +Z:
/// Rx(A) Rz(C) k = (0, 0, 1), C = atan2(i, j), A = atan2(sqrt(i^2 + j^2), k), or the other
/// branch (-A, C + 180); the branch nearer the previous angles, C unwrapped.
std::pair<double, double> ac_angles(const Eigen::Vector3d& k, const std::pair<double, double>* prev,
                                    bool c_hold, double t) {
  const double rho = std::hypot(k(0), k(1));
  if (rho < 1e-12) {
    if (!c_hold)
      throw Error(Errc::invalid_input,
                  "--rotary ac: the tool axis is vertical at t = " + std::to_string(t) +
                      " (|k| = 1), where C is undefined; use --c-hold to keep the previous C");
    const double c = prev ? prev->second : 0.0;
    return {k(2) > 0 ? 0.0 : 180.0, c};
  }
  const double a = std::atan2(rho, k(2)) * 180 / kPi, c = std::atan2(k(0), k(1)) * 180 / kPi;
  if (!prev) return {a, c};
  std::pair<double, double> best{0, 0};
  double cost = HUGE_VAL;
  for (const auto& [aa, cc] :
       {std::pair<double, double>(a, c), std::pair<double, double>(-a, c + 180)}) {
    const double cu = cc + 360 * std::round((prev->second - cc) / 360);  // unwrapped
    const double dcost = std::abs(aa - prev->first) + std::abs(cu - prev->second);
    if (dcost < cost) {
      cost = dcost;
      best = {aa, cu};
    }
  }
  return best;
}

Eigen::Matrix3d ac_matrix(double a_deg, double c_deg) {
  const double a = a_deg * kPi / 180, c = c_deg * kPi / 180;
  Eigen::Matrix3d rx, rz;
  rx << 1, 0, 0, 0, std::cos(a), -std::sin(a), 0, std::sin(a), std::cos(a);
  rz << std::cos(c), -std::sin(c), 0, std::sin(c), std::cos(c), 0, 0, 0, 1;
  return rx * rz;
}

std::string num(double x, int digits = 6) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", digits,
                std::abs(x) < 0.5 * std::pow(10.0, -digits) ? 0.0 : x);
  return buf;
}

/// An APT statement folded at 72 columns with '$' continuations, breaking after commas.
void apt_line(std::ostringstream& os, const std::string& s) {
  std::string rest = s;
  while (rest.size() > 72) {
    std::size_t cut = rest.rfind(',', 70);
    if (cut == std::string::npos) cut = 70;
    os << rest.substr(0, cut + 1) << "$\n";
    rest = rest.substr(cut + 1);
  }
  os << rest << "\n";
}

/// The length of the exact trajectory over [t0, t1] (Gauss-Legendre on the velocity).
double arc_length(const cam::ToolTrajectories& src, double t0, double t1) {
  double len = 0;
  for (const auto& [node, w] : sweep::detail::gauss_legendre())
    len += w * (t1 - t0) / 2 * src.exact_velocity((t0 + t1) / 2 + (t1 - t0) / 2 * node).norm();
  return len;
}

/// The fewest decimals (at least `least`) that print every value so that it reads back
/// unchanged.
int exact_decimals(const std::vector<double>& v, int least) {
  for (int d = least; d < 17; ++d)
    if (std::all_of(v.begin(), v.end(),
                    [&](double x) { return std::strtod(num(x, d).c_str(), nullptr) == x; }))
      return d;
  return 17;
}

/// Decimals of the NURBS G-code's coordinates and weights.
constexpr double kNurbsQuantum = 1e6;

/// `--nurbs`: the trajectory as a NURBS of degree <= 3 (cam::cam_nurbs) within the
/// tolerance `tol` (the motion's unit) less the quaternion spline's fit, certified for the
/// numbers as written; measured against the exact motion at 64 points per span; Fanuc
/// G06.2 blocks into os.
void nurbs_toolpath(Toolpath& tp, const cam::ToolTrajectories& src, double k, double tol,
                    std::ostringstream& os) {
  cam::CamNurbsOptions no;
  no.tol = tol - src.fit_error;
  no.written = [k](const Eigen::Vector4d& v) {
    const double w = std::round(v(0) * kNurbsQuantum) / kNurbsQuantum;
    Eigen::Vector3d x = v.tail<3>() / v(0) * k;
    for (int i = 0; i < 3; ++i) x(i) = std::round(x(i) * kNurbsQuantum) / kNurbsQuantum;
    Eigen::Vector4d r;
    r << w, w * x / k;
    return r;
  };
  const cam::CamNurbs cn = cam::cam_nurbs(src.h, src.exact_point, src.breaks, src.continuity, no);
  NurbsToolpath nt;
  nt.curve = kernel::map_coeffs(cn.curve, [k](const Eigen::Vector4d& v) {
    Eigen::Vector4d r;
    r << v(0), v.tail<3>() * k;
    return r;
  });
  nt.t_knots = cn.t_knots;
  nt.exact = cn.exact;
  nt.spans = cn.spans;
  nt.max_deviation_bound = (cn.bound + src.fit_error) * k;
  for (const auto& v : nt.curve.ctrl())
    if (!(v(0) >= 1e-4 && v(0) <= 99.9999))
      throw Error(Errc::internal, "a NURBS weight outside 0.0001..99.9999: " + num(v(0)));
  // Dense confirmation and the path length, span by span (span j of the curve stands for
  // span j of t_knots).
  std::vector<double> xt = cn.t_knots;
  xt.erase(std::unique(xt.begin(), xt.end()), xt.end());
  const std::vector<double> xc = nt.curve.breakpoints();
  for (std::size_t j = 0; j + 1 < xt.size(); ++j) {
    const auto piece = kernel::bezier_piece(nt.curve, xc[j], xc[j + 1]);
    for (int s = 0; s <= 64; ++s) {
      const Eigen::Vector4d c = kernel::evaluate(piece, xc[j] + (xc[j + 1] - xc[j]) * s / 64);
      const Eigen::Vector3d e = src.exact_point(xt[j] + (xt[j + 1] - xt[j]) * s / 64) * k;
      nt.max_deviation_measured =
          std::max(nt.max_deviation_measured, (Eigen::Vector3d(c.tail<3>() / c(0)) - e).norm());
    }
    for (int s = 0; s < 4; ++s)
      tp.path_length += k * arc_length(src, xt[j] + (xt[j + 1] - xt[j]) * s / 4,
                                       xt[j] + (xt[j + 1] - xt[j]) * (s + 1) / 4);
  }
  // The blocks: the first control point is the current position (a rapid move there), the
  // first block carries G06.2, the order P, the first knot and the feed; every control point
  // its knot; the last `order` knots stand alone.
  const auto& c = nt.curve;
  const int order = c.degree() + 1, kd = exact_decimals(c.knots(), 9);
  const std::size_t n = c.ctrl().size();
  std::ostringstream head;
  head.precision(3);
  head << "(qmotion toolpath: NURBS of degree " << c.degree() << ", " << n << " control points, "
       << nt.spans << (nt.spans == 1 ? " span, " : " spans, ")
       << (nt.exact ? "the exact trajectory" : "a fit")
       << ", certified deviation <= " << nt.max_deviation_bound << " " << tp.units << ")\n";
  os << head.str() << (tp.units == "in" ? "G20" : "G21") << " G90 G17 G94\n";
  auto xyz = [](const Eigen::Vector4d& v) {
    return " X" + num(v(1) / v(0)) + " Y" + num(v(2) / v(0)) + " Z" + num(v(3) / v(0));
  };
  os << "G0" << xyz(c.ctrl().front()) << "\n";
  for (std::size_t i = 0; i < n; ++i)
    os << (i == 0 ? "G06.2 P" + std::to_string(order) + " " : "") << "K" << num(c.knots()[i], kd)
       << xyz(c.ctrl()[i]) << " R" << num(c.ctrl()[i](0)) << (i == 0 ? " F" + num(tp.feed, 4) : "")
       << "\n";
  for (std::size_t i = n; i < c.knots().size(); ++i) os << "K" << num(c.knots()[i], kd) << "\n";
  os << "M2\n";
  tp.nurbs = std::move(nt);
}

}  // namespace

json Toolpath::report() const {
  if (nurbs) {
    double lo = HUGE_VAL, hi = 0;
    for (const auto& v : nurbs->curve.ctrl()) {
      lo = std::min(lo, v(0));
      hi = std::max(hi, v(0));
    }
    return json{{"path", path},
                {"nurbs", true},
                {"degree", nurbs->curve.degree()},
                {"control_points", nurbs->curve.ctrl().size()},
                {"spans", nurbs->spans},
                {"exact", nurbs->exact},
                {"min_weight", lo},
                {"max_weight", hi},
                {"units", units},
                {"path_length", path_length},
                {"feed", feed},
                {"machining_time_min", path_length / feed},
                {"chord_tolerance", chord_tol},
                {"max_deviation_bound", nurbs->max_deviation_bound},
                {"max_deviation_measured", nurbs->max_deviation_measured}};
  }
  json j{{"path", path},
         {"points", samples.size()},
         {"segments", samples.empty() ? 0 : samples.size() - 1},
         {"units", units},
         {"path_length", path_length},
         {"feed", feed},
         {"machining_time_min", path_length / feed},
         {"chord_tolerance", chord_tol},
         {"max_chord_deviation_bound", max_chord_bound},
         {"max_chord_deviation_measured", max_chord_measured},
         {"angle_tolerance_deg", angle_tol_deg},
         {"max_angle_deviation_bound_deg", max_angle_bound_deg}};
  if (!a_deg.empty()) j["rotary"] = "ac";
  return j;
}

Toolpath toolpath(const Motion& motion, const ToolpathOptions& o) {
  const CamFormat f = cam_format(o.output);
  check_options(o, f);
  const std::string& munits = motion.units();
  Toolpath tp;
  // The output unit: --units, else the motion's; APT and G-code know only mm and inches,
  // so other units become mm there unless asked for (then refused).
  if (!o.units.empty()) {
    tp.units = canonical_unit(o.units, "--units");
    if (f != CamFormat::csv && tp.units != "mm" && tp.units != "in")
      throw Error(Errc::invalid_input, "--units " + o.units +
                                           ": APT and G-code declare millimetres or inches only "
                                           "(mm, in); CSV takes any unit");
  } else {
    tp.units = f == CamFormat::csv ? munits : munits == "in" ? "in" : "mm";
  }
  const double k = unit_factor(munits, tp.units);  // motion unit -> output unit
  const double tol = o.chord_tol / k;              // in the motion's unit
  const cam::ToolTrajectories src = cam::tool_trajectories(motion, o.point, o.axis, tol);
  tp.chord_tol = o.chord_tol;
  tp.angle_tol_deg = o.angle_tol_deg;
  tp.feed = o.feed;
  tp.path = o.output;
  if (o.nurbs && o.chord_tol < 10 / kNurbsQuantum) {
    std::ostringstream m;
    m << "--chord-tol " << o.chord_tol << ": --nurbs writes 6 decimals, so it certifies "
      << "tolerances from 1e-05 (in the output unit)";
    throw Error(Errc::invalid_input, m.str());
  }
  if (o.nurbs) {
    std::ostringstream os;
    nurbs_toolpath(tp, src, k, tol, os);
    write_file_atomic(o.output, os.str());
    return tp;
  }
  cam::SamplerOptions so;
  so.chord_tol = tol - src.fit_error;
  so.angle_tol = o.angle_tol_deg * kPi / 180;
  if (o.max_step > 0) so.max_step = o.max_step / k;
  so.progress = [](double f) { report_progress("toolpath", 0.8 * f); };
  const auto sampled = cam::sample_toolpath(src.h, src.d, so);
  tp.samples = sampled.samples;
  tp.max_chord_bound = (sampled.max_chord_bound + src.fit_error) * k;
  tp.max_angle_bound_deg = sampled.max_angle_bound * 180 / kPi;
  // The arc length of the exact trajectory up to every sample, and the chords measured
  // against it.
  std::vector<double> arc{0.0};
  for (std::size_t i = 0; i + 1 < tp.samples.size(); ++i) {
    if (i % 256 == 0)
      report_progress("toolpath",
                      0.8 + 0.2 * static_cast<double>(i) / static_cast<double>(tp.samples.size()));
    const double t0 = tp.samples[i].t, t1 = tp.samples[i + 1].t;
    arc.push_back(arc.back() + arc_length(src, t0, t1) * k);
    for (int s = 1; s < 32; ++s)
      tp.max_chord_measured = std::max(
          tp.max_chord_measured,
          cam::detail::point_segment_distance(src.exact_point(t0 + (t1 - t0) * s / 32),
                                              tp.samples[i].point, tp.samples[i + 1].point));
  }
  tp.path_length = arc.back();
  report_progress("toolpath", 1.0);
  tp.max_chord_measured *= k;
  for (auto& s : tp.samples) s.point *= k;
  if (!o.rotary.empty()) {
    std::pair<double, double> prev;
    for (std::size_t i = 0; i < tp.samples.size(); ++i) {
      prev = ac_angles(tp.samples[i].axis, i ? &prev : nullptr, o.c_hold, tp.samples[i].t);
      tp.a_deg.push_back(prev.first);
      tp.c_deg.push_back(prev.second);
    }
  }
  std::ostringstream os;
  bool multax = false;
  for (const auto& s : tp.samples)
    multax = multax || cam::detail::angle_between(s.axis, tp.samples.front().axis) > 1e-12;
  switch (f) {
    case CamFormat::csv: {
      os << "t,x,y,z,i,j,k" << (o.arc_length ? ",s" : "") << "\n";
      for (std::size_t i = 0; i < tp.samples.size(); ++i) {
        const auto& p = tp.samples[i];
        os << num(p.t, 12) << "," << num(p.point(0), 9) << "," << num(p.point(1), 9) << ","
           << num(p.point(2), 9) << "," << num(p.axis(0), 12) << "," << num(p.axis(1), 12) << ","
           << num(p.axis(2), 12);
        if (o.arc_length) os << "," << num(arc[i], 9);
        os << "\n";
      }
      break;
    }
    case CamFormat::apt: {
      apt_line(os, "PARTNO/QMOTION TOOLPATH");
      apt_line(os, tp.units == "in" ? "UNITS/INCHES" : "UNITS/MM");
      if (multax) apt_line(os, "MULTAX/ON");
      apt_line(os, "FEDRAT/" + num(o.feed, 4));
      for (const auto& s : tp.samples) {
        std::string g = "GOTO/" + num(s.point(0)) + "," + num(s.point(1)) + "," + num(s.point(2));
        if (multax)
          g += "," + num(s.axis(0), 9) + "," + num(s.axis(1), 9) + "," + num(s.axis(2), 9);
        apt_line(os, g);
      }
      apt_line(os, "FINI");
      break;
    }
    case CamFormat::gcode: {
      os << "(qmotion toolpath: " << tp.samples.size() << " points, chord tolerance "
         << num(o.chord_tol, 6) << " " << tp.units
         << (o.rotary.empty() ? ")\n" : ", table-tilting A/C, pivot at the workpiece origin)\n");
      os << (tp.units == "in" ? "G20" : "G21") << " G90 G17 G94\n";
      os << "F" << num(o.feed, 4) << "\n";
      for (std::size_t i = 0; i < tp.samples.size(); ++i) {
        Eigen::Vector3d p = tp.samples[i].point;
        std::string extra;
        if (!o.rotary.empty()) {
          p = ac_matrix(tp.a_deg[i], tp.c_deg[i]) * p;
          extra = " A" + num(tp.a_deg[i], 9) + " C" + num(tp.c_deg[i], 9);
        }
        os << (i == 0 ? "G0" : "G1") << " X" << num(p(0)) << " Y" << num(p(1)) << " Z" << num(p(2))
           << extra << "\n";
      }
      os << "M2\n";
      break;
    }
  }
  write_file_atomic(o.output, os.str());
  return tp;
}

}  // namespace qmotion
