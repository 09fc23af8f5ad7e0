// Exact faces of swept spheres (qmotion::volume to STEP, IGES and JSON), checked through what
// OpenCASCADE reads back: one valid closed solid whose every sampled face point, as
// OpenCASCADE evaluates it, lies at distance r from the centre's trajectory (qmotion's
// motion evaluation, searched along t), and whose volume (OpenCASCADE's BRepGProp) lies in
// the certified bounds and equals the tube formula pi r^2 L + 4/3 pi r^3.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <qmotion/io/nurbs_json.hpp>
#include <qmotion/io/occt.hpp>
#include <qmotion/qmotion.hpp>

#include "io_test_util.hpp"

namespace qmotion {
namespace volume_exact_tests {  // named: the unity build merges test files

namespace fs = std::filesystem;

std::string file(const std::string& name) {
  return test::scratch_path("volume_exact", name).string();
}

Motion helix(std::size_t poses) {
  auto p = io::read_poses(test::test_data("poses/helix_40.json"));
  p.poses.resize(poses);
  return interpolate(p, {}).motion;
}

/// Distance from x to the trajectory of the moving point `centre` (a scan of 4000 times,
/// then golden sections around the best).
double distance_to_path(const Motion& m, const Eigen::Vector3d& centre, const Eigen::Vector3d& x) {
  const int N = 4000;
  double best = HUGE_VAL, bt = m.a();
  for (int k = 0; k <= N; ++k) {
    const double t = m.a() + (m.b() - m.a()) * k / N;
    const double d = (m.place(t, centre) - x).norm();
    if (d < best) best = d, bt = t;
  }
  const double step = (m.b() - m.a()) / N;
  double a = std::max(m.a(), bt - step), b = std::min(m.b(), bt + step);
  const double g = (std::sqrt(5.0) - 1) / 2;
  for (int it = 0; it < 200 && b - a > 1e-16; ++it) {
    const double m1 = b - g * (b - a), m2 = a + g * (b - a);
    if ((m.place(m1, centre) - x).norm() < (m.place(m2, centre) - x).norm())
      b = m2;
    else
      a = m1;
  }
  return std::min(best, (m.place(0.5 * (a + b), centre) - x).norm());
}

/// pi r^2 L + 4/3 pi r^3, with L by Simpson's rule on central differences of the placement.
double tube_volume(const Motion& m, const Eigen::Vector3d& centre, double r) {
  const int N = 20000;
  double L = 0;
  for (int i = 0; i <= N; ++i) {
    const double t = m.a() + (m.b() - m.a()) * i / N, h = 1e-6 * (m.b() - m.a());
    const double t0 = std::max(m.a(), t - h), t1 = std::min(m.b(), t + h);
    const double speed = (m.place(t1, centre) - m.place(t0, centre)).norm() / (t1 - t0);
    L += (i == 0 || i == N ? 1 : (i % 2 ? 4 : 2)) * speed;
  }
  L *= (m.b() - m.a()) / N / 3;
  return M_PI * r * r * L + 4.0 / 3 * M_PI * r * r * r;
}

TEST(ExactSweptVolume, SphereToStepAndIgesIsOneSolidOfTheTubesVolume) {
  const Motion m = helix(8);
  const double r = 3;
  const double tube = tube_volume(m, Eigen::Vector3d::Zero(), r);
  for (const char* name : {"pipe.step", "pipe.igs"}) {
    VolumeOptions o;
    o.output = file(name);
    o.body = "sphere:3";
    o.tol = 0.5;
    const VolumeReport rep = volume(m, o);
    ASSERT_TRUE(rep.exact) << name;
    EXPECT_EQ(rep.degree, 13) << name;  // polynomial cubic path: 3 + 2 * 2 + 6
    EXPECT_LE(rep.orthogonality, 1e-9) << name;
    EXPECT_NEAR(rep.exact_volume, tube, 1e-7 * tube) << name;
    ASSERT_TRUE(rep.has_bounds);
    EXPECT_LE(rep.volume.volume_lower, tube) << name;
    EXPECT_GE(rep.volume.volume_upper, tube) << name;
    const io::CadGeometry g = io::read_cad(o.output, true);
    EXPECT_EQ(g.solids, 1) << name;
    EXPECT_TRUE(g.valid) << name;
    EXPECT_TRUE(g.closed) << name;
    EXPECT_EQ(static_cast<std::size_t>(g.faces), rep.faces) << name;
    EXPECT_NEAR(g.volume, tube, 1e-6 * tube) << name;
    EXPECT_GE(g.volume, rep.volume.volume_lower) << name;
    EXPECT_LE(g.volume, rep.volume.volume_upper) << name;
    // OpenCASCADE's own evaluation of every face, 5 x 5 points each.
    double worst = 0;
    for (const auto& f : g.face_list) {
      ASSERT_FALSE(f.is_plane) << name;
      const auto& s = f.surface;
      for (int i = 0; i <= 4; ++i)
        for (int j = 0; j <= 4; ++j) {
          const double u = s.knots_u.front() + (s.knots_u.back() - s.knots_u.front()) * i / 4,
                       v = s.knots_v.front() + (s.knots_v.back() - s.knots_v.front()) * j / 4;
          worst = std::max(
              worst, std::abs(distance_to_path(m, Eigen::Vector3d::Zero(), f.value(u, v)) - r));
        }
    }
    EXPECT_LE(worst, 1e-10 * r) << name;
  }
}

TEST(ExactSweptVolume, JsonShellOfTheBallAndItsDegree) {
  // A ball cutter that tilts: the ball's centre (0, 0, D/2) runs on a rational path of
  // degree 9, and the pipe's degree is above the 25 OpenCASCADE stores: JSON holds it
  // exactly; STEP holds faces of degree 9 within a proven bound of it (below).
  const Motion m = helix(4);
  VolumeOptions o;
  o.body = "cutter:ball,6,20";
  o.output = file("ball.json");
  const VolumeReport rep = volume(m, o);
  EXPECT_TRUE(rep.exact);
  EXPECT_FALSE(rep.has_bounds);
  EXPECT_GT(rep.degree, 25);
  std::ifstream in(o.output);
  const nlohmann::json j = nlohmann::json::parse(in);
  EXPECT_EQ(j.at("type"), "nurbs_shell");
  EXPECT_TRUE(j.at("closed").get<bool>());
  ASSERT_EQ(j.at("faces").size(), rep.faces);
  const Eigen::Vector3d centre(0, 0, 3);
  double worst = 0;
  for (const auto& fj : j.at("faces")) {
    const auto s = io::surface_from_json(fj, "face");
    for (int i = 0; i <= 2; ++i)
      for (int k = 0; k <= 2; ++k) {
        const double u = s.knots_u.front() + (s.knots_u.back() - s.knots_u.front()) * i / 2,
                     v = s.knots_v.front() + (s.knots_v.back() - s.knots_v.front()) * k / 2;
        // Rational Bezier point by the Bernstein sums of the file's own poles and weights.
        auto B = [](int n, int a, double x) {
          double c = 1;
          for (int q = 1; q <= a; ++q) c = c * (n - a + q) / q;
          return c * std::pow(x, a) * std::pow(1 - x, n - a);
        };
        const double a = (u - s.knots_u.front()) / (s.knots_u.back() - s.knots_u.front()),
                     b = (v - s.knots_v.front()) / (s.knots_v.back() - s.knots_v.front());
        Eigen::Vector4d h = Eigen::Vector4d::Zero();
        for (int p = 0; p <= s.degree_u; ++p)
          for (int q = 0; q <= s.degree_v; ++q) {
            const auto pp = static_cast<std::size_t>(p), qq = static_cast<std::size_t>(q);
            const double w = s.weights[pp][qq] * B(s.degree_u, p, a) * B(s.degree_v, q, b);
            h += Eigen::Vector4d(w, w * s.points[pp][qq](0), w * s.points[pp][qq](1),
                                 w * s.points[pp][qq](2));
          }
        worst = std::max(worst, std::abs(distance_to_path(m, centre, h.tail<3>() / h(0)) - 3));
      }
  }
  EXPECT_LE(worst, 1e-9 * 3);
  const double tube = tube_volume(m, centre, 3);
  EXPECT_NEAR(rep.exact_volume, tube, 1e-7 * tube);
}

/// The tilting ball cutter's pipe to STEP: faces of degree 9 whose proven bound from the
/// exact pipe holds at every sampled point of OpenCASCADE's reading of the file (distance to
/// the centre's path, by the test's own search), one valid closed solid of the tube's volume.
TEST(ExactSweptVolume, TiltingBallToStepWithinItsProvenBound) {
  const Motion m = helix(4);
  VolumeOptions o;
  o.body = "cutter:ball,6,20";
  o.output = file("ball.step");
  const VolumeReport rep = volume(m, o);
  ASSERT_TRUE(rep.approximated);
  EXPECT_GT(rep.exact_degree, 25);
  EXPECT_LE(rep.degree, 9);
  const nlohmann::json j = rep.report();
  const double bound = j.at("approximation").at("bound").get<double>();
  EXPECT_EQ(j.at("distance_bound").get<double>(), bound);
  EXPECT_GT(bound, 0);
  EXPECT_LE(bound, 1e-3);  // 1e-6 of the pipe's diagonal
  const io::CadGeometry g = io::read_cad(o.output, true);
  EXPECT_EQ(g.solids, 1);
  EXPECT_TRUE(g.valid);
  EXPECT_TRUE(g.closed);
  EXPECT_EQ(static_cast<std::size_t>(g.faces), rep.faces);
  const Eigen::Vector3d centre(0, 0, 3);
  double worst = 0;
  for (const auto& f : g.face_list) {
    const auto& s = f.surface;
    for (int i = 0; i <= 6; ++i)
      for (int k = 0; k <= 4; ++k) {
        const double u = s.knots_u.front() + (s.knots_u.back() - s.knots_u.front()) * i / 6,
                     v = s.knots_v.front() + (s.knots_v.back() - s.knots_v.front()) * k / 4;
        worst = std::max(worst, std::abs(distance_to_path(m, centre, f.value(u, v)) - 3));
      }
  }
  std::cout << "degree " << rep.degree << " (exact " << rep.exact_degree << "), " << rep.faces
            << " faces, proven " << bound << ", sampled " << worst << "\n";
  EXPECT_LE(worst, bound + 1e-9);
  const double tube = tube_volume(m, centre, 3);
  EXPECT_NEAR(g.volume, tube, 1e-6 * tube);
  EXPECT_NEAR(rep.exact_volume, tube, 1e-6 * tube);
}

TEST(ExactSweptVolume, Refusals) {
  VolumeOptions o;
  o.output = file("box.step");
  o.body = "box:1,2,3";
  EXPECT_TRUE(test::throws_error([&] { volume(helix(3), o); }, Errc::invalid_input,
                                 {"box.step", "sphere:r and cutter:ball"}));
  EXPECT_FALSE(fs::exists(o.output));
  // A quaternion spline: no exact faces for STEP; its JSON is the mesh.
  auto poses = io::read_poses(test::test_data("helix_10.json"));
  poses.poses.resize(3);
  QSplineOptions q;
  q.scheme = "kks";
  const Motion kks = qspline(poses, q).motion;
  o.body = "sphere:2";
  o.output = file("kks.igs");
  EXPECT_TRUE(test::throws_error([&] { volume(kks, o); }, Errc::invalid_input,
                                 {"kks.igs", "quaternion spline"}));
  EXPECT_FALSE(fs::exists(o.output));
  o.output = file("kks.json");
  o.tol = 2.0;
  EXPECT_FALSE(volume(kks, o).exact);
  std::ifstream in(o.output);
  EXPECT_EQ(nlohmann::json::parse(in).at("kind"), "swept_volume_mesh");
}

}  // namespace volume_exact_tests
}  // namespace qmotion
