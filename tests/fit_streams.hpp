// tests/fit_streams.hpp: dense pose streams of known smooth motions with bounded or Gaussian
// noise, for the fit's tests and benchmark.
#pragma once
#include <Eigen/Geometry>
#include <cmath>
#include <functional>
#include <memory>
#include <qmotion/kernel/interpolation.hpp>
#include <qmotion/kernel/pose.hpp>
#include <qmotion/kernel/qspline.hpp>
#include <qmotion/kernel/spline_interpolation.hpp>
#include <random>
#include <vector>

namespace qmotion::test {

inline kernel::Quaternion<double> from_eigen(const Eigen::Quaterniond& q) {
  return kernel::Quaternion<double>(q.w(), q.x(), q.y(), q.z());
}

/// A smooth non-rational motion on u in [0, 1]: an ellipse with a wobble, turning about z
/// and rocking about a tilted axis.
inline kernel::Pose<double> smooth_pose(double u) {
  kernel::Pose<double> p;
  p.position = Eigen::Vector3d(100 * std::cos(2 * M_PI * u), 60 * std::sin(2 * M_PI * u),
                               30 * u + 10 * std::sin(6 * u));
  const Eigen::Quaterniond r =
      Eigen::Quaterniond(Eigen::AngleAxisd(2 * M_PI * 0.9 * u, Eigen::Vector3d::UnitZ())) *
      Eigen::Quaterniond(
          Eigen::AngleAxisd(0.8 * std::sin(3 * u), Eigen::Vector3d(1, 0.3, 0).normalized()));
  p.rotation = from_eigen(r);
  return p;
}

/// Moves a pose by a random offset shorter than `dist` and turns it by less than `deg`.
inline void perturb(kernel::Pose<double>& p, std::mt19937& rng, double dist, double deg) {
  std::normal_distribution<double> g(0.0, 1.0);
  std::uniform_real_distribution<double> f(0.0, 1.0);
  const Eigen::Vector3d a(g(rng), g(rng), g(rng)), b(g(rng), g(rng), g(rng));
  p.position += a.normalized() * dist * f(rng);
  const Eigen::Quaterniond turn(Eigen::AngleAxisd(deg * M_PI / 180 * f(rng), b.normalized()));
  p.rotation = p.rotation * from_eigen(turn);
}

/// Moves a pose by Gaussian noise: each coordinate by a normal deviate of standard deviation
/// `sigma`, and turns it by a rotation vector whose components have standard deviation
/// `sigma_deg` (degrees). Unbounded: a few poses of a long stream lie beyond 3 sigma.
inline void perturb_gaussian(kernel::Pose<double>& p, std::mt19937& rng, double sigma,
                             double sigma_deg) {
  std::normal_distribution<double> g(0.0, 1.0);
  const Eigen::Vector3d a(g(rng), g(rng), g(rng)), b(g(rng), g(rng), g(rng));
  p.position += sigma * a;
  const Eigen::Vector3d r = b * sigma_deg * M_PI / 180;
  if (r.norm() > 0)
    p.rotation =
        p.rotation * from_eigen(Eigen::Quaterniond(Eigen::AngleAxisd(r.norm(), r.normalized())));
}

struct Stream {
  std::vector<kernel::Pose<double>> poses;
  std::vector<double> t;
};

/// n samples of smooth_pose at evenly spaced u, each perturbed within dist and deg.
inline Stream noisy_stream(std::size_t n, double dist, double deg, unsigned seed) {
  std::mt19937 rng(seed);
  Stream s;
  for (std::size_t i = 0; i < n; ++i) {
    const double u = static_cast<double>(i) / static_cast<double>(n - 1);
    kernel::Pose<double> p = smooth_pose(u);
    perturb(p, rng, dist, deg);
    s.poses.push_back(p);
    s.t.push_back(u);
  }
  return s;
}

/// A frame (4x4 on homogeneous points) as a pose.
inline kernel::Pose<double> pose_of(const Eigen::Matrix4d& f) {
  kernel::Pose<double> p;
  p.position = f.block<3, 1>(1, 0);
  p.rotation = from_eigen(Eigen::Quaterniond(Eigen::Matrix3d(f.block<3, 3>(1, 1))));
  return p;
}

/// n samples of a source motion's frame on [0, 1], each perturbed within dist and deg, or
/// (gaussian) by Gaussian noise of standard deviations dist and deg (test::perturb_gaussian).
template <typename Frame>
Stream samples(const Frame& frame, std::size_t n, double dist, double deg, bool gaussian = false) {
  std::mt19937 rng(11);
  Stream s;
  for (std::size_t i = 0; i < n; ++i) {
    const double u = static_cast<double>(i) / static_cast<double>(n - 1);
    kernel::Pose<double> p = pose_of(frame(u));
    if (gaussian)
      perturb_gaussian(p, rng, dist, deg);
    else
      perturb(p, rng, dist, deg);
    s.poses.push_back(p);
    s.t.push_back(u);
  }
  return s;
}

/// The three sources: a Bezier Q-motion through five poses, a B-spline Q-motion through ten
/// at uneven parameters, and a KKS quaternion spline through ten.
inline std::vector<std::pair<const char*, std::function<Eigen::Matrix4d(double)>>> sources() {
  std::vector<kernel::Pose<double>> five, ten;
  std::vector<double> t5, t10, uneven;
  for (int i = 0; i < 5; ++i) five.push_back(smooth_pose(i / 8.0)), t5.push_back(i / 4.0);
  for (int i = 0; i < 10; ++i) {
    ten.push_back(smooth_pose(i / 9.0));
    t10.push_back(i / 9.0);
    uneven.push_back(std::pow(i / 9.0, 1.6));
  }
  auto bezier = std::make_shared<kernel::Motion<double>>(kernel::interpolate_bezier(five, t5, {}));
  auto bspline =
      std::make_shared<kernel::Motion<double>>(kernel::interpolate_bspline(ten, uneven, {}));
  std::vector<kernel::Quaternion<double>> keys;
  std::vector<Eigen::Vector3d> positions;
  for (const auto& p : ten) keys.push_back(p.rotation), positions.push_back(p.position);
  auto kks = std::make_shared<kernel::QuaternionSpline>(
      kernel::qspline(kernel::QSplineScheme::kks, keys, positions, t10));
  auto rational = [](const std::shared_ptr<kernel::Motion<double>>& m) {
    return [m](double u) {
      const Eigen::Matrix4d f = kernel::to_matrix4(kernel::evaluate(m->curve, u));
      Eigen::Matrix4d g = Eigen::Matrix4d::Zero();
      g(0, 0) = 1;
      g.block<3, 1>(1, 0) = f.block<3, 1>(1, 0) / f(0, 0);
      g.block<3, 3>(1, 1) = f.block<3, 3>(1, 1) / f(0, 0);
      return g;
    };
  };
  return {{"bezier", rational(bezier)},
          {"bspline uneven", rational(bspline)},
          {"kks", [kks](double u) { return kks->frame(u); }}};
}

}  // namespace qmotion::test
