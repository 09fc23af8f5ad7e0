// tests/sweep/self_intersection_test.cpp mirrors sweep/self_intersection.hpp: the proof
// that a sweep's surfaces do not meet themselves, on surfaces whose answer is known from
// their construction.
#include <qmotion/api/export.hpp>
#include <qmotion/api/interpolate.hpp>
#include <qmotion/io/poses.hpp>
#include <qmotion/io/profiles.hpp>
#include <qmotion/sweep/self_intersection.hpp>
#include <set>
#include <sstream>

#include "io_test_util.hpp"

namespace qmotion::test {
namespace {
using V3 = Eigen::Vector3d;
using Proof = sweep::SelfIntersectionProof;
using Status = Proof::Status;

/// The faces of a profile extruded along z by `height` (degree 1 along u = t in [0, 1]).
std::vector<sweep::NurbsSurface<double>> extrude(const sweep::Profile<double>& profile,
                                                 double height) {
  std::vector<sweep::NurbsSurface<double>> faces;
  for (const auto& e : profile.edges) {
    sweep::NurbsSurface<double> s;
    s.degree_u = 1;
    s.degree_v = e.degree;
    s.knots_u = {0, 0, 1, 1};
    s.knots_v = e.knots;
    for (const double z : {0.0, height}) {
      std::vector<V3> row;
      for (const auto& x : e.points) row.push_back(x + V3(0, 0, z));
      s.points.push_back(row);
      s.weights.push_back(e.weights);
    }
    faces.push_back(std::move(s));
  }
  return faces;
}

/// The profile: the right half of the unit circle from (0, -1) to (0, 1), then segments up
/// to (0, 2), across to (x, 2) and down to (x, -1). At x = 1 the last segment touches the arc
/// tangentially at (1, 0), in the middle of both edges; at x > 1 they are apart by x - 1, at x < 1
/// the segment crosses the arc.
sweep::Profile<double> hook_profile(double x) {
  auto p = io::read_profile("arc:1,-90,90");
  std::ostringstream spec;
  spec.precision(17);
  spec << "polyline:0,1,0:0,2,0:" << x << ",2,0:" << x << ",-1,0";
  for (const auto& e : io::read_profile(spec.str()).edges) p.edges.push_back(e);
  p.closed = false;
  return p;
}

TEST(SelfIntersectionProof, TellsApartNearTouchTangencyAndCrossing) {
  // Apart by 1e-4 and 1e-7 (gaps a tessellation cannot see): proven.
  for (const double gap : {1e-4, 1e-7}) {
    const Proof apart =
        sweep::prove_no_self_intersection(extrude(hook_profile(1 + gap), 2), false, false);
    EXPECT_EQ(apart.status, Status::none) << gap << ": " << apart.describe();
  }
  // Tangent along the line x = 1, y = 0: touching, found on the arc's middle and the last
  // segment's middle, at no particular t.
  const Proof touch =
      sweep::prove_no_self_intersection(extrude(hook_profile(1.0), 2), false, false);
  ASSERT_EQ(touch.status, Status::touching) << touch.describe();
  std::set<std::size_t> edges{touch.first.edge, touch.second.edge};
  EXPECT_EQ(edges, (std::set<std::size_t>{0, 3}));
  for (const auto* p : {&touch.first, &touch.second}) {
    const double v = (p->v0 + p->v1) / 2;
    if (p->edge == 3) {
      EXPECT_NEAR(v, 2.0 / 3, 1e-6);  // y = 0 on the last segment
    }
  }
  // Crossing by 1e-3.
  const Proof cross =
      sweep::prove_no_self_intersection(extrude(hook_profile(0.999), 2), false, false);
  EXPECT_EQ(cross.status, Status::crossing) << cross.describe();
}

TEST(SelfIntersectionProof, ProvesCornersSeamsAndCaps) {
  // A rectangle's four faces meet at right angles, and a circle's four arcs at a seam: both
  // proven free, with their caps.
  for (const std::string spec : {"rect:4,2", "circle:3"}) {
    SCOPED_TRACE(spec);
    const auto profile = io::read_profile(spec);
    const auto faces = extrude(profile, 5);
    for (const bool caps : {false, true}) {
      const Proof p = sweep::prove_no_self_intersection(faces, profile.closed, caps);
      EXPECT_EQ(p.status, Status::none) << p.describe();
    }
  }
  // A cap that the surface crosses: a square tube whose top is pushed down through the
  // bottom cap's plane inside the square (a fold: faces go up and come back down).
  auto faces = extrude(io::read_profile("rect:4,2"), 5);
  for (auto& f : faces) {
    f.degree_u = 2;
    f.knots_u = {0, 0, 0, 1, 1, 1};
    auto top = f.points.back();
    for (auto& x : top) x = V3(x(0) * 0.5, x(1) * 0.5, -1);  // inside, below the bottom
    f.points.back() = top;
    f.points.insert(f.points.begin() + 1, f.points.front());
    for (auto& x : f.points[1]) x(2) = 6;
    f.weights.push_back(f.weights.back());
  }
  const Proof folded = sweep::prove_no_self_intersection(faces, true, true);
  EXPECT_NE(folded.status, Status::none) << folded.describe();
  EXPECT_TRUE(folded.status == Status::crossing || folded.status == Status::touching)
      << folded.describe();
}

/// The exact surfaces of a profile swept by the motion through the poses file.
std::vector<sweep::NurbsSurface<double>> swept(const std::string& poses, const std::string& spec) {
  const auto m = qmotion::interpolate(io::read_poses(test_data(poses)), {}).motion;
  ExportOptions opt;
  opt.self_intersection_check = false;
  return qmotion::sweep_nurbs(m, io::read_profile(spec), opt);
}

TEST(SelfIntersectionProof, TubesAlongCoils) {
  // A tube of radius 3 along a coil of pitch 20 is proven free, caps included; at pitch 2
  // the coils overlap and the proof finds a crossing.
  const auto open = swept("self_intersection/coil_open.json", "circle:3");
  const Proof p = sweep::prove_no_self_intersection(open, true, true);
  EXPECT_EQ(p.status, Status::none) << p.describe();
  const auto tight = swept("self_intersection/coil_tight.json", "circle:3");
  const Proof q = sweep::prove_no_self_intersection(tight, true, true);
  EXPECT_EQ(q.status, Status::crossing) << q.describe();
  const auto eight = swept("self_intersection/figure8.json", "circle:3");
  const Proof r = sweep::prove_no_self_intersection(eight, true, false);
  EXPECT_EQ(r.status, Status::crossing) << r.describe();
}

TEST(SelfIntersectionProof, SeesAnOverlapTheTessellationMisses) {
  // Pitch 6.02764 (coil.py): the tube of radius 3 overlaps the next turn by about 1e-5.
  const auto m =
      qmotion::interpolate(io::read_poses(test_data("self_intersection/coil_touching.json")), {})
          .motion;
  const auto circle = io::read_profile("circle:3");
#ifdef QMOTION_WITH_CGAL
  EXPECT_FALSE(qmotion::sweep_self_intersections(m, circle).found());  // the mesh check
#endif
  ExportOptions opt;
  opt.self_intersection_check = false;
  const Proof p =
      sweep::prove_no_self_intersection(qmotion::sweep_nurbs(m, circle, opt), true, false);
  EXPECT_TRUE(p.status == Status::touching || p.status == Status::crossing) << p.describe();
  // Where: two places on successive turns, half a turn of the profile apart (the top of one
  // turn against the bottom of the next).
  EXPECT_GT(std::abs((p.first.t0 + p.first.t1) / 2 - (p.second.t0 + p.second.t1) / 2), 0.4);
}

TEST(SelfIntersectionProof, AStillPointIsSingularNotProven) {
  // A segment turning half a turn about its midpoint: the midpoint never moves, so every t
  // maps it to one point (the surface's t-derivative vanishes there).
  const auto disk = swept("self_intersection/half_turn.json", "segment:-10,0,0:10,0,0");
  const Proof p = sweep::prove_no_self_intersection(disk, false, false);
  ASSERT_EQ(p.status, Status::singular) << p.describe();
  EXPECT_LE(p.first.v0, 0.5 + 1e-6);
  EXPECT_GE(p.first.v1, 0.5 - 1e-6);
}

}  // namespace
}  // namespace qmotion::test
