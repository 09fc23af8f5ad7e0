// <qmotion/kernel/parametrization.hpp>
#pragma once
#include <cmath>
#include <optional>
#include <qmotion/kernel/error.hpp>
#include <qmotion/kernel/pose.hpp>
#include <string>
#include <vector>

namespace qmotion::kernel {

/// The parametrisation rules of (15), plus the poses' own parameters.
enum class ParamRule {
  given,
  uniform,
  chordal,
  star_chordal,
  centripetal,
  angular,
  angular_chordal
};

inline const char* to_string(ParamRule r) {
  switch (r) {
    case ParamRule::given:
      return "given";
    case ParamRule::uniform:
      return "uniform";
    case ParamRule::chordal:
      return "chordal";
    case ParamRule::star_chordal:
      return "star-chordal";
    case ParamRule::centripetal:
      return "centripetal";
    case ParamRule::angular:
      return "angular";
    case ParamRule::angular_chordal:
      return "angular-chordal";
  }
  return "?";
}

inline std::optional<ParamRule> param_rule_from_string(const std::string& s) {
  for (ParamRule r :
       {ParamRule::given, ParamRule::uniform, ParamRule::chordal, ParamRule::star_chordal,
        ParamRule::centripetal, ParamRule::angular, ParamRule::angular_chordal})
    if (s == to_string(r)) return r;
  if (s == "equidistant") return ParamRule::uniform;
  if (s == "*-chordal" || s == "star_chordal") return ParamRule::star_chordal;
  return std::nullopt;
}

/// Angle (radians, in [0, pi]) of the rotation taking orientation a to orientation b.
inline double rotation_angle(const Quaternion<double>& a, const Quaternion<double>& b) {
  const double c = std::abs(a.dot(b)) / std::sqrt(a.norm2() * b.norm2());
  return 2.0 * std::acos(std::min(1.0, c));
}

/// dist*(P, Q) of section 2: the length of the translation along the axis of the screw
/// motion taking P to Q, i.e. the projection of the vector between the origins onto the
/// axis of the relative rotation. Independent of the choice of the moving origin. For a
/// pure translation (no rotation) the screw axis is the translation direction, so dist* is
/// the plain distance.
inline double screw_distance(const Pose<double>& p, const Pose<double>& q) {
  const Eigen::Vector3d d = q.position - p.position;
  const Quaternion<double> rel = q.rotation * p.rotation.conj();  // fixed-frame relative rotation
  const Eigen::Vector3d axis = rel.vec();
  const double s = axis.norm(), c = std::abs(rel.w());
  if (s <= 1e-12 * std::max(c, 1e-300)) return d.norm();
  return std::abs(d.dot(axis / s));
}

/// Parameters t_0 < ... < t_m for the poses by rule (15). `given` returns the poses' own t
/// (all must have one); the others run from 0 to 1 with steps proportional to the rule's
/// measure. Throws Errc::invalid_input naming the poses when a step is zero.
inline std::vector<double> parametrize(const std::vector<Pose<double>>& poses, ParamRule rule) {
  const std::size_t m = poses.size() - 1;
  std::vector<double> t(poses.size(), 0.0);
  if (rule == ParamRule::given) {
    for (std::size_t i = 0; i <= m; ++i) {
      if (!poses[i].t)
        throw Error(Errc::invalid_input, "--param given: pose " + std::to_string(i) + " has no t");
      t[i] = *poses[i].t;
    }
    return t;
  }
  std::vector<double> step(m);
  for (std::size_t i = 0; i < m; ++i) {
    const Pose<double>&a = poses[i], &b = poses[i + 1];
    const double dist = (b.position - a.position).norm();
    switch (rule) {
      case ParamRule::uniform:
        step[i] = 1.0;
        break;
      case ParamRule::chordal:
        step[i] = dist;
        break;
      case ParamRule::star_chordal:
        step[i] = screw_distance(a, b);
        break;
      case ParamRule::centripetal:
        step[i] = std::sqrt(dist);
        break;
      case ParamRule::angular:
        step[i] = rotation_angle(a.rotation, b.rotation);
        break;
      case ParamRule::angular_chordal:
        step[i] = rotation_angle(a.rotation, b.rotation) + dist;
        break;
      case ParamRule::given:
        break;
    }
  }
  double total = 0;
  for (double s : step) total += s;
  for (std::size_t i = 0; i < m; ++i)
    if (!(step[i] > 1e-12 * total))
      throw Error(Errc::invalid_input,
                  std::string("--param ") + to_string(rule) + ": poses " + std::to_string(i) +
                      " and " + std::to_string(i + 1) + " give a zero parameter step" +
                      " (they coincide in what the rule measures); choose another --param");
  for (std::size_t i = 0; i < m; ++i) t[i + 1] = t[i] + step[i] / total;
  t[m] = 1.0;
  return t;
}

}  // namespace qmotion::kernel
