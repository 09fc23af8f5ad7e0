// tests/io/poses_test.cpp mirrors io/poses.hpp
#include <cmath>
#include <cstring>
#include <filesystem>
#include <optional>
#include <qmotion/io/atomic_file.hpp>
#ifdef QMOTION_WITH_CGAL
#include <qmotion/io/exact_number.hpp>
#endif
#include <qmotion/io/json_number.hpp>
#include <qmotion/io/json_text.hpp>
#include <qmotion/io/poses.hpp>
#include <qmotion/kernel/error.hpp>
#include <variant>

#include "io_test_util.hpp"

namespace qmotion::test {
namespace {

TEST(Poses, SharedSamplesReadWithEveryRotationForm) {
  const auto set = io::read_poses(test_data("poses/five_positions.json"));
  ASSERT_EQ(set.poses.size(), 5u);
  EXPECT_TRUE(set.has_t());
  EXPECT_EQ(set.units, "mm");
  const auto P = io::to_poses_double(set);
  // Pose 1: 45 degrees about z.
  EXPECT_NEAR(P[1].rotation.w(), std::cos(M_PI / 8), 1e-15);
  EXPECT_NEAR(P[1].rotation.z(), std::sin(M_PI / 8), 1e-15);
  // Pose 2: 80 degrees about (1,1,0)/sqrt2: the axis is kept.
  EXPECT_NEAR(P[2].rotation.x(), P[2].rotation.y(), 1e-15);
  EXPECT_NEAR(P[2].rotation.w(), std::cos(40 * M_PI / 180), 1e-15);
  for (const auto& p : P) EXPECT_NEAR(p.rotation.norm2(), 1.0, 1e-12);
  // The pose's dual quaternion maps the origin to the position.
  const auto s = kernel::translation_vector(P[3].dual_quaternion());
  EXPECT_NEAR((s - Eigen::Vector3d(90, 80, 10)).norm(), 0.0, 1e-12);

  const auto no_t = io::read_poses(test_data("poses/three_positions_no_t.json"));
  EXPECT_FALSE(no_t.has_t());
  EXPECT_EQ(io::read_poses(test_data("poses/helix_40.json")).poses.size(), 40u);
}

#ifdef QMOTION_WITH_CGAL
TEST(Poses, RationalStringsAreKeptExactly) {
  const auto set = io::read_poses(test_data("poses/rational_exact.json"));
  ASSERT_EQ(set.poses.size(), 4u);
  EXPECT_EQ(io::exact_from_text(set.poses[1].t->source()),
            kernel::Rational(1) / kernel::Rational(3));
  EXPECT_EQ(io::exact_from_text(set.poses[3].position[2].source()),
            kernel::Rational(1) / kernel::Rational(7));
  EXPECT_EQ(set.poses[2].rotation.values[0].source(), "2");
}
#endif

TEST(Poses, MatrixRotationsMatchTheirQuaternion) {
  const nlohmann::json m = {{std::cos(0.3) / std::cos(0.3), 0.0, 0.0},
                            {0.0, std::cos(0.3), -std::sin(0.3)},
                            {0.0, std::sin(0.3), std::cos(0.3)}};
  const std::string text = R"({"poses":[{"position":[0,0,0],"rotation":{"matrix":)" + m.dump() +
                           R"(}},{"position":[1,0,0],"rotation":{"quaternion":[1,0,0,0]}}]})";
  const auto P = io::to_poses_double(io::parse_poses_json(text, "m.json"));
  EXPECT_NEAR(P[0].rotation.w(), std::cos(0.15), 1e-15);
  EXPECT_NEAR(P[0].rotation.x(), std::sin(0.15), 1e-15);
  EXPECT_NEAR(P[0].rotation.norm2(), 1.0, 1e-15);
}

TEST(Poses, CsvWithAndWithoutT) {
  const auto set = io::read_poses(test_data("good_poses.csv"));
  ASSERT_EQ(set.poses.size(), 3u);
  EXPECT_TRUE(set.has_t());
  const auto P = io::to_poses_double(set);
  EXPECT_EQ(P[2].position, Eigen::Vector3d(10, 10, 5));
  EXPECT_NEAR(P[1].rotation.w(), 0.5, 1e-15);
  const auto no_t =
      io::parse_poses_csv("x,y,z,qw,qx,qy,qz\n0,0,0,1,0,0,0\n1,2,3,0,1,0,0\n", "n.csv");
  EXPECT_FALSE(no_t.has_t());
}

#ifdef QMOTION_WITH_CGAL
TEST(Poses, JsonRoundTripKeepsEveryNumber) {
  for (const std::string f : {"poses/five_positions.json", "poses/rational_exact.json",
                              "poses/three_positions_no_t.json"}) {
    const auto a = io::read_poses(test_data(f));
    const auto b = io::parse_poses_json(io::poses_to_json(a).dump(), "roundtrip");
    ASSERT_EQ(a.poses.size(), b.poses.size());
    for (std::size_t i = 0; i < a.poses.size(); ++i) {
      EXPECT_EQ(a.poses[i].t.has_value(), b.poses[i].t.has_value());
      if (a.poses[i].t) {
        EXPECT_EQ(io::exact_from_text(a.poses[i].t->source()),
                  io::exact_from_text(b.poses[i].t->source()));
      }
      for (int k = 0; k < 3; ++k)
        EXPECT_EQ(io::exact_from_text(a.poses[i].position[k].source()),
                  io::exact_from_text(b.poses[i].position[k].source()));
      ASSERT_EQ(a.poses[i].rotation.values.size(), b.poses[i].rotation.values.size());
      for (std::size_t k = 0; k < a.poses[i].rotation.values.size(); ++k)
        EXPECT_EQ(io::exact_from_text(a.poses[i].rotation.values[k].source()),
                  io::exact_from_text(b.poses[i].rotation.values[k].source()));
    }
  }
}
#endif

#ifdef QMOTION_WITH_CGAL
TEST(Poses, TheFastReaderKeepsNoTextItsValueGivesBack) {
  const std::string text =
      R"({"poses":[{"t":0.10000000000000001,"position":[0.30000000000000004,0.1,1e-5],)"
      R"("rotation":{"quaternion":[1,0,0,0]}},{"t":1,"position":[0,0,0],)"
      R"("rotation":{"axis_angle":{"axis":[0,0,1],"angle_deg":12.5}}}]})";
  const auto fast = io::parse_poses_fast(text, "p.json");
  ASSERT_TRUE(fast.has_value());
  const auto& p = fast->poses[0];
  // Shortest round-trip texts are kept as their values alone...
  EXPECT_TRUE(p.position[0].text.empty());
  EXPECT_TRUE(p.position[1].text.empty());
  EXPECT_TRUE(fast->poses[1].rotation.values[3].text.empty());
  // ...and give the same decimal back: exact mode still reads 0.1 as 1/10.
  EXPECT_EQ(p.position[0].source(), "0.30000000000000004");
  EXPECT_EQ(io::exact_from_text(p.position[1].source()),
            kernel::Rational(1) / kernel::Rational(10));
  // Other spellings keep their text.
  EXPECT_EQ(p.position[2].text, "1e-5");
  EXPECT_EQ(p.t->text, "0.10000000000000001");
  // Written back, a value-only number is a JSON number with the same text; a text the value
  // does not give back stays a string.
  const auto j = io::poses_to_json(*fast);
  const auto& jp = j["poses"][0];
  ASSERT_TRUE(jp["position"][0].is_number_float());
  EXPECT_EQ(jp["position"][0].dump(), "0.30000000000000004");
  EXPECT_EQ(jp["position"][0].get<double>(), p.position[0].value);
  EXPECT_EQ(jp["t"], "0.10000000000000001");
  io::JsonText streamed;
  io::poses_text(streamed, *fast, 0);
  EXPECT_EQ(nlohmann::json::parse(streamed.out), j);
  const auto again = io::parse_poses_json(streamed.out, "again.json");
  for (int k = 0; k < 3; ++k)
    EXPECT_EQ(io::exact_from_text(again.poses[0].position[k].source()),
              io::exact_from_text(p.position[k].source()));
  EXPECT_EQ(io::exact_from_text(again.poses[0].t->source()), io::exact_from_text(p.t->source()));
}
#endif

/// The set read by the tree reader alone (nlohmann's parser), or its message.
std::variant<io::PoseSet, std::string> dom_read(const std::string& text) {
  try {
    return io::parse_poses_json_value(io::parse_json_reference(text, "p.json"), "p.json");
  } catch (const Error& e) {
    return std::string(e.what());
  }
}

/// The same number: the same source text (the fast reader keeps none where the text is the
/// value's shortest round-trip text; source() gives it back) and the same double.
void expect_same_numbers(const io::Number& a, const io::Number& b, const std::string& where) {
  EXPECT_EQ(a.source(), b.source()) << where;
  EXPECT_EQ(std::memcmp(&a.value, &b.value, sizeof(double)), 0) << where;  // bit for bit
}

TEST(Poses, TheFastReaderReadsWhatTheTreeReaderReads) {
  std::vector<std::pair<std::string, std::string>> inputs;
  for (const auto& dir : {test_data("poses"), test_data("bad_poses")})
    for (const auto& e : std::filesystem::directory_iterator(dir))
      if (e.path().extension() == ".json")
        inputs.emplace_back(e.path().filename().string(), io::read_text_file(e.path().string()));
  // Shapes the files do not show: unknown members (ignored), null t, a key given twice, a
  // matrix row too short, an axis without its angle, numbers as decimal strings.
  const std::string q = R"("rotation": {"quaternion": [1, 0, 0, 0]})";
  for (const std::string& body :
       {R"({"poses": [{"t": null, "position": [0,0,0], )" + q + R"(, "note": [1, {"a": 2}]},
                      {"position": [1,2,3], )" +
            q + R"(}], "author": "x"})",
        R"({"poses": [{"t": 0, "t": 1, "position": [0,0,0], )" + q + R"(},
                      {"t": 2, "position": [1,2,3], )" +
            q + "}]}",
        R"({"units": "cm", "poses": [{"position": ["0.1","2e-3",-0.0], "rotation":
            {"matrix": [[1,0,0],[0,1,0],[0,0]]}}, {"position": [1,2,3], )" +
            q + "}]}",
        R"({"poses": [{"position": [0,0,0], "rotation": {"axis_angle": {"axis": [0,0,1]}}},
                      {"position": [1,2,3], )" +
            q + "}]}",
        R"({"poses": [{"position": [0,0,0], "rotation": {"axis_angle": {"axis": [0,0,1],
            "angle_deg": "12.5"}}}, {"position": ["1.10","2","3"], )" +
            q + "}], \"units\": \"in\"}"})
    inputs.emplace_back("inline", body);
  int fast = 0;
  for (const auto& [name, text] : inputs) {
    SCOPED_TRACE(name + ": " + text.substr(0, 200));
    const auto dom = dom_read(text);
    std::optional<io::PoseSet> got;
    std::string message;
    try {
      got = io::parse_poses_fast(text, "p.json");
      if (!got)
        got = io::parse_poses_json(text, "p.json");  // the fallback
      else
        ++fast;
    } catch (const Error& e) {
      message = e.what();
    }
    if (const auto* m = std::get_if<std::string>(&dom)) {
      EXPECT_EQ(message, *m);  // refused with the tree reader's very message
      continue;
    }
    ASSERT_TRUE(got) << message;
    const auto& a = std::get<io::PoseSet>(dom);
    EXPECT_EQ(got->units, a.units);
    ASSERT_EQ(got->poses.size(), a.poses.size());
    for (std::size_t i = 0; i < a.poses.size(); ++i) {
      const auto &x = got->poses[i], &y = a.poses[i];
      const std::string w = "pose " + std::to_string(i);
      ASSERT_EQ(x.t.has_value(), y.t.has_value()) << w;
      if (y.t) expect_same_numbers(*x.t, *y.t, w + " t");
      for (std::size_t k = 0; k < 3; ++k) expect_same_numbers(x.position[k], y.position[k], w);
      EXPECT_EQ(x.rotation.kind, y.rotation.kind) << w;
      ASSERT_EQ(x.rotation.values.size(), y.rotation.values.size()) << w;
      for (std::size_t k = 0; k < y.rotation.values.size(); ++k)
        expect_same_numbers(x.rotation.values[k], y.rotation.values[k], w + " rotation");
    }
  }
  // The ordinary files (every rotation form) are read by the fast path.
  EXPECT_GE(fast, 6);
  EXPECT_FALSE(
      io::parse_poses_fast(io::read_text_file(test_data("poses/rational_exact.json")), "r"));
}

struct BadCase {
  std::string file;
  std::vector<std::string> needles;
};

TEST(Poses, EveryBadInputIsRefusedWithItsReason) {
  const std::vector<BadCase> cases = {
      {test_data("bad_poses/bad_decreasing_t.json"), {"pose 2", "increase"}},
      {test_data("bad_poses/bad_nan.json"), {"NaN"}},
      {test_data("bad_poses/bad_single_pose.json"), {"at least two poses"}},
      {test_data("bad_poses/bad_zero_quaternion.json"), {"pose 1", "zero quaternion"}},
      {test_data("bad_poses/malformed.json"), {"invalid JSON", "line 1"}},
      {test_data("bad_poses/missing_position.json"), {"pose 1", "position"}},
      {test_data("bad_poses/missing_rotation.json"), {"pose 1", "rotation"}},
      {test_data("bad_poses/string_nan.json"), {"poses[1].position[1]", "finite"}},
      {test_data("bad_poses/infinity.json"), {"line 1, column", "1e999", "range"}},
      {test_data("bad_poses/equal_t.json"), {"pose 2", "increase"}},
      {test_data("bad_poses/mixed_t.json"), {"pose 1", "every pose or for none"}},
      {test_data("bad_poses/bad_matrix.json"), {"pose 1", "not orthogonal"}},
      {test_data("bad_poses/reflection.json"), {"pose 1", "reflection"}},
      {test_data("bad_poses/zero_axis.json"), {"pose 1", "axis"}},
      {test_data("bad_poses/wrong_arity.json"), {"poses[1].rotation.quaternion", "expected 4"}},
      {test_data("bad_poses/empty_poses.json"), {"at least two poses", "found 0"}},
      {test_data("bad_poses/two_rotation_forms.json"), {"pose 1", "only one"}},
      {test_data("bad_poses/bad_units.json"), {"units"}},
      {test_data("bad_poses/bad_rational.json"), {"poses[1].t", "zero denominator"}},
      {test_data("bad_poses/bad_header.csv"), {"line 1", "header"}},
      {test_data("bad_poses/short_row.csv"), {"line 3", "pose 1", "expected 8"}},
      {test_data("bad_poses/not_number.csv"), {"line 3", "'x'", "not a number"}},
      {test_data("bad_poses/zero_quaternion.csv"), {"pose 1", "zero quaternion"}},
      {test_data("bad_poses/does_not_exist.json"), {"does_not_exist.json", "cannot open"}},
  };
  for (const auto& c : cases) {
    std::vector<std::string> needles = c.needles;
    needles.push_back(c.file);  // every message names the file
    try {
      io::read_poses(c.file);
      ADD_FAILURE() << c.file << " was accepted";
    } catch (const Error& e) {
      EXPECT_EQ(e.code(), Errc::invalid_input) << c.file;
      for (const auto& n : needles)
        EXPECT_NE(std::string(e.what()).find(n), std::string::npos) << e.what() << " lacks " << n;
    }
  }
}

}  // namespace
}  // namespace qmotion::test
