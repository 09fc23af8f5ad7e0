// tests/bench/occt_peers_case.hpp: a case of tests/bench/occt_peers.cpp, the motion and
// profile whose exact sweep every route builds, with the motion's rational frame and its
// first two derivatives (what route 2's location law evaluates).
#pragma once
#include <Eigen/Dense>
#include <cmath>
#include <memory>
#include <qmotion/kernel/bspline.hpp>
#include <qmotion/kernel/dual_quaternion.hpp>
#include <qmotion/kernel/motion.hpp>
#include <qmotion/sweep/profiles.hpp>
#include <qmotion/sweep/surface.hpp>
#include <qmotion/sweep/trajectory.hpp>
#include <string>
#include <vector>

namespace qmotion::bench {
using M4 = Eigen::Matrix4d;
using V3 = Eigen::Vector3d;

// ---- the exact sweep: motion, profile, frame and its derivatives ----------------------

/// The motion's rational frame x -> R(t) x + T(t) with its first two derivatives, from the
/// homogeneous matrix spline M(t) = [[w, 0], [a, U]] (sweep::matrix_from_factors):
/// H = M / w, H' = (M' - w' H) / w, H'' = (M'' - 2 w' H' - w'' H) / w.
struct Frames {
  kernel::BSpline<M4> M, dM, ddM;
  double a = 0, b = 1;

  explicit Frames(const kernel::Motion<double>& m)
      : M(sweep::matrix_from_factors(*m.factors)),
        dM(kernel::derivative(M)),
        ddM(kernel::derivative(dM)),
        a(m.a()),
        b(m.b()) {}

  void at(double t, M4& H, M4* dH = nullptr, M4* ddH = nullptr) const {
    const M4 m = kernel::evaluate(M, t);
    const double w = m(0, 0);
    H = m / w;
    if (!dH) return;
    const M4 m1 = kernel::evaluate(dM, t);
    *dH = (m1 - m1(0, 0) * H) / w;
    if (!ddH) return;
    const M4 m2 = kernel::evaluate(ddM, t);
    *ddH = (m2 - 2 * m1(0, 0) * *dH - m2(0, 0) * H) / w;
  }

  /// Interior breakpoints where the motion is less than C^k.
  std::vector<double> breaks(int k) const {
    std::vector<double> out;
    for (const double x : M.breakpoints())
      if (x != a && x != b && kernel::continuity_at(M, x) < k) out.push_back(x);
    return out;
  }
};

struct Case {
  std::string motion_name, profile_name;
  kernel::Motion<double> motion;
  sweep::NurbsCurve<double> profile;
  std::shared_ptr<const Frames> frames;
  sweep::NurbsSurface<double> exact;  // built once for measuring (u = t, v = profile)
  double diagonal = 0;

  Case(std::string mn, std::string pn, kernel::Motion<double> m, sweep::NurbsCurve<double> c)
      : motion_name(std::move(mn)),
        profile_name(std::move(pn)),
        motion(std::move(m)),
        profile(std::move(c)),
        frames(std::make_shared<Frames>(motion)),
        exact(sweep::kinematic_nurbs(motion, profile)) {
    V3 lo = V3::Constant(HUGE_VAL), hi = -lo;
    for (int i = 0; i <= 400; ++i)
      for (int j = 0; j <= 20; ++j) {
        const V3 p = point(motion.a() + (motion.b() - motion.a()) * i / 400.0, j / 20.0);
        lo = lo.cwiseMin(p);
        hi = hi.cwiseMax(p);
      }
    diagonal = (hi - lo).norm();
  }

  /// The motion-applied profile M(t) c(s), straight from the dual quaternion curve (not
  /// through any surface).
  V3 point(double t, double s) const {
    return kernel::apply_point(kernel::evaluate(motion, t), sweep::evaluate(profile, s));
  }
  int spans() const { return static_cast<int>(frames->M.breakpoints().size()) - 1; }
};

/// The profile moved by the motion at t (a rigid map of the poles; weights unchanged).
inline sweep::NurbsCurve<double> placed(const Case& c, double t) {
  M4 H;
  c.frames->at(t, H);
  sweep::NurbsCurve<double> out = c.profile;
  for (auto& p : out.points) p = H.block<3, 3>(1, 1) * p + H.block<3, 1>(1, 0);
  return out;
}

}  // namespace qmotion::bench
