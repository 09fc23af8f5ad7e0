// tests/bench/kks_convergence.cpp: the shape of Kim, Kim and Shin's Figures 1-3 (seed 000):
// iterations of the fixed-point map (13) until no control quaternion moves by 1e-4, against
// the key distance theta, the axis difference phi and the number of keys. Prints Markdown
// tables (README, "Kim-Kim-Shin convergence"). Keys: Q_0 = 1, Q_i = Q_{i-1} exp(theta a_i)
// with unit axes a_i in the x-y plane, each turned by phi from the one before.
#include <Eigen/Geometry>
#include <cmath>
#include <cstdio>
#include <qmotion/kernel/qspline.hpp>
#include <string>
#include <vector>

namespace {
using qmotion::kernel::Quaternion;

std::string iterations(int n, double theta, double phi) {
  std::vector<Quaternion<double>> q{Quaternion<double>(1, 0, 0, 0)};
  for (int i = 1; i < n; ++i) {
    const Eigen::Vector3d axis(std::cos(phi * (i - 1)), std::sin(phi * (i - 1)), 0);
    q.push_back(q.back() * qmotion::kernel::from_axis_angle(axis, 2 * theta));
  }
  qmotion::kernel::KksOptions o;
  o.refine = false;
  try {
    const auto s = qmotion::kernel::kks_spline(q, std::vector<Eigen::Vector3d>(n), 0, 1, o);
    return std::to_string(s.iterations);
  } catch (const qmotion::Error&) {
    return "no convergence";
  }
}

}  // namespace

int main() {
  const double half_pi = std::acos(0.0);
  std::printf("Iterations against the key distance theta (10 keys, phi = pi/2):\n\n");
  std::printf("| theta (rad) | iterations |\n| --- | --- |\n");
  for (const double theta :
       {0.1, 0.2, 0.4, 0.6, 0.8, 1.0, 1.1, 1.2, 1.3, 1.4, 1.45, 1.5, 1.52, 1.54, 1.55, 1.56, 1.565})
    std::printf("| %g | %s |\n", theta, iterations(10, theta, half_pi).c_str());
  std::printf("\nIterations against the axis difference phi (10 keys, theta = 1.2):\n\n");
  std::printf("| phi (rad) | iterations |\n| --- | --- |\n");
  for (int k = 0; k <= 8; ++k)
    std::printf("| %.3f | %s |\n", k * half_pi / 4, iterations(10, 1.2, k * half_pi / 4).c_str());
  std::printf("\nIterations against the number of keys (theta = 0.8, phi = pi/2):\n\n");
  std::printf("| keys | iterations |\n| --- | --- |\n");
  for (int n : {3, 5, 10, 20, 50, 100, 1000})
    std::printf("| %d | %s |\n", n, iterations(n, 0.8, half_pi).c_str());
  return 0;
}
