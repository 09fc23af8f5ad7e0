// api/src/toolpath.cpp: `qmotion toolpath`: the certified sampler, what each format writes,
// the machine's axes, and the feeds (docs/cam.md).
#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <functional>
#include <qmotion/api/toolpath.hpp>
#include <qmotion/cam/controller.hpp>
#include <qmotion/io/atomic_file.hpp>
#include <qmotion/io/machine_file.hpp>
#include <qmotion/io/progress.hpp>
#include <qmotion/io/units.hpp>
#include <qmotion/kernel/error.hpp>

#include "toolpath_detail.hpp"

namespace qmotion {
using namespace io;               // NOLINT: the formats this call reads and writes
using namespace toolpath_detail;  // NOLINT: the writers' shared helpers
namespace {

using json = nlohmann::json;

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
  if (!o.rotary.empty() && o.rotary != "ac" && o.rotary != "bc")
    throw Error(Errc::invalid_input, "--rotary " + o.rotary + ": expected ac or bc");
  const int machines = !o.rotary.empty() + !o.machine_file.empty() + o.machine.has_value();
  if (machines > 1)
    throw Error(Errc::invalid_input, "--rotary and --machine both name a machine; give one");
  if (machines && f != CamFormat::gcode)
    throw Error(Errc::invalid_input, std::string(o.rotary.empty() ? "--machine" : "--rotary") +
                                         " is for G-code output (.nc, .ngc)");
  if (o.c_hold && !machines)
    throw Error(Errc::invalid_input, "--c-hold is for a 5-axis machine (--rotary or --machine)");
  if (o.nurbs && f != CamFormat::gcode)
    throw Error(Errc::invalid_input, "--nurbs is for G-code output (.nc, .ngc)");
  if (o.nurbs && machines)
    throw Error(Errc::invalid_input,
                "--nurbs writes 3-axis G06.2 blocks; it does not combine with --rotary or "
                "--machine");
  if (o.nurbs && o.max_step > 0)
    throw Error(Errc::invalid_input, "--max-step caps linear moves; it does not apply to --nurbs");
  if (o.arc_length && f != CamFormat::csv)
    throw Error(Errc::invalid_input, "--arc-length is for CSV output (.csv)");
  if (!o.feed_mode.empty() && o.feed_mode != "units-per-minute" && o.feed_mode != "inverse-time")
    throw Error(Errc::invalid_input,
                "--feed-mode " + o.feed_mode + ": expected units-per-minute or inverse-time");
  const bool inverse = o.feed_mode == "inverse-time";
  if (inverse && f != CamFormat::gcode)
    throw Error(Errc::invalid_input,
                "--feed-mode inverse-time writes G93 G-code (.nc, .ngc); APT and CSV carry no "
                "feed per block");
  if (inverse && o.nurbs)
    throw Error(Errc::invalid_input,
                "--feed-mode inverse-time is for G1 moves; --nurbs blocks take a feed per minute");
  if (!o.axis_limits.empty() && !inverse)
    throw Error(Errc::invalid_input,
                "--axis-limits needs --feed-mode inverse-time: one feed per minute cannot keep "
                "every axis within its limit");
  for (const auto& [word, v] : o.axis_limits)
    if (!(v > 0) || !std::isfinite(v))
      throw Error(Errc::invalid_input,
                  "--axis-limits " + std::string(1, word) + ": expected a positive velocity limit");
  if (!o.dialect.empty()) {
    if (f != CamFormat::gcode)
      throw Error(Errc::invalid_input, "--dialect is for G-code output (.nc, .ngc)");
    if (o.nurbs && cam::parse_dialect(o.dialect, "--dialect") != cam::Dialect::fanuc)
      throw Error(Errc::invalid_input, "--dialect " + o.dialect +
                                           ": --nurbs writes Fanuc's G06.2 blocks; use "
                                           "--dialect fanuc or none");
  }
  if (!(o.controller_tol >= 0) || !std::isfinite(o.controller_tol))
    throw Error(Errc::invalid_input, "--controller-tol: expected a length >= 0 (0: exact path)");
  if (o.controller_tol > 0) {
    if (f != CamFormat::gcode || o.nurbs)
      throw Error(Errc::invalid_input,
                  "--controller-tol is for G-code G1 programs (.nc, .ngc without --nurbs)");
    if (machines)
      throw Error(Errc::invalid_input,
                  "--controller-tol is for 3-axis programs: a controller's blending of rotary axes "
                  "bounds no distance at the tool tip, so machine programs run in exact path "
                  "mode");
    if (!(o.controller_tol < 0.5 * o.chord_tol))
      throw Error(Errc::invalid_input,
                  "--controller-tol: expected less than half of --chord-tol (the chords need "
                  "the rest)");
  }
}

/// The machine of the options in the output unit (its pivots converted), with the velocity
/// limits that apply: a machine file's, overridden word by word by axis_limits.
std::optional<cam::Machine> resolve_machine(const ToolpathOptions& o, const std::string& units,
                                            std::map<char, double>& limits) {
  std::optional<cam::Machine> m;
  std::map<char, double> file_limits;
  double file_factor = 1;  // the machine file's unit per minute -> the output unit per minute
  if (o.machine) {
    m = *o.machine;
    const std::string problem = cam::machine_problem(*m);
    if (!problem.empty()) throw Error(Errc::invalid_input, "machine " + m->name + ": " + problem);
  } else if (!o.machine_file.empty()) {
    MachineFile mf = read_machine_file(o.machine_file);
    m = mf.machine;
    file_limits = mf.velocity;
    file_factor = unit_factor(m->units, units);
  } else if (!o.rotary.empty()) {
    m = cam::builtin_machine(o.rotary);
  }
  if (m) {
    const double f = unit_factor(m->units, units);
    for (auto& ax : m->axes) ax.pivot *= f;
    for (std::size_t i = 0; i < 3; ++i) {
      m->travel[i].min *= f;
      m->travel[i].max *= f;
      m->acceleration[i] *= f;
    }
    m->units = units;
  }
  std::string words = "XYZ";
  if (m)
    for (const auto& ax : m->axes) words += ax.name;
  for (const auto& [w, v] : file_limits)
    limits[w] = w == 'X' || w == 'Y' || w == 'Z' ? v * file_factor : v;
  for (const auto& [w, v] : o.axis_limits) {
    if (words.find(w) == std::string::npos)
      throw Error(Errc::invalid_input, "--axis-limits " + std::string(1, w) +
                                           ": not an axis of this machine (" + words + ")");
    limits[w] = v;
  }
  return m;
}

/// Decimals each format prints: of points (and machine XYZ), of axes (and machine angles).
std::pair<int, int> decimals(CamFormat f) {
  return f == CamFormat::csv ? std::pair<int, int>(9, 12) : std::pair<int, int>(6, 9);
}

/// Per G1 block of an inverse-time program: the minutes it takes (the exact arc at the
/// feed, longer where an axis limit asks) into tp, and the F written: 1/minutes rounded down
/// (so no axis goes faster) to enough decimals that the feed it implies is within 1e-8
/// relative, with those decimals.
std::vector<std::pair<double, int>> inverse_time(Toolpath& tp, const std::vector<double>& arc) {
  std::vector<std::pair<double, int>> feeds;
  auto word_value = [&](std::size_t i, char w) {
    if (tp.machine) {
      if (w == 'X' || w == 'Y' || w == 'Z')
        return tp.machine_axes[i][static_cast<std::size_t>(w - 'X')];
      return tp.machine_axes[i][tp.machine->axes[0].name == w ? 3 : 4];
    }
    return tp.samples[i].written.point(w - 'X');
  };
  for (std::size_t i = 0; i + 1 < tp.samples.size(); ++i) {
    double minutes = (arc[i + 1] - arc[i]) / tp.feed;
    bool limited = false;
    for (const auto& [w, v] : tp.axis_limits) {
      const double need = std::abs(word_value(i + 1, w) - word_value(i, w)) / v;
      if (need > minutes) {
        minutes = need;
        limited = true;
      }
    }
    if (!(minutes > 1e-12))
      throw Error(Errc::invalid_input,
                  "--feed-mode inverse-time: the tool tip stands still between t = " +
                      std::to_string(tp.samples[i].t) + " and " +
                      std::to_string(tp.samples[i + 1].t) +
                      " while the axes move; give --axis-limits for them so the block has a time");
    tp.limited_blocks += limited;
    const double f = 1 / minutes;
    const int d = std::clamp(8 - static_cast<int>(std::floor(std::log10(f))), 4, 15);
    const double q = std::pow(10.0, d);
    feeds.emplace_back(std::floor(f * q) / q, d);
    tp.block_minutes.push_back(1 / feeds.back().first);
  }
  return feeds;
}

/// The output unit: --units, else the motion's; APT and G-code know only mm and inches, so
/// other units become mm there unless asked for (then refused). A tolerance is certified
/// down to ten units of the last printed decimal (--nurbs prints 6, as G-code does).
std::string output_unit(const ToolpathOptions& o, CamFormat f, const std::string& munits) {
  std::string units;
  if (!o.units.empty()) {
    units = canonical_unit(o.units, "--units");
    if (f != CamFormat::csv && units != "mm" && units != "in")
      throw Error(Errc::invalid_input, "--units " + o.units +
                                           ": APT and G-code declare millimetres or inches only "
                                           "(mm, in); CSV takes any unit");
  } else {
    units = f == CamFormat::csv ? munits : munits == "in" ? "in" : "mm";
  }
  const int point_digits = decimals(f).first;
  const double least = 10 * std::pow(10.0, -point_digits);
  if (o.chord_tol < least) {
    std::ostringstream m;
    m << "--chord-tol " << o.chord_tol << ": "
      << (o.nurbs               ? "--nurbs"
          : f == CamFormat::csv ? "CSV"
                                : "the file")
      << " writes " << point_digits << " decimals, so it certifies tolerances from " << least
      << " (in the output unit)";
    throw Error(Errc::invalid_input, m.str());
  }
  return units;
}

/// The arc length of the exact trajectory up to every sample (output unit), and the written
/// chords (and what the machine runs) measured against it into tp; the samples scaled from
/// the motion's unit to the output's (k).
std::vector<double> measure(Toolpath& tp, const cam::ToolTrajectories& src, double k) {
  std::vector<double> arc{0.0};
  std::vector<Eigen::Vector3d> exact(33);
  for (std::size_t i = 0; i + 1 < tp.samples.size(); ++i) {
    if (i % 256 == 0)
      report_progress("toolpath",
                      0.8 + 0.2 * static_cast<double>(i) / static_cast<double>(tp.samples.size()));
    const double t0 = tp.samples[i].t, t1 = tp.samples[i + 1].t;
    const cam::WrittenEnd &w0 = tp.samples[i].written, &w1 = tp.samples[i + 1].written;
    arc.push_back(arc.back() + arc_length(src, t0, t1) * k);
    for (int s = 0; s <= 32; ++s) {
      exact[static_cast<std::size_t>(s)] = src.exact_point(t0 + (t1 - t0) * s / 32);
      tp.max_chord_measured = std::max(tp.max_chord_measured,
                                       cam::detail::point_segment_distance(
                                           exact[static_cast<std::size_t>(s)], w0.point, w1.point));
    }
    if (tp.machine)
      for (int s = 1; s < 16; ++s) {
        cam::MachineAxes q;
        for (std::size_t j = 0; j < 5; ++j)
          q[j] = w0.machine[j] + (w1.machine[j] - w0.machine[j]) * s / 16;
        const Eigen::Vector3d x = cam::forward_kinematics(*tp.machine, q).first / k;
        double d = HUGE_VAL;
        for (std::size_t e = 0; e + 1 < exact.size(); ++e)
          d = std::min(d, cam::detail::point_segment_distance(x, exact[e], exact[e + 1]));
        tp.tip_measured = std::max(tp.tip_measured, d);
        tp.machine_measured = std::max(
            tp.machine_measured, (x - (w0.point + (w1.point - w0.point) * (s / 16.0))).norm());
      }
  }
  tp.path_length = arc.back();
  report_progress("toolpath", 1.0);
  tp.max_chord_measured *= k;
  tp.machine_measured *= k;
  tp.tip_measured *= k;
  for (auto& s : tp.samples) {
    s.point *= k;
    s.written.point *= k;
    if (tp.machine) tp.machine_axes.push_back(s.written.machine);
  }
  return arc;
}

/// The sampler from the first block's branch within travel nearer the machine's zero, and
/// from the other one when an axis leaves its travel on the way. With travel, tp.branch
/// says whether the first block took the solution nearer the machine's zero (of both,
/// travel aside) or the other one; k: the motion's unit to the output's.
cam::SampledToolpath sample_within_travel(const cam::ToolTrajectories& src,
                                          const cam::SamplerOptions& so, int& first_branch,
                                          double k, Toolpath& tp) {
  bool limited = false;
  if (tp.machine)
    for (const auto& tr : tp.machine->travel) limited = limited || tr.limited();
  auto label = [&](const cam::SampledToolpath& out) {
    if (!limited) return;
    cam::Machine free = *tp.machine;
    free.travel = {};
    const cam::ToolpathSample& s0 = out.samples.front();
    const cam::MachineAxes q =
        cam::inverse_kinematics(free, s0.point * k, s0.axis, {}, true, "", 0);
    auto same = [](double u, double v) { return std::abs(std::remainder(u - v, 360.0)) < 1e-6; };
    tp.branch =
        same(q[3], s0.written.machine[3]) && same(q[4], s0.written.machine[4]) ? "nearer" : "other";
  };
  first_branch = 0;
  try {
    cam::SampledToolpath out = cam::sample_toolpath(src.h, src.d, so);
    label(out);
    return out;
  } catch (const cam::TravelError& e) {
    if (e.at_start()) throw;  // the first block has no branch within travel
    first_branch = 1;
    try {
      cam::SampledToolpath out = cam::sample_toolpath(src.h, src.d, so);
      label(out);
      return out;
    } catch (const cam::TravelError& other) {
      throw Error(Errc::invalid_input,
                  std::string(e.what()) + "; starting on the other branch: " + other.what());
    }
  }
}

/// The G1 program's time with the machine's accelerations (cam::block_minutes): every
/// block at its velocity-only time (the feed along the exact arc, or its inverse-time F)
/// and its axes' displacements.
void machining_time_with_acceleration(Toolpath& tp, const std::vector<double>& arc) {
  std::array<double, 5> accel{HUGE_VAL, HUGE_VAL, HUGE_VAL, HUGE_VAL, HUGE_VAL};
  if (tp.machine) accel = tp.machine->acceleration;
  tp.machining_time_accel_min = 0;
  for (std::size_t i = 0; i + 1 < tp.samples.size(); ++i) {
    const double minutes =
        tp.block_minutes.empty() ? (arc[i + 1] - arc[i]) / tp.feed : tp.block_minutes[i];
    std::array<double, 5> delta{};
    for (std::size_t j = 0; j < 5; ++j)
      delta[j] = tp.machine ? tp.machine_axes[i + 1][j] - tp.machine_axes[i][j]
                 : j < 3    ? tp.samples[i + 1].written.point(static_cast<int>(j)) -
                               tp.samples[i].written.point(static_cast<int>(j))
                         : 0.0;
    tp.machining_time_accel_min += cam::block_minutes(minutes, delta, accel);
  }
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
                {"feed_mode", feed_mode},
                {"machining_time_min", machining_time_min},
                {"chord_tolerance", chord_tol},
                {"max_deviation_bound", nurbs->max_deviation_bound},
                {"max_deviation_measured", nurbs->max_deviation_measured},
                {"dialect", dialect},
                {"path_mode", path_mode}};
  }
  json j{{"path", path},
         {"points", samples.size()},
         {"segments", samples.empty() ? 0 : samples.size() - 1},
         {"units", units},
         {"path_length", path_length},
         {"feed", feed},
         {"feed_mode", feed_mode},
         {"machining_time_min", machining_time_min},
         {"chord_tolerance", chord_tol},
         {"max_chord_deviation_bound", max_chord_bound},
         {"max_chord_deviation_measured", max_chord_measured},
         {"rounding_bound", rounding_bound},
         {"angle_tolerance_deg", angle_tol_deg},
         {"max_angle_deviation_bound_deg", max_angle_bound_deg}};
  if (!path_mode.empty()) {
    j["dialect"] = dialect;
    j["path_mode"] = path_mode;
    j["controller_tolerance"] = controller_tol;
    j["max_path_deviation_bound"] = max_chord_bound + controller_tol;
    j["machining_time_with_acceleration_min"] = machining_time_accel_min;
  }
  if (fit_bound > 0 || fit_measured > 0) {
    j["fit_deviation_bound"] = fit_bound;
    j["fit_deviation_measured"] = fit_measured;
  }
  if (machine) {
    json axes = json::array();
    for (const auto& ax : machine->axes)
      axes.push_back({{"name", std::string(1, ax.name)},
                      {"on", ax.head ? "head" : "table"},
                      {"direction", {ax.direction(0), ax.direction(1), ax.direction(2)}},
                      {"pivot", {ax.pivot(0), ax.pivot(1), ax.pivot(2)}}});
    j["machine"] = {{"name", machine->name}, {"axes", axes}};
    json travel = json::object(), accel = json::object();
    for (std::size_t i = 0; i < 5; ++i) {
      const std::string w(1, machine->word(i));
      if (machine->travel[i].limited())
        travel[w] = {machine->travel[i].min, machine->travel[i].max};
      if (std::isfinite(machine->acceleration[i])) accel[w] = machine->acceleration[i];
    }
    if (!travel.empty()) j["machine"]["travel"] = travel;
    if (!accel.empty()) j["machine"]["acceleration"] = accel;
    if (!branch.empty()) j["branch"] = branch;
    j["machine_interpolation_bound"] = machine_bound;
    j["machine_interpolation_angle_bound_deg"] = machine_angle_bound_deg;
    j["machine_interpolation_measured"] = machine_measured;
    j["max_tip_deviation_measured"] = tip_measured;
  }
  if (!axis_limits.empty()) {
    json l = json::object();
    for (const auto& [w, v] : axis_limits) l[std::string(1, w)] = v;
    j["axis_limits"] = l;
    j["limited_blocks"] = limited_blocks;
  }
  return j;
}

Toolpath toolpath(const Motion& motion, const ToolpathOptions& o) {
  const CamFormat f = cam_format(o.output);
  check_options(o, f);
  const std::string& munits = motion.units();
  Toolpath tp;
  tp.units = output_unit(o, f, munits);
  tp.machine = resolve_machine(o, tp.units, tp.axis_limits);
  if (!o.feed_mode.empty()) tp.feed_mode = o.feed_mode;
  if (tp.feed_mode != "inverse-time") tp.axis_limits.clear();  // a file's: the controller's
  const double k = unit_factor(munits, tp.units);              // motion unit -> output unit
  const double tol = o.chord_tol / k;                          // in the motion's unit
  const auto [point_digits, axis_digits] = decimals(f);
  const cam::ToolTrajectories src = cam::tool_trajectories(motion, o.point, o.axis, tol);
  tp.chord_tol = o.chord_tol;
  tp.angle_tol_deg = o.angle_tol_deg;
  tp.feed = o.feed;
  tp.path = o.output;
  const cam::Dialect dialect = o.dialect.empty()
                                   ? o.nurbs ? cam::Dialect::fanuc : cam::Dialect::linuxcnc
                                   : cam::parse_dialect(o.dialect, "--dialect");
  tp.dialect = cam::dialect_name(dialect);
  tp.controller_tol = o.controller_tol;
  cam::PathMode mode;
  if (f == CamFormat::gcode) mode = cam::path_mode(dialect, o.controller_tol, tp.units);
  tp.path_mode = mode.words;
  if (o.nurbs) {
    std::ostringstream os;
    nurbs_toolpath(tp, src, k, tol, mode, os);
    tp.machining_time_min = tp.path_length / tp.feed;
    write_file_atomic(o.output, os.str());
    return tp;
  }
  cam::SamplerOptions so;
  so.chord_tol = tol - src.fit_error - o.controller_tol / k;
  // The fitted axis: its tip 100 units out is within fit_error of the exact one.
  const double fit_angle = std::asin(std::min(1.0, 2 * src.fit_error / 100));
  so.angle_tol = o.angle_tol_deg * kPi / 180 - fit_angle;
  if (o.max_step > 0) so.max_step = o.max_step / k;
  so.progress = [](double x) { report_progress("toolpath", 0.8 * x); };
  const std::optional<cam::Machine>& machine = tp.machine;
  int first_branch = 0;  // of the branches within travel, the nearer to the machine's zero
  so.write = [&, pd = point_digits, ad = axis_digits](double t, const Eigen::Vector3d& p,
                                                      const Eigen::Vector3d& kd,
                                                      const cam::WrittenEnd* prev) {
    cam::WrittenEnd w;
    if (machine) {
      cam::MachineAxes q = cam::inverse_kinematics(
          *machine, p * k, kd, prev ? prev->machine : cam::MachineAxes{}, o.c_hold,
          (o.rotary.empty() ? "--machine " + machine->name : "--rotary " + o.rotary) +
              " at t = " + std::to_string(t),
          prev ? -1 : first_branch);
      for (std::size_t i = 0; i < 5; ++i)  // as printed, still within travel
        q[i] = std::clamp(rounded(q[i], i < 3 ? pd : ad), machine->travel[i].min,
                          machine->travel[i].max);
      const auto [pw, kw] = cam::forward_kinematics(*machine, q);
      w.point = pw / k;
      w.axis = kw;
      w.machine = q;
      return w;
    }
    for (int i = 0; i < 3; ++i) {
      w.point(i) = rounded(p(i) * k, pd) / k;
      w.axis(i) = f == CamFormat::gcode ? kd(i) : rounded(kd(i), ad);  // G1: no axis written
    }
    return w;
  };
  if (machine)
    so.between = [&](const cam::WrittenEnd& w0, const cam::WrittenEnd& w1) {
      const auto [e, ea] =
          cam::interpolation_bound(*machine, w0.machine, w1.machine, w0.axis, w1.axis);
      return std::pair<double, double>(e / k, ea);
    };
  const auto sampled = sample_within_travel(src, so, first_branch, k, tp);
  tp.samples = sampled.samples;
  tp.max_chord_bound = (sampled.max_chord_bound + src.fit_error) * k;
  tp.fit_bound = src.fit_error * k;
  tp.fit_measured = src.fit_measured * k;
  tp.max_angle_bound_deg = (sampled.max_angle_bound + fit_angle) * 180 / kPi;
  tp.rounding_bound = sampled.max_rounding * k;
  tp.machine_bound = sampled.max_between * k;
  tp.machine_angle_bound_deg = sampled.max_between_angle * 180 / kPi;
  const std::vector<double> arc = measure(tp, src, k);
  const bool inverse = tp.feed_mode == "inverse-time";
  std::vector<std::pair<double, int>> feeds;
  if (inverse) {
    feeds = inverse_time(tp, arc);
    for (double m : tp.block_minutes) tp.machining_time_min += m;
  } else {
    tp.machining_time_min = tp.path_length / tp.feed;
  }
  if (f == CamFormat::gcode) machining_time_with_acceleration(tp, arc);
  std::ostringstream os;
  const ToolpathHeader head = header(tp);
  if (f == CamFormat::gcode) {
    write_gcode(os, head, tp.samples, tp.machine_axes, feeds, axis_digits, dialect, mode);
  } else if (f == CamFormat::csv) {
    write_csv(os, tp.samples, o.arc_length ? arc : std::vector<double>{}, point_digits,
              axis_digits);
  } else {
    write_apt(os, head, tp.samples, axis_digits);
  }
  write_file_atomic(o.output, os.str());
  return tp;
}

}  // namespace qmotion
