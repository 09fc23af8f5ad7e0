// tests/io/nurbs_json_test.cpp mirrors io/nurbs_json.hpp
#include <tbb/task_arena.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <qmotion/io/json_number.hpp>
#include <qmotion/io/json_text.hpp>
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

TEST(NurbsJson, LongArraysAreWrittenInBlocksWithTheBytesOfOneCore) {
  // Long arrays are formatted in blocks on every core and joined: the text must be the
  // tree's document and the very bytes a one-thread arena writes, for a long curve, a
  // surface long in u, one long in v, and a shell of both (several waves of blocks each).
  auto awkward = [](std::size_t i, int k) {
    return std::sin(0.37 * double(i) + k) * std::pow(10.0, double(int(i % 7) - 3)) + 1.0 / 3;
  };
  sweep::NurbsCurve<double> c;
  c.degree = 3;
  const std::size_t n = 40001;
  c.knots.assign(4, 0.0);
  for (std::size_t i = 1; i + 3 < n; ++i) c.knots.push_back(double(i) / double(n - 3));
  c.knots.insert(c.knots.end(), 4, 1.0);
  for (std::size_t i = 0; i < n; ++i) {
    c.points.emplace_back(awkward(i, 0), awkward(i, 1), awkward(i, 2));
    c.weights.push_back(1 + 0.5 * std::abs(awkward(i, 3)));
  }
  auto surface = [&](std::size_t rows, std::size_t cols) {
    sweep::NurbsSurface<double> s{1, 1, {0, 0, 1, 1}, {0, 0, 1, 1}, {}, {}};
    s.knots_u.assign(2, 0.0);
    for (std::size_t i = 1; i + 1 < rows; ++i) s.knots_u.push_back(double(i) / double(rows - 1));
    s.knots_u.insert(s.knots_u.end(), 2, 1.0);
    s.knots_v.assign(2, 0.0);
    for (std::size_t j = 1; j + 1 < cols; ++j) s.knots_v.push_back(double(j) / double(cols - 1));
    s.knots_v.insert(s.knots_v.end(), 2, 1.0);
    for (std::size_t i = 0; i < rows; ++i) {
      s.points.emplace_back();
      s.weights.emplace_back();
      for (std::size_t j = 0; j < cols; ++j) {
        s.points.back().emplace_back(awkward(i * cols + j, 0), awkward(j, 1), awkward(i, 2));
        s.weights.back().push_back(2 + awkward(i + j, 3));
      }
    }
    return s;
  };
  const auto tall = surface(20000, 4), wide = surface(3, 30000);
  const nlohmann::json extra{{"units", "mm"}};
  auto texts = [&] {
    return std::vector<std::string>{
        io::curve_json_text(c, extra), io::surface_json_text(tall, extra),
        io::surface_json_text(wide, extra), io::shell_json_text({tall, wide}, false, extra)};
  };
  const auto all = texts();
  tbb::task_arena one(1);
  const auto single = one.execute(texts);
  ASSERT_EQ(all.size(), single.size());
  for (std::size_t k = 0; k < all.size(); ++k) EXPECT_TRUE(all[k] == single[k]) << "text " << k;
  nlohmann::json tree = io::curve_to_json(c);
  tree.update(extra);
  EXPECT_EQ(nlohmann::json::parse(all[0]), tree);
  // One pole a line: the curve's text has a line for each pole, none lost or doubled.
  EXPECT_EQ(std::count(all[0].begin(), all[0].end(), '\n'), std::ptrdiff_t(n + 9));
  const auto back = io::curve_from_json(io::parse_json(all[0], "c"), "c");
  EXPECT_EQ(back.points, c.points);
  EXPECT_EQ(back.weights, c.weights);
  EXPECT_EQ(back.knots, c.knots);
  for (const auto& [k, s] : {std::pair{1, &tall}, std::pair{2, &wide}}) {
    nlohmann::json st = io::surface_to_json(*s);
    st.update(extra);
    EXPECT_EQ(nlohmann::json::parse(all[std::size_t(k)]), st) << k;
  }
  const auto shell = nlohmann::json::parse(all[3]);
  EXPECT_EQ(shell["faces"][0], io::surface_to_json(tall));
  EXPECT_EQ(shell["faces"][1], io::surface_to_json(wide));

  // Written to files as they are made (never held whole): the same bytes.
  namespace fs = std::filesystem;
  const fs::path d = fs::temp_directory_path() / ("qmotion_blocks_" + std::to_string(::getpid()));
  fs::remove_all(d);
  fs::create_directories(d);
  io::write_curve_json((d / "c.json").string(), c, extra);
  io::write_surface_json((d / "tall.json").string(), tall, extra);
  io::write_surface_json((d / "wide.json").string(), wide, extra);
  io::write_shell_json((d / "shell.json").string(), {tall, wide}, false, extra);
  EXPECT_TRUE(io::read_text_file((d / "c.json").string()) == all[0]);
  EXPECT_TRUE(io::read_text_file((d / "tall.json").string()) == all[1]);
  EXPECT_TRUE(io::read_text_file((d / "wide.json").string()) == all[2]);
  EXPECT_TRUE(io::read_text_file((d / "shell.json").string()) == all[3]);

  // A sink that fails halfway (a full disk) stops the writer with its error while blocks
  // are still being formatted, and the file is not left behind.
  int calls = 0;
  io::JsonText t;
  t.sink = [&calls](const std::string&) {
    if (++calls == 3) throw Error(Errc::invalid_input, "out.json: write failed: disk full");
  };
  EXPECT_TRUE(throws_error([&] { t.numbers(c.knots); }, Errc::invalid_input, {"disk full"}));
  EXPECT_EQ(calls, 3);
  EXPECT_TRUE(throws_error(
      [&] {
        io::write_json_atomic((d / "half.json").string(), [&](io::JsonText& w) {
          w.numbers(c.weights);
          throw Error(Errc::invalid_input, "stopped halfway");
        });
      },
      Errc::invalid_input, {"halfway"}));
  EXPECT_FALSE(fs::exists(d / "half.json"));
  EXPECT_EQ(std::distance(fs::directory_iterator(d), fs::directory_iterator()), 4);
  fs::remove_all(d);
}

/// A 3 x 4 bilinear-by-cubic surface with awkward numbers, for the file reader.
sweep::NurbsSurface<double> awkward_surface(double shift) {
  sweep::NurbsSurface<double> s{1, 2, {0, 0, 0.5, 1, 1}, {0, 0, 0, 1.0 / 3, 1, 1, 1}, {}, {}};
  for (int i = 0; i < 3; ++i) {
    s.points.push_back({});
    s.weights.push_back({});
    for (int k = 0; k < 4; ++k) {
      s.points.back().emplace_back(i / 3.0 + shift, -2e-300 * k, 1e21 * i - 0.1 * k);
      s.weights.back().push_back(1.0 / (7 + i + k));
    }
  }
  return s;
}

void write_text(const std::filesystem::path& p, const std::string& text) {
  std::ofstream(p, std::ios::binary) << text;
}

/// read_nurbs_file gives back what was written, bit for bit, through its scanner and
/// through the tree (a file the scanner declines), and refuses as the tree readers do.
TEST(NurbsJson, FilesReadBackBitForBitThroughEitherReader) {
  const auto a = awkward_surface(0), b = awkward_surface(1e-9);
  const auto same = [](const sweep::NurbsSurface<double>& x, const sweep::NurbsSurface<double>& y) {
    return x.degree_u == y.degree_u && x.degree_v == y.degree_v && x.knots_u == y.knots_u &&
           x.knots_v == y.knots_v && x.points == y.points && x.weights == y.weights;
  };
  const auto shell = scratch_path("nurbs_read", "shell.json");
  io::write_shell_json(shell.string(), {a, b}, true, {{"units", "in"}});
  io::NurbsFile f = io::read_nurbs_file(shell.string(), true);
  EXPECT_EQ(f.units, "in");
  ASSERT_EQ(f.faces.size(), 2u);
  EXPECT_TRUE(same(f.faces[0], a));
  EXPECT_TRUE(same(f.faces[1], b));
  const auto surface = scratch_path("nurbs_read", "surface.json");
  io::write_surface_json(surface.string(), a);
  f = io::read_nurbs_file(surface.string(), true);
  EXPECT_EQ(f.units, "");
  ASSERT_EQ(f.faces.size(), 1u);
  EXPECT_TRUE(same(f.faces[0], a));
  // A weight written as an exact fraction: the scanner declines it, the tree reads it.
  nlohmann::json tree = io::surface_to_json(a);
  tree["weights"][0][0] = "1/7";
  write_text(surface, tree.dump());
  f = io::read_nurbs_file(surface.string(), true);
  ASSERT_EQ(f.faces.size(), 1u);
  EXPECT_DOUBLE_EQ(f.faces[0].weights[0][0], 1.0 / 7);
  EXPECT_EQ(f.faces[0].points, a.points);
  // A curve, its weights left out (all 1).
  const sweep::NurbsCurve<double> c{
      2, {0, 0, 0, 1, 1, 1}, {{0, 0, 0}, {1, 2, 3}, {0.1, 0, 1e-7}}, {1, 1, 1}};
  const auto curve = scratch_path("nurbs_read", "curve.json");
  nlohmann::json ct = io::curve_to_json(c);
  ct.erase("weights");
  write_text(curve, ct.dump());
  f = io::read_nurbs_file(curve.string(), false);
  EXPECT_EQ(f.curve.points, c.points);
  EXPECT_EQ(f.curve.weights, c.weights);
  // Refusals, worded by the tree reader and naming the face.
  nlohmann::json bad = nlohmann::json::parse(io::shell_json_text({a, b}, true));
  bad["faces"][1]["weights"][2][3] = 0;
  write_text(shell, bad.dump());
  EXPECT_TRUE(throws_error([&] { io::read_nurbs_file(shell.string(), true); }, Errc::invalid_input,
                           {"face 2", "weights[2][3]", "positive"}));
  bad = io::surface_to_json(a);
  bad["knots_v"][2] = 0.9;  // decreasing
  write_text(surface, bad.dump());
  EXPECT_TRUE(throws_error([&] { io::read_nurbs_file(surface.string(), true); },
                           Errc::invalid_input, {"surface.json", "v: "}));
  EXPECT_TRUE(throws_error([&] { io::read_nurbs_file(surface.string(), false); },
                           Errc::invalid_input, {"surface.json", "type"}));
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
