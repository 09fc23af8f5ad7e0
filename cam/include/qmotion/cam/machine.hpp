// <qmotion/cam/machine.hpp>: 5-axis machines with two rotary axes on the table, on the head,
// or one on each; their forward and inverse kinematics, and a certified bound on how far the
// tool tip and the tool axis, seen from the workpiece, leave the chord when the controller
// moves every machine axis linearly from one block to the next (no tool-centre-point
// control). docs/cam.md states the conventions.
#pragma once
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <qmotion/kernel/error.hpp>
#include <string>
#include <utility>
#include <vector>

namespace qmotion::cam {

/// A rotary axis: a rotation of `angle` degrees (right-handed) about the line through
/// `pivot` along `direction`, both at zero angles in machine coordinates. A table axis's
/// pivot is in workpiece coordinates (they coincide with the machine's at zero angles); a
/// head axis's is measured from the tool tip with every axis at zero and XYZ at the origin.
struct RotaryAxis {
  char name = 'C';  ///< 'A', 'B' or 'C': the G-code word
  bool head = false;
  Eigen::Vector3d direction = Eigen::Vector3d::UnitZ();  ///< unit
  Eigen::Vector3d pivot = Eigen::Vector3d::Zero();
};

/// A machine with two rotary axes. The table axes carry the workpiece and the head axes the
/// tool; in `axes`, of each kind the outer one (nearer the machine's frame) comes first. At
/// zero angles the tool points along -Z from the spindle (its axis, tip to spindle, is +Z)
/// and the programmed XYZ is the tool tip. In general
///   tip (machine) = XYZ + H(angles)(0),  tip (workpiece) = T(angles)^-1 (tip (machine)),
///   axis (workpiece) = T_lin^T H_lin (0, 0, 1),
/// with T the table axes' composition (outer after inner) and H the head's.
/// The travel of one machine axis, [min, max] (length, or degrees for a rotary axis);
/// unlimited by default.
struct Travel {
  double min = -HUGE_VAL, max = HUGE_VAL;
  bool limited() const { return std::isfinite(min) || std::isfinite(max); }
  bool contains(double v) const { return v >= min && v <= max; }
};

/// The machine axes of one block: X, Y, Z (length) and the two rotary angles (degrees) in the
/// order of Machine::axes.
using MachineAxes = std::array<double, 5>;

struct Machine {
  std::string name;                  ///< for the report and the G-code header
  std::array<RotaryAxis, 2> axes{};  ///< see above
  std::string units = "mm";  ///< the unit of the pivots, the linear travel and accelerations
  /// Per axis in the order of MachineAxes (X, Y, Z, axes[0], axes[1]): the travel, and the
  /// acceleration limit (units or degrees per s^2; infinite: none).
  std::array<Travel, 5> travel{};
  std::array<double, 5> acceleration{HUGE_VAL, HUGE_VAL, HUGE_VAL, HUGE_VAL, HUGE_VAL};
  /// The G-code word of axis i of MachineAxes.
  char word(std::size_t i) const { return i < 3 ? static_cast<char>('X' + i) : axes[i - 3].name; }
};

/// Errc::invalid_input raised when an axis would leave its travel. `at_start`: at the first
/// block, where no choice of branch helps; otherwise on the way, where the caller may start
/// from the other branch.
class TravelError : public Error {
 public:
  TravelError(const std::string& message, bool at_start)
      : Error(Errc::invalid_input, message), at_start_(at_start) {}
  bool at_start() const { return at_start_; }

 private:
  bool at_start_;
};

namespace detail {

inline Eigen::Matrix3d rotation(const RotaryAxis& ax, double deg) {
  return Eigen::AngleAxisd(deg * 3.14159265358979323846 / 180, ax.direction).toRotationMatrix();
}

/// The signed angle (radians) about the unit u from x to w, both seen across u.
inline double angle_about(const Eigen::Vector3d& u, const Eigen::Vector3d& x,
                          const Eigen::Vector3d& w) {
  const Eigen::Vector3d xp = x - u.dot(x) * u, wp = w - u.dot(w) * u;
  return std::atan2(u.dot(xp.cross(wp)), xp.dot(wp));
}

inline double rad_to_deg(double r) { return r * 180 / 3.14159265358979323846; }

}  // namespace detail

/// How the rotary axes split between table and head: which angle turns which way in the
/// two-rotation problem R(a, alpha) x = R(b, beta) y that the inverse kinematics solves.
struct MachineLayout {
  int alpha_axis = 0, beta_axis = 1;  ///< indices into Machine::axes
  double alpha_sign = 1, beta_sign = 1;
};

/// The layout of the two-rotation problem for the machine (see inverse_kinematics).
/// - table, table: R(t0, q0) R(t1, q1) k = z, so R(t1, q1) k = R(t0, -q0) z;
/// - head, head:   k = R(h0, q0) R(h1, q1) z, so R(h0, -q0) k = R(h1, q1) z;
/// - table and head: R(t, qt) k = R(h, qh) z.
/// In each, beta turns the tool axis k about b and alpha turns z about a.
inline MachineLayout machine_layout(const Machine& m) {
  const bool h0 = m.axes[0].head, h1 = m.axes[1].head;
  if (!h0 && !h1) return {0, 1, -1, 1};
  if (h0 && h1) return {1, 0, 1, -1};
  const int t = h0 ? 1 : 0;
  return {1 - t, t, 1, 1};
}

/// Why the machine cannot work, or "" when it can: axes A, B or C, distinct, unit directions
/// not parallel to each other, and the axis that turns the tool direction not along it.
inline std::string machine_problem(const Machine& m) {
  for (const auto& ax : m.axes) {
    if (ax.name != 'A' && ax.name != 'B' && ax.name != 'C')
      return std::string("axis ") + ax.name + ": expected A, B or C";
    if (!ax.direction.allFinite() || std::abs(ax.direction.norm() - 1) > 1e-12)
      return std::string("axis ") + ax.name + ": the direction must be a unit vector";
    if (!ax.pivot.allFinite()) return std::string("axis ") + ax.name + ": the pivot must be finite";
  }
  if (m.axes[0].name == m.axes[1].name) return std::string("two axes are named ") + m.axes[0].name;
  if (m.axes[0].direction.cross(m.axes[1].direction).norm() < 1e-6)
    return "the two rotary axes are parallel, so they cannot orient the tool";
  const MachineLayout l = machine_layout(m);
  if (m.axes[l.alpha_axis].direction.cross(Eigen::Vector3d::UnitZ()).norm() < 1e-6)
    return std::string("axis ") + m.axes[l.alpha_axis].name +
           " lies along the tool at zero angles, so it cannot tilt the tool";
  return "";
}

/// The table's map T (workpiece to machine) or the head's H (tool frame to machine offsets)
/// at the angles: the composition of its axes' rotations about their pivots.
inline Eigen::Affine3d chain(const Machine& m, bool head, const MachineAxes& q) {
  Eigen::Affine3d out = Eigen::Affine3d::Identity();
  for (int i = 0; i < 2; ++i) {
    const RotaryAxis& ax = m.axes[static_cast<std::size_t>(i)];
    if (ax.head != head) continue;
    Eigen::Affine3d r = Eigen::Affine3d::Identity();
    r.linear() = detail::rotation(ax, q[static_cast<std::size_t>(3 + i)]);
    r.translation() = ax.pivot - r.linear() * ax.pivot;
    out = out * r;  // the outer axis comes first, so it acts last
  }
  return out;
}

/// Forward kinematics: the tool tip and the unit tool axis in workpiece coordinates.
inline std::pair<Eigen::Vector3d, Eigen::Vector3d> forward_kinematics(const Machine& m,
                                                                      const MachineAxes& q) {
  const Eigen::Affine3d t = chain(m, false, q), h = chain(m, true, q);
  const Eigen::Vector3d tip = Eigen::Vector3d(q[0], q[1], q[2]) + h.translation();
  const Eigen::Vector3d p = t.linear().transpose() * (tip - t.translation());
  const Eigen::Vector3d k = t.linear().transpose() * (h.linear() * Eigen::Vector3d::UnitZ());
  return {p, k};
}

namespace detail {

/// x with nine significant digits, as messages print it.
inline std::string number_text(double x) {
  char b[32];
  std::snprintf(b, sizeof b, "%.9g", x);
  return b;
}

inline std::string travel_text(const Travel& r) {
  return "[" + number_text(r.min) + ", " + number_text(r.max) + "]";
}

/// deg + 360 k within 180 degrees of `near`.
inline double unwrap(double deg, double near) { return deg + 360 * std::round((near - deg) / 360); }

/// The value deg + 360 k within `travel` nearest to `near`, or NaN when none is.
inline double within_travel(double deg, double near, const Travel& travel) {
  const double u = unwrap(deg, near);
  if (travel.contains(u)) return u;
  double best = std::nan(""), cost = HUGE_VAL;
  for (const double c :
       {u + 360 * std::ceil((travel.min - u) / 360), u - 360 * std::ceil((u - travel.max) / 360)})
    if (travel.contains(c) && std::abs(c - near) < cost) {
      best = c;
      cost = std::abs(c - near);
    }
  return best;
}

}  // namespace detail

/// Inverse kinematics: the machine axes that put the tool tip at p and the tool axis along
/// the unit k (workpiece coordinates).
/// - A following block (first_branch < 0) takes, of the two solutions, the one nearer `prev`
///   (the sum of the angle changes), each angle unwrapped to within 180 degrees of its
///   previous value. An axis that would then leave its travel throws TravelError naming it
///   and the limit (the machine would have to jump or unwind).
/// - The first block (first_branch 0 or 1) takes, of the solutions within travel (a limited
///   rotary axis may start at any turn that lies within it), the nearer to `prev` (the
///   machine's zero) or the other one; TravelError when there is none.
/// Where k lies along the axis that turns it (the singular axis: C of an A/C or B/C table),
/// that axis's angle is undefined: it keeps its previous value when `hold`, else
/// Errc::invalid_input (`what` names the option and t). Errc::invalid_input too when no
/// angles reach k (a head whose axes are not orthogonal).
inline MachineAxes inverse_kinematics(const Machine& m, const Eigen::Vector3d& p,
                                      const Eigen::Vector3d& k, const MachineAxes& prev, bool hold,
                                      const std::string& what, int first_branch = -1) {
  const MachineLayout l = machine_layout(m);
  const Eigen::Vector3d a = m.axes[static_cast<std::size_t>(l.alpha_axis)].direction;
  const Eigen::Vector3d b = m.axes[static_cast<std::size_t>(l.beta_axis)].direction;
  const Eigen::Vector3d x = Eigen::Vector3d::UnitZ(), y = k.normalized();
  // The common vector w = R(a, alpha) x = R(b, beta) y: a.w = a.x, b.w = b.y, |w| = 1.
  const double ab = a.dot(b), den = 1 - ab * ab, ax = a.dot(x), by = b.dot(y);
  const double pa = (ax - ab * by) / den, pb = (by - ab * ax) / den;
  const Eigen::Vector3d w0 = pa * a + pb * b, n = a.cross(b);
  double r2 = (1 - w0.squaredNorm()) / n.squaredNorm();
  if (r2 < -1e-9)
    throw Error(Errc::invalid_input, what + ": machine " + m.name +
                                         " cannot turn the tool onto the axis (" +
                                         std::to_string(k(0)) + ", " + std::to_string(k(1)) + ", " +
                                         std::to_string(k(2)) + ")");
  const double r = std::sqrt(std::max(r2, 0.0));
  const bool singular = (y - by * b).norm() < 1e-12;
  const char singular_name = m.axes[static_cast<std::size_t>(l.beta_axis)].name;
  if (singular && !hold) {
    const std::string name(1, singular_name);
    const bool vertical = std::abs(b(2)) > 1 - 1e-12;
    throw Error(Errc::invalid_input,
                what + ": the tool axis " + (vertical ? "is vertical, along" : "lies along") +
                    " the " + name + " axis, where " + name +
                    " is undefined; use --c-hold to keep the previous " + name);
  }
  // The angles of both branches, unwrapped near prev; XYZ only for what is returned or, at
  // the first block, checked against travel.
  std::array<MachineAxes, 2> cand{};
  for (std::size_t s = 0; s < 2; ++s) {
    const Eigen::Vector3d w = w0 + (s == 0 ? r : -r) * n;
    std::array<double, 2> ang{};
    ang[static_cast<std::size_t>(l.alpha_axis)] =
        l.alpha_sign * detail::rad_to_deg(detail::angle_about(a, x, w));
    ang[static_cast<std::size_t>(l.beta_axis)] =
        singular ? prev[static_cast<std::size_t>(3 + l.beta_axis)]
                 : l.beta_sign * detail::rad_to_deg(detail::angle_about(b, y, w));
    for (std::size_t i = 0; i < 2; ++i) cand[s][3 + i] = detail::unwrap(ang[i], prev[3 + i]);
  }
  auto cost = [&](const MachineAxes& q) {
    return std::abs(q[3] - prev[3]) + std::abs(q[4] - prev[4]);
  };
  if (cost(cand[1]) < cost(cand[0])) std::swap(cand[0], cand[1]);  // the nearer first
  auto place = [&](MachineAxes& q) {
    const Eigen::Affine3d t = chain(m, false, q), h = chain(m, true, q);
    const Eigen::Vector3d xyz = t * p - h.translation();
    for (int i = 0; i < 3; ++i) q[static_cast<std::size_t>(i)] = xyz(i);
  };
  if (first_branch < 0) {
    // The nearer branch; it must lie within travel (the other one is a jump away).
    MachineAxes& q = cand[0];
    place(q);
    for (std::size_t i = 0; i < 5; ++i)
      if (!m.travel[i].contains(q[i])) {
        const bool unwind = i >= 3 && !std::isnan(detail::within_travel(q[i], q[i], m.travel[i]));
        throw TravelError(what + ": " + std::string(1, m.word(i)) +
                              " reaches the end of its travel " + detail::travel_text(m.travel[i]) +
                              " and would have to go on" +
                              (unwind ? " (it would have to unwind)" : ""),
                          false);
      }
    return q;
  }
  // The first block: a limited rotary axis may start at any turn within its travel.
  std::vector<MachineAxes> ok;
  std::string refusal;
  for (MachineAxes& q : cand) {
    std::string outside;  // the first axis outside its travel, in words
    for (std::size_t i = 3; i < 5; ++i) {
      const Travel& tr = m.travel[i];
      const double v = tr.limited() ? detail::within_travel(q[i], prev[i], tr) : q[i];
      if (std::isnan(v) && outside.empty())
        outside = std::string(1, m.word(i)) + " = " + detail::number_text(q[i]) +
                  " (no turn of it lies within its travel " + detail::travel_text(tr) + ")";
      if (!std::isnan(v)) q[i] = v;
    }
    place(q);
    for (std::size_t i = 0; i < 5 && outside.empty(); ++i)
      if (!m.travel[i].contains(q[i]))
        outside = std::string(1, m.word(i)) + " = " + detail::number_text(q[i]) + " (travel " +
                  detail::travel_text(m.travel[i]) + ")";
    if (outside.empty()) {
      ok.push_back(q);
    } else {
      refusal += (refusal.empty() ? "" : "; ") + outside;
    }
  }
  if (static_cast<std::size_t>(first_branch) >= ok.size())
    throw TravelError(what + ": " +
                          (ok.empty() ? "neither branch of the inverse kinematics lies within "
                                        "travel: "
                                      : "the other branch of the inverse kinematics leaves its "
                                        "travel: ") +
                          refusal,
                      true);
  return ok[static_cast<std::size_t>(first_branch)];
}

/// Bounds on |f|, |f'|, |f''| and |f'''| of a vector function of s in [0, 1].
struct Jet {
  double m0 = 0, m1 = 0, m2 = 0, m3 = 0;
  /// The function turned by a rotation whose angle moves at the rate w (radians per unit s):
  /// (R f)^(n) = sum_k C(n, k) R^(k) f^(n-k) with |R^(k)| = w^k.
  Jet rotated(double w) const {
    return {m0, m1 + w * m0, m2 + 2 * w * m1 + w * w * m0,
            m3 + 3 * w * m2 + 3 * w * w * m1 + w * w * w * m0};
  }
  Jet shifted(const Eigen::Vector3d& c) const { return {m0 + c.norm(), m1, m2, m3}; }
};

/// A vector function's value and first two derivatives at one s.
struct Taylor2 {
  Eigen::Vector3d v = Eigen::Vector3d::Zero(), d1 = Eigen::Vector3d::Zero(),
                  d2 = Eigen::Vector3d::Zero();
  /// Turned by R(u, theta(s)) with theta(s) = theta and theta' = w: R commutes with u x, and
  /// (R f)' = R (w u x f + f'), (R f)'' = R (w^2 u x (u x f) + 2 w u x f' + f'').
  Taylor2 rotated(const Eigen::Vector3d& u, double theta, double w) const {
    const Eigen::Matrix3d r = Eigen::AngleAxisd(theta, u).toRotationMatrix();
    const Eigen::Vector3d uf = u.cross(v), ud = u.cross(d1);
    return {r * v, r * (w * uf + d1), r * (w * w * u.cross(uf) + 2 * w * ud + d2)};
  }
  Taylor2 shifted(const Eigen::Vector3d& c) const { return {v + c, d1, d2}; }
};

namespace detail {

/// Visits the machine's axes in the order the tip meets them on its way from the tool to
/// the workpiece: the head's axes inner first, then the table's outer first (turning back).
template <class F, class G>
void machine_chain(const Machine& m, F&& head_step, G&& table_step) {
  for (int i = 1; i >= 0; --i)
    if (m.axes[static_cast<std::size_t>(i)].head) head_step(i);
  for (int i = 0; i < 2; ++i)
    if (!m.axes[static_cast<std::size_t>(i)].head) table_step(i);
}

}  // namespace detail

/// Certified bounds on what the machine does between two blocks when it moves every axis
/// linearly from q0 to q1: how far the tool tip, in workpiece coordinates, leaves the chord
/// between its two ends (length), and how far the tool axis leaves the direction of the
/// linear blend of its two ends (radians). Each function g(s) minus its chord vanishes at
/// both ends, so |g - chord| <= max |g''| / 8, and max |g''| <= |g''(1/2)| + max |g'''| / 2:
/// g''(1/2) is computed exactly (Taylor2) and |g'''| bounded by composing the rotations'
/// rates (Jet). The axis's blend has length at least cos(phi/2) (phi between the ends), so
/// its direction is within asin(d / cos(phi/2)) of the axis when the deviation d is smaller.
/// k0 and k1 are the tool axes at q0 and q1 (forward_kinematics), when the caller has them.
inline std::pair<double, double> interpolation_bound(const Machine& m, const MachineAxes& q0,
                                                     const MachineAxes& q1,
                                                     const Eigen::Vector3d& k0,
                                                     const Eigen::Vector3d& k1) {
  constexpr double kRad = 3.14159265358979323846 / 180;
  std::array<double, 2> w{}, mid{};  // signed rates and mid-block angles, radians
  for (std::size_t i = 0; i < 2; ++i) {
    w[i] = (q1[3 + i] - q0[3 + i]) * kRad;
    mid[i] = 0.5 * (q0[3 + i] + q1[3 + i]) * kRad;
  }
  const Eigen::Vector3d x0(q0[0], q0[1], q0[2]), x1(q1[0], q1[1], q1[2]);
  Jet tip, axis{1, 0, 0, 0};
  Taylor2 tip2, axis2{Eigen::Vector3d::UnitZ(), Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()};
  // The head turns the tool: its offset H(angles)(0), about each pivot, and the axis.
  auto head = [&](int i) {
    const RotaryAxis& ax = m.axes[static_cast<std::size_t>(i)];
    const double wi = w[static_cast<std::size_t>(i)], th = mid[static_cast<std::size_t>(i)];
    tip = tip.shifted(ax.pivot).rotated(std::abs(wi)).shifted(ax.pivot);
    tip2 = tip2.shifted(-ax.pivot).rotated(ax.direction, th, wi).shifted(ax.pivot);
    axis = axis.rotated(std::abs(wi));
    axis2 = axis2.rotated(ax.direction, th, wi);
  };
  bool added = false;  // the programmed point, once the head is done
  auto add_xyz = [&] {
    if (added) return;
    added = true;
    tip.m0 += std::max(x0.norm(), x1.norm());
    tip.m1 += (x1 - x0).norm();
    tip2.v += 0.5 * (x0 + x1);
    tip2.d1 += x1 - x0;
  };
  // The table turns back to the workpiece: by -angle about each pivot.
  auto table = [&](int i) {
    add_xyz();
    const RotaryAxis& ax = m.axes[static_cast<std::size_t>(i)];
    const double wi = w[static_cast<std::size_t>(i)], th = mid[static_cast<std::size_t>(i)];
    tip = tip.shifted(ax.pivot).rotated(std::abs(wi)).shifted(ax.pivot);
    tip2 = tip2.shifted(-ax.pivot).rotated(ax.direction, -th, -wi).shifted(ax.pivot);
    axis = axis.rotated(std::abs(wi));
    axis2 = axis2.rotated(ax.direction, -th, -wi);
  };
  detail::machine_chain(m, head, table);
  add_xyz();
  const double e = (tip2.d2.norm() + tip.m3 / 2) / 8;
  const double d = (axis2.d2.norm() + axis.m3 / 2) / 8;
  const double blend = std::cos(0.5 * std::atan2(k0.cross(k1).norm(), k0.dot(k1)));
  const double angle = d < blend ? std::asin(std::min(1.0, d / blend)) : 3.14159265358979323846 / 2;
  return {e, angle};
}

inline std::pair<double, double> interpolation_bound(const Machine& m, const MachineAxes& q0,
                                                     const MachineAxes& q1) {
  return interpolation_bound(m, q0, q1, forward_kinematics(m, q0).second,
                             forward_kinematics(m, q1).second);
}

/// The built-in machines: "ac" (table A about X carrying C about Z) and "bc" (table B about Y
/// carrying C about Z), both with the pivot at the workpiece origin, so that
/// machine XYZ = Rx(A) Rz(C) p or Ry(B) Rz(C) p.
inline Machine builtin_machine(const std::string& name) {
  Machine m;
  if (name == "ac") {
    m.name = "table-tilting A/C";
    m.axes = {RotaryAxis{'A', false, Eigen::Vector3d::UnitX(), Eigen::Vector3d::Zero()},
              RotaryAxis{'C', false, Eigen::Vector3d::UnitZ(), Eigen::Vector3d::Zero()}};
  } else if (name == "bc") {
    m.name = "table-tilting B/C";
    m.axes = {RotaryAxis{'B', false, Eigen::Vector3d::UnitY(), Eigen::Vector3d::Zero()},
              RotaryAxis{'C', false, Eigen::Vector3d::UnitZ(), Eigen::Vector3d::Zero()}};
  } else {
    throw Error(Errc::invalid_input, "--rotary " + name + ": expected ac or bc");
  }
  return m;
}

}  // namespace qmotion::cam
