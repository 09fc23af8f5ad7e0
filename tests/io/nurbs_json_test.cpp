// tests/io/nurbs_json_test.cpp mirrors io/nurbs_json.hpp
#include <qmotion/io/json_number.hpp>
#include <qmotion/io/nurbs_json.hpp>

#include "io_test_util.hpp"

namespace qmotion::test {
namespace {

TEST(NurbsJson, SharedProfilesReadAndEvaluate) {
  const auto arc = io::curve_from_json(
      io::read_json_file(test_data("profiles/quarter_circle.json")), "quarter_circle");
  EXPECT_EQ(arc.degree, 2);
  // The rational quarter circle has radius 10 everywhere (x-z plane).
  for (int i = 0; i <= 20; ++i) {
    const Eigen::Vector3d p = sweep::evaluate(arc, i / 20.0);
    EXPECT_NEAR(std::hypot(p.x(), p.z()), 10.0, 1e-12);
    EXPECT_EQ(p.y(), 0.0);
  }
  const auto par =
      io::curve_from_json(io::read_json_file(test_data("profiles/parabola.json")), "parabola");
  EXPECT_EQ(par.points.size(), 3u);
}

TEST(NurbsJson, CurveAndSurfaceFollowTheSpecLayout) {
  sweep::NurbsCurve<double> c{
      2, {0, 0, 0, 1, 1, 1}, {{1, 0, 0}, {1, 1, 0}, {0, 1, 0}}, {1, 0.5, 1}};
  const auto j = io::curve_to_json(c);
  EXPECT_EQ(j["type"], "nurbs_curve");
  EXPECT_EQ(j["knots"].size(), c.points.size() + 3);
  const auto back = io::curve_from_json(io::parse_json(j.dump(), "rt"), "rt");
  EXPECT_EQ(back.points, c.points);
  EXPECT_EQ(back.weights, c.weights);
  EXPECT_EQ(back.knots, c.knots);
  sweep::NurbsSurface<double> s{1, 2, {0, 0, 1, 1}, {0, 0, 0, 1, 1, 1}, {}, {}};
  for (int i = 0; i < 2; ++i) {
    s.points.push_back({});
    s.weights.push_back({});
    for (int k = 0; k < 3; ++k) {
      s.points.back().emplace_back(i, k, i * k);
      s.weights.back().push_back(1.0 + k);
    }
  }
  const auto js = io::surface_to_json(s);
  EXPECT_EQ(js["type"], "nurbs_surface");
  EXPECT_EQ(js["control_points"][1][2],
            nlohmann::json({1.0, 2.0, 2.0}));  // pole i=1 along u, j=2 along v
  EXPECT_EQ(js["weights"][0][2], 3.0);
}

TEST(NurbsJson, BadProfilesAreRefused) {
  auto bad = [](const std::string& text, std::initializer_list<std::string> needles) {
    return throws_error([&] { io::curve_from_json(io::parse_json(text, "p.json"), "p.json"); },
                        Errc::invalid_input, needles);
  };
  EXPECT_TRUE(bad(
      R"({"type":"nurbs_curve","degree":1,"knots":[0,0,1,1],"control_points":[[0,0,0],[1,0,0]],"weights":[1,-1]})",
      {"p.json", "weights[1]", "positive"}));
  EXPECT_TRUE(
      bad(R"({"type":"nurbs_curve","degree":1,"knots":[0,1],"control_points":[[0,0,0],[1,0,0]]})",
          {"knot vector"}));
  EXPECT_TRUE(bad(R"({"type":"line","degree":1})", {"type"}));
  EXPECT_TRUE(
      bad(R"({"type":"nurbs_curve","degree":1,"knots":[0,0,1,1],"control_points":[[0,0],[1,0,0]]})",
          {"control_points[0]", "3 numbers"}));
}

}  // namespace
}  // namespace qmotion::test
