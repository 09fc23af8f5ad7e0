// The exact pipe of a sphere swept along a rational path (sweep/pipe.hpp), checked by an
// evaluation of its own: every face point at distance r from the path, the normal across the
// path, the faces meeting along shared edges, positive weights, the predicted degree, and
// the volume of the tube formula pi r^2 L + 4/3 pi r^3 (L by Simpson's rule).
#include <gtest/gtest.h>

#include <iostream>
#include <map>
#include <qmotion/kernel/error.hpp>
#include <qmotion/sweep/pipe.hpp>
#include <qmotion/sweep/pipe_approx.hpp>
#include <random>

namespace qmotion {
namespace pipe_tests {  // named: the unity build merges test files

using Path = kernel::BSpline<Eigen::Vector4d>;

/// A path along x with random wiggles: `poles` homogeneous poles of `degree`, weights in
/// [1 - wobble, 1 + wobble] (0: polynomial), uniform interior knots.
Path random_path(unsigned seed, int degree, int poles, double wobble) {
  std::mt19937 g(seed);
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<double> T(static_cast<std::size_t>(degree + 1), 0.0);
  for (int i = 1; i < poles - degree; ++i) T.push_back(i);
  T.insert(T.end(), static_cast<std::size_t>(degree + 1), double(poles - degree));
  std::vector<Eigen::Vector4d> P;
  for (int i = 0; i < poles; ++i) {
    const double w = 1 + wobble * u(g);
    const Eigen::Vector3d x(10.0 * i + 2 * u(g), 5 * u(g), 5 * u(g));
    P.emplace_back(w, w * x(0), w * x(1), w * x(2));
  }
  return Path::make(degree, T, P);
}

/// Point of a single-span NURBS face at local (a, b) in [0, 1]^2, by the Bernstein sums.
Eigen::Vector3d at(const sweep::NurbsSurface<double>& f, double a, double b) {
  auto B = [](int n, int i, double x) {
    double c = 1;
    for (int k = 1; k <= i; ++k) c = c * (n - i + k) / k;
    return c * std::pow(x, i) * std::pow(1 - x, n - i);
  };
  Eigen::Vector4d h = Eigen::Vector4d::Zero();
  for (int i = 0; i <= f.degree_u; ++i)
    for (int j = 0; j <= f.degree_v; ++j) {
      const auto ii = static_cast<std::size_t>(i), jj = static_cast<std::size_t>(j);
      const double w = f.weights[ii][jj] * B(f.degree_u, i, a) * B(f.degree_v, j, b);
      h += Eigen::Vector4d(w, w * f.points[ii][jj](0), w * f.points[ii][jj](1),
                           w * f.points[ii][jj](2));
    }
  return h.tail<3>() / h(0);
}

Eigen::Vector3d point(const Path& c, double t) {
  const Eigen::Vector4d y = kernel::evaluate(c, t);
  return y.tail<3>() / y(0);
}

/// Distance from x to the path near t (golden sections on [t - dt, t + dt] after a scan).
double distance_to_path(const Path& c, const Eigen::Vector3d& x, double t, double dt) {
  double lo = std::max(c.a(), t - dt), hi = std::min(c.b(), t + dt);
  double best = HUGE_VAL, bt = t;
  for (int k = 0; k <= 64; ++k) {
    const double s = lo + (hi - lo) * k / 64;
    const double d = (point(c, s) - x).norm();
    if (d < best) best = d, bt = s;
  }
  double a = std::max(lo, bt - (hi - lo) / 64), b = std::min(hi, bt + (hi - lo) / 64);
  const double g = (std::sqrt(5.0) - 1) / 2;
  for (int it = 0; it < 200 && b - a > 1e-15 * (1 + std::abs(a)); ++it) {
    const double m1 = b - g * (b - a), m2 = a + g * (b - a);
    if ((point(c, m1) - x).norm() < (point(c, m2) - x).norm())
      b = m2;
    else
      a = m1;
  }
  return std::min(best, (point(c, 0.5 * (a + b)) - x).norm());
}

double arc_length(const Path& c) {
  const auto dc = kernel::derivative(c);
  const int N = 40000;
  double L = 0;
  for (int i = 0; i <= N; ++i) {
    const double t = c.a() + (c.b() - c.a()) * i / N;
    const Eigen::Vector4d y = kernel::evaluate(c, t), dy = kernel::evaluate(dc, t);
    const double speed = ((dy.tail<3>() * y(0) - y.tail<3>() * dy(0)) / (y(0) * y(0))).norm();
    L += (i == 0 || i == N ? 1 : (i % 2 ? 4 : 2)) * speed;
  }
  return L * (c.b() - c.a()) / N / 3;
}

struct Case {
  unsigned seed;
  int degree, poles;
  double wobble;
  int expected_degree;  // m + 2 d_v + 6: polynomial m + 2 (m - 1) + 6, rational m + 2 (2m - 2) + 6
};

class Pipe : public ::testing::TestWithParam<Case> {};

TEST_P(Pipe, ExactClosedAndOfTheTubesVolume) {
  const Case k = GetParam();
  const Path c = random_path(k.seed, k.degree, k.poles, k.wobble);
  const double r = 1.5;
  const sweep::PipeShell pipe = sweep::pipe_shell(c, r, "path");
  EXPECT_EQ(pipe.degree_t, k.expected_degree);
  ASSERT_EQ(pipe.shell.faces.size(), pipe.pipe_faces + 8);
  EXPECT_TRUE(pipe.shell.closed);
  const auto dc = kernel::derivative(c);
  double worst_r = 0, worst_path = 0, worst_n = 0;
  for (std::size_t f = 0; f < pipe.shell.faces.size(); ++f) {
    const auto& face = pipe.shell.faces[f];
    for (const auto& row : face.weights)
      for (double w : row) ASSERT_GT(w, 0) << "face " << f;
    const bool cap = f >= pipe.pipe_faces, start = f < pipe.pipe_faces + 4;
    for (int i = 0; i <= 6; ++i)
      for (int j = 0; j <= 6; ++j) {
        const double a = i / 6.0, b = j / 6.0;
        const Eigen::Vector3d x = at(face, a, b);
        if (cap) {  // distance r from the end point, behind it
          const double t = start ? c.a() : c.b();
          const Eigen::Vector4d y = kernel::evaluate(c, t), dy = kernel::evaluate(dc, t);
          const Eigen::Vector3d tangent = dy.tail<3>() * y(0) - y.tail<3>() * dy(0);
          worst_r = std::max(worst_r, std::abs((x - point(c, t)).norm() - r) / r);
          EXPECT_LE((start ? 1 : -1) * (x - point(c, t)).dot(tangent.normalized()), 1e-12 * r);
          continue;
        }
        const double t = face.knots_u.front() + a * (face.knots_u.back() - face.knots_u.front());
        const Eigen::Vector4d y = kernel::evaluate(c, t), dy = kernel::evaluate(dc, t);
        const Eigen::Vector3d tangent = dy.tail<3>() * y(0) - y.tail<3>() * dy(0);
        worst_r = std::max(worst_r, std::abs((x - point(c, t)).norm() - r) / r);
        worst_n = std::max(worst_n, std::abs((x - point(c, t)).dot(tangent.normalized())) / r);
        worst_path = std::max(worst_path, std::abs(distance_to_path(c, x, t, 0.3) - r) / r);
      }
  }
  EXPECT_LE(worst_r, 1e-12);
  EXPECT_LE(worst_n, 1e-6);  // the factorisation's rounding; it enters the distance squared
  EXPECT_LE(worst_path, 1e-12);
  // Shared edges: every boundary edge (9 samples) that is not a cap's pole has a partner.
  std::vector<std::vector<Eigen::Vector3d>> edges;
  for (const auto& face : pipe.shell.faces)
    for (int side = 0; side < 4; ++side) {
      std::vector<Eigen::Vector3d> e;
      for (int k2 = 0; k2 <= 8; ++k2) {
        const double s = k2 / 8.0;
        e.push_back(side == 0   ? at(face, 0, s)
                    : side == 1 ? at(face, 1, s)
                    : side == 2 ? at(face, s, 0)
                                : at(face, s, 1));
      }
      if ((e.front() - e.back()).norm() + (e.front() - e[4]).norm() < 1e-9 * r) continue;
      edges.push_back(e);
    }
  for (std::size_t i = 0; i < edges.size(); ++i) {
    double best = HUGE_VAL;
    for (std::size_t j = 0; j < edges.size(); ++j) {
      if (i == j) continue;
      double fwd = 0, bwd = 0;
      for (std::size_t s = 0; s < 9; ++s) {
        fwd = std::max(fwd, (edges[i][s] - edges[j][s]).norm());
        bwd = std::max(bwd, (edges[i][s] - edges[j][8 - s]).norm());
      }
      best = std::min(best, std::min(fwd, bwd));
    }
    ASSERT_LE(best, 1e-9 * r) << "edge " << i << " has no partner";
  }
  const double tube = M_PI * r * r * arc_length(c) + 4.0 / 3 * M_PI * r * r * r;
  EXPECT_NEAR(pipe.volume, tube, 1e-9 * tube);
}

INSTANTIATE_TEST_SUITE_P(Paths, Pipe,
                         ::testing::Values(Case{1, 3, 8, 0.0, 13}, Case{7, 3, 8, 0.0, 13},
                                           Case{2, 3, 8, 0.3, 17}, Case{6, 4, 8, 0.3, 22},
                                           Case{5, 5, 8, 0.3, 27}, Case{3, 2, 6, 0.2, 12}),
                         [](const auto& info) {
                           const Case& k = info.param;
                           return std::string(k.wobble > 0 ? "rational" : "polynomial") +
                                  "_degree" + std::to_string(k.degree) + "_seed" +
                                  std::to_string(k.seed);
                         });

TEST(PipeRefusals, CornerRadiusAndCusp) {
  // Two straight spans meeting at a right angle: a corner.
  const Path corner = Path::make(
      1, {0, 0, 1, 2, 2},
      {Eigen::Vector4d(1, 0, 0, 0), Eigen::Vector4d(1, 10, 0, 0), Eigen::Vector4d(1, 10, 10, 0)});
  try {
    sweep::pipe_shell(corner, 1, "corner");
    FAIL() << "no refusal";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), Errc::invalid_input);
    EXPECT_NE(std::string(e.what()).find("corner at t = 1"), std::string::npos) << e.what();
  }
  const Path line =
      Path::make(1, {0, 0, 1, 1}, {Eigen::Vector4d(1, 0, 0, 0), Eigen::Vector4d(1, 10, 0, 0)});
  for (double r : {0.0, -1.0, std::nan("")})
    EXPECT_THROW(sweep::pipe_shell(line, r, "line"), Error);
  // A path that stops: the speed vanishes at its start (x = t^2).
  const Path stop = Path::make(
      2, {0, 0, 0, 1, 1, 1},
      {Eigen::Vector4d(1, 0, 0, 0), Eigen::Vector4d(1, 0, 0, 0), Eigen::Vector4d(1, 1, 0, 0)});
  try {
    sweep::pipe_shell(stop, 0.1, "stop");
    FAIL() << "no refusal";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), Errc::numerical_failure) << e.what();
  }
  // A straight line: one piece, a cylinder and two half spheres.
  const auto p = sweep::pipe_shell(line, 2, "line");
  EXPECT_EQ(p.pipe_faces, 4u);
  EXPECT_NEAR(p.volume, M_PI * 4 * 10 + 4.0 / 3 * M_PI * 8, 1e-10 * p.volume);
}

/// A pipe of degree 27 (a rational path of degree 5) brought to degree 9 (pipe_approx.hpp):
/// every sampled point of every fitted face, by the test's own Bernstein sums, lies within
/// the proven bound of distance r from the path; the end circles are kept, so the volume
/// stays the exact shell's.
TEST(PipeToDegree, WithinItsProvenBound) {
  for (unsigned seed : {3u, 8u}) {
    const Path c = random_path(seed, 5, 7, 0.3);
    const double r = 1.5;
    const auto exact = sweep::pipe_shell(c, r, "path");
    ASSERT_GT(exact.degree_t, 20);
    const double target = 1e-6 * sweep::diagonal(exact.shell);
    const auto low = sweep::pipe_to_degree(exact, 9, target, "path");
    EXPECT_EQ(low.pipe.degree_t, 9);
    EXPECT_GT(low.bound, 0);
    EXPECT_LE(low.bound, target);
    EXPECT_EQ(low.pipe.shell.faces.size() - low.pipe.pipe_faces,
              exact.shell.faces.size() - exact.pipe_faces);
    double worst = 0;
    for (std::size_t k = 0; k < low.pipe.pipe_faces; ++k) {
      const auto& f = low.pipe.shell.faces[k];
      ASSERT_LE(f.degree_u, 9);
      for (int i = 0; i <= 6; ++i)
        for (int j = 0; j <= 4; ++j) {
          const double t = f.knots_u.front() + (f.knots_u.back() - f.knots_u.front()) * i / 6;
          const Eigen::Vector3d x = at(f, i / 6.0, j / 4.0);
          worst = std::max(worst, std::abs(distance_to_path(c, x, t, 0.5) - r));
        }
    }
    std::cout << "seed " << seed << ": degree " << exact.degree_t << " -> 9, "
              << low.pipe.pipe_faces << " faces (from " << exact.pipe_faces << "), proven "
              << low.bound << ", sampled " << worst << "\n";
    EXPECT_LE(worst, low.bound + 1e-10 * r);
    EXPECT_NEAR(low.pipe.volume, exact.volume, 1e-7 * exact.volume);
  }
}

}  // namespace pipe_tests
}  // namespace qmotion
