// tests/fit_streams.hpp: dense pose streams of known smooth motions with bounded noise, for the
// fit's tests and benchmark.
#pragma once
#include <Eigen/Geometry>
#include <cmath>
#include <qmotion/kernel/pose.hpp>
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

}  // namespace qmotion::test
