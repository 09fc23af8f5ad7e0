// tests/sweep/span_faces_test.cpp mirrors sweep/span_faces.hpp: a solid's faces, one u span
// each, are the same surface.
#include <qmotion/sweep/span_faces.hpp>
#include <qmotion/sweep/surface.hpp>

#include "io_test_util.hpp"
#include "surface_util.hpp"

namespace qmotion::test {
namespace {

/// A rational surface of degree 3 x 2 whose u knots have multiplicities 1, 2 and 3 inside
/// (the last a C0 knot, already split by split_c0).
sweep::NurbsSurface<double> mixed_knots_surface() {
  return random_surface(3, {0, 0, 0, 0, 0.2, 0.45, 0.45, 0.7, 0.7, 0.7, 0.85, 1, 1, 1, 1}, 2,
                        {0, 0, 0, 0.5, 1, 1, 1}, 7);
}

TEST(SpanFaces, FullKnotsKeepTheSurface) {
  const auto s = mixed_knots_surface();
  const auto r = sweep::with_full_u_knots(s);
  // Every interior knot at multiplicity 3: 0.2 (+2), 0.45 (+1), 0.85 (+2).
  EXPECT_EQ(r.knots_u, (std::vector<double>{0,   0,   0,   0,    0.2,  0.2,  0.2, 0.45, 0.45, 0.45,
                                            0.7, 0.7, 0.7, 0.85, 0.85, 0.85, 1,   1,    1,    1}));
  EXPECT_EQ(r.points.size(), 16u);
  EXPECT_EQ(r.knots_v, s.knots_v);
  for (const auto& row : r.weights)
    for (double w : row) EXPECT_GT(w, 0);
  for (int i = 0; i <= 40; ++i)
    for (int j = 0; j <= 10; ++j) {
      const double u = i / 40.0, v = j / 10.0;
      EXPECT_LT((sweep::evaluate(r, u, v) - sweep::evaluate(s, u, v)).norm(), 1e-13)
          << u << ", " << v;
    }
}

TEST(SpanFaces, OneFaceAUSpanAndTogetherTheSurface) {
  const auto s = mixed_knots_surface();
  const auto faces = sweep::split_u_spans(s);
  // Five u spans; v is C1 at 0.5 (a single knot of a quadratic): one piece.
  ASSERT_EQ(faces.size(), 5u);
  const std::vector<double> ends = {0, 0.2, 0.45, 0.7, 0.85, 1};
  for (std::size_t k = 0; k < faces.size(); ++k) {
    const auto& f = faces[k];
    ASSERT_EQ(f.knots_u.size(), 8u) << k;  // one span: 4 + 4 clamped knots
    EXPECT_EQ(f.knots_u.front(), ends[k]);
    EXPECT_EQ(f.knots_u.back(), ends[k + 1]);
    for (int i = 0; i <= 8; ++i)
      for (int j = 0; j <= 6; ++j) {
        const double u = ends[k] + (ends[k + 1] - ends[k]) * i / 8.0, v = j / 6.0;
        EXPECT_LT((sweep::evaluate(f, u, v) - sweep::evaluate(s, u, v)).norm(), 1e-13);
      }
  }
  // A surface of one u span is its own face.
  sweep::NurbsSurface<double> one = s;
  one.knots_u = {0, 0, 0, 0, 1, 1, 1, 1};
  one.points.resize(4);
  one.weights.resize(4);
  EXPECT_EQ(sweep::split_u_spans(one).size(), 1u);
}

}  // namespace
}  // namespace qmotion::test
