// tests/cam/collision_test.cpp: <qmotion/cam/collision.hpp>: a holder's first contact with
// a box against the instant worked out apart (tests/holder_truth.hpp) on random straight
// moves, and against dense sampling on arcs; the plane distance it bounds with.
#include <gtest/gtest.h>

#include <cmath>
#include <qmotion/cam/collision.hpp>
#include <random>

#include "../holder_truth.hpp"

namespace qmotion::test {
namespace {

using V3 = Eigen::Vector3d;
constexpr double kR = 10, kH = 40, kL = 30, kTol = 0.01;
const Eigen::AlignedBox3d kBox(V3(-50, -50, -40), V3(50, 50, 0));

/// The holder (radius kR over heights [kL, kL + kH] above the tip at p) inside kBox, by
/// more than eps.
bool holder_inside(const V3& p, double eps) {
  const Eigen::Vector2d c = p.head<2>();
  const Eigen::Vector2d q = c.cwiseMax(kBox.min().head<2>()).cwiseMin(kBox.max().head<2>());
  return (c - q).norm() < kR - eps && p.z() + kL < kBox.max().z() - eps &&
         p.z() + kL + kH > kBox.min().z() + eps;
}

/// Moves near the box's top, faces and corners, their ends within 12 mm of its boundary in
/// the plane and their holder's bottom within 1 mm of its top.
TEST(Collision, FirstContactHoldsTheTrueInstantOnRandomMoves) {
  std::mt19937 rng(56);
  std::uniform_real_distribution<double> u(-70, 70), z(-31, -29);
  const auto body = cam::holder_cores(kR, kH, kL);
  const cam::Stock stock{kBox, nullptr};
  int contacts = 0, clear = 0, undecided = 0;
  for (int i = 0; i < 4000; ++i) {
    cam::Move m;
    m.kind = cam::Move::Kind::traverse;
    m.from = V3(u(rng), u(rng), z(rng));
    m.to = V3(u(rng), u(rng), i % 4 ? m.from.z() : z(rng));
    const double truth = cylinder_box_first_contact(m.from, m.to, kR, kL, kL + kH, kBox);
    const cam::Contact k = cam::first_contact(m, 0, body, stock, nullptr, kTol);
    if (k.kind == cam::Contact::Kind::undecided) {
      ++undecided;
      continue;
    }
    if (truth < 0) {
      ASSERT_EQ(k.kind, cam::Contact::Kind::clear) << i;
      ++clear;
      continue;
    }
    ASSERT_EQ(k.kind, cam::Contact::Kind::contact) << i << " truth " << truth;
    EXPECT_LE(k.t_lo, truth + 1e-12) << i;
    EXPECT_GE(k.t_hi, truth - 1e-12) << i;
    // The witness: a point of the holder at t_hi, inside the box.
    const V3 p = cam::position(m, k.t_hi), w = k.point - p;
    EXPECT_LE(w.head<2>().norm(), kR) << i;
    EXPECT_GT(k.point.z(), p.z() + kL - 1e-9) << i;
    EXPECT_GT(stock.depth(k.point), 0) << i;
    ++contacts;
  }
  EXPECT_GT(contacts, 1000);
  EXPECT_GT(clear, 1000);
  EXPECT_LE(undecided, 40);  // grazing contacts, at most 1 %
}

/// Arcs in the XY plane past the box's corner and across its top: no sampled instant before
/// the interval has the holder inside the box, and the witness at its end is inside.
TEST(Collision, FirstContactOnArcsHasNoSampledContactBefore) {
  std::mt19937 rng(57);
  std::uniform_real_distribution<double> c(40, 75), rad(5, 25), z(-30.5, -29.5);
  const auto body = cam::holder_cores(kR, kH, kL);
  const cam::Stock stock{kBox, nullptr};
  int contacts = 0;
  for (int i = 0; i < 300; ++i) {
    cam::Move m;
    m.kind = cam::Move::Kind::arc;
    m.plane = 17;
    m.centre = V3(c(rng), c(rng), z(rng));
    const double a = rad(rng);
    m.from = m.centre + V3(a, 0, 0);
    m.to = m.from;
    m.turns = i % 2 ? 1 : -1;
    const cam::Contact k = cam::first_contact(m, 0, body, stock, nullptr, kTol);
    const double end = k.kind == cam::Contact::Kind::clear ? 1.0 : k.t_lo;
    for (int s = 0; s < 20000 && end > 0; ++s) {  // before t_lo (all of a clear arc)
      const double t = end * s / 20000;
      ASSERT_FALSE(holder_inside(cam::position(m, t), 1e-9)) << i << " t " << t;
    }
    if (k.kind != cam::Contact::Kind::contact) continue;
    ++contacts;
    EXPECT_GT(stock.depth(k.point), 0) << i;
    EXPECT_LE((k.point - cam::position(m, k.t_hi)).head<2>().norm(), kR) << i;
  }
  EXPECT_GT(contacts, 50);
}

/// The plane distance from a segment to a box is a lower bound of every sampled point's and
/// within the sampling step of the least.
TEST(Collision, SegmentToRectangleDistance) {
  std::mt19937 rng(58);
  std::uniform_real_distribution<double> u(-4, 4);
  const Eigen::AlignedBox2d r(Eigen::Vector2d(-1, -0.5), Eigen::Vector2d(1, 0.5));
  for (int i = 0; i < 2000; ++i) {
    const Eigen::Vector2d a(u(rng), u(rng)), b(u(rng), u(rng));
    const double d = cam::detail::segment_rect_distance(a, b, r);
    double least = HUGE_VAL;
    const int n = 4000;
    for (int s = 0; s <= n; ++s) {
      const Eigen::Vector2d p = a + (b - a) * (double(s) / n);
      least = std::min(least, (p - p.cwiseMax(r.min()).cwiseMin(r.max())).norm());
    }
    ASSERT_LE(d, least + 1e-12) << i;
    ASSERT_GE(d, least - (b - a).norm() / n - 1e-12) << i;
  }
}

}  // namespace
}  // namespace qmotion::test
