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

TEST(NurbsJson, StreamedTextIsTheTreesDocumentBitForBit) {
  // Awkward doubles: the shortest round-trip text must give back the same bits.
  sweep::NurbsCurve<double> c{2,
                              {0, 0, 0, 1.0 / 3, 1, 1, 1},
                              {{0.1, -2e-300, 1e21},
                               {1.0 / 7, 5e-324, -0.0},
                               {123456789.123456789, 1, 2},
                               {std::nextafter(1.0, 2.0), 3, 4}},
                              {1, 0.3, 2.0 / 3, 7}};
  const nlohmann::json extra{
      {"units", "mm"}, {"continuity", 1}, {"approximation", {{"tolerance", 1e-6}}}};
  const std::string text = io::curve_json_text(c, extra);
  nlohmann::json tree = io::curve_to_json(c);
  tree.update(extra);
  EXPECT_EQ(nlohmann::json::parse(text), tree);
  const auto back = io::curve_from_json(io::parse_json(text, "streamed"), "streamed");
  ASSERT_EQ(back.points.size(), c.points.size());
  for (std::size_t i = 0; i < c.points.size(); ++i)
    for (int k = 0; k < 3; ++k)
      EXPECT_EQ(std::signbit(back.points[i](k)), std::signbit(c.points[i](k)));
  EXPECT_EQ(back.points, c.points);
  EXPECT_EQ(back.knots, c.knots);
  EXPECT_EQ(back.weights, c.weights);
  // One pole a line.
  EXPECT_NE(text.find("\n  [0.1,-2e-300,1e+21],\n"), std::string::npos) << text;

  sweep::NurbsSurface<double> s{1, 1, {0, 0, 1, 1}, {0, 0, 0.5, 1, 1}, {}, {}};
  for (int i = 0; i < 2; ++i) {
    s.points.push_back({});
    s.weights.push_back({});
    for (int k = 0; k < 3; ++k) {
      s.points.back().emplace_back(i / 3.0, k * 0.1, i * k);
      s.weights.back().push_back(1.0 + k / 9.0);
    }
  }
  const std::string st = io::surface_json_text(s, {{"units", "in"}});
  nlohmann::json stree = io::surface_to_json(s);
  stree["units"] = "in";
  EXPECT_EQ(nlohmann::json::parse(st), stree);
  const auto sback = io::surface_from_json(io::parse_json(st, "s"), "s");
  EXPECT_EQ(sback.points, s.points);
  EXPECT_EQ(sback.weights, s.weights);
  const nlohmann::json shell = nlohmann::json::parse(io::shell_json_text({s, s}, true));
  EXPECT_EQ(shell["type"], "nurbs_shell");
  EXPECT_EQ(shell["closed"], true);
  ASSERT_EQ(shell["faces"].size(), 2u);
  EXPECT_EQ(shell["faces"][1], io::surface_to_json(s));
  // A member twice is a bug of the caller.
  EXPECT_TRUE(throws_error(
      [&] {
        io::curve_json_text(c, {{"degree", 3}});
      },
      Errc::internal, {"degree"}));
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
