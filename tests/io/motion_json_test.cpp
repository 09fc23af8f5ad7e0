// tests/io/motion_json_test.cpp mirrors io/motion_json.hpp
#include <filesystem>
#include <qmotion/io/exact_number.hpp>
#include <qmotion/io/interpolate.hpp>
#include <qmotion/io/motion_json.hpp>
#include <qmotion/io/poses.hpp>

#include "io_test_util.hpp"

namespace qmotion::test {
namespace {

const std::string kExamples = QMOTION_EXAMPLES;
const std::string kData = QMOTION_TEST_DATA;

TEST(MotionJson, HandWrittenExamplesAreRigidAndFollowTheirTranslation) {
  // Both examples are (2 + eps p(t)) * r(t): the origin follows p(t) exactly.
  const auto bez = io::to_motion_double(io::read_motion(kExamples + "/motions/bezier_tr.json"));
  EXPECT_EQ(bez.basis, kernel::Basis::bezier);
  EXPECT_EQ(bez.degree(), 2);
  EXPECT_EQ(kernel::plucker_residual(bez), 0.0);
  for (double t : {0.0, 0.3, 0.5, 1.0})
    EXPECT_NEAR(
        (kernel::translation_vector(kernel::evaluate(bez, t)) - Eigen::Vector3d(10 * t, 20 * t, 0))
            .norm(),
        0, 1e-13);
  const auto bsp = io::to_motion_double(io::read_motion(kExamples + "/motions/bspline_tr.json"));
  EXPECT_EQ(bsp.basis, kernel::Basis::bspline);
  EXPECT_EQ(bsp.segments(), 2);
  for (double t : {0.0, 0.25, 0.5, 0.75, 1.0}) {
    const Eigen::Vector3d p =
        t <= 0.5 ? Eigen::Vector3d(20 * t, 0, 0) : Eigen::Vector3d(10, 20 * (t - 0.5), 0);
    EXPECT_NEAR((kernel::translation_vector(kernel::evaluate(bsp, t)) - p).norm(), 0, 1e-13) << t;
  }
  // Exactly: the Plucker residual of the exact reading is zero.
  EXPECT_EQ(kernel::plucker_residual(
                io::to_motion_exact(io::read_motion(kExamples + "/motions/bspline_tr.json"))),
            kernel::Rational(0));
}

TEST(MotionJson, RoundTripDoubleAndExact) {
  for (const std::string f : {"/motions/bezier_tr.json", "/motions/bspline_tr.json"}) {
    const auto file = io::read_motion(kExamples + f);
    const auto m = io::to_motion_double(file);
    const auto back = io::to_motion_double(
        io::parse_motion(io::parse_json(io::motion_to_json(m, file.method).dump(), "rt"), "rt"));
    EXPECT_EQ(back.curve.knots(), m.curve.knots());
    for (std::size_t i = 0; i < m.curve.ctrl().size(); ++i)
      EXPECT_EQ(back.curve.ctrl()[i], m.curve.ctrl()[i]);
    // Exact: non-dyadic rationals survive as "p/q" strings.
    auto e = io::to_motion_exact(file);
    auto ctrl = e.curve.ctrl();
    ctrl[1] = ctrl[1] * (kernel::Rational(1) / kernel::Rational(3));
    const kernel::QMotion<kernel::Rational> e3{
        e.basis, kernel::BSpline<kernel::DualQuaternion<kernel::Rational>>::make(
                     e.degree(), e.curve.knots(), ctrl)};
    const auto eback = io::to_motion_exact(
        io::parse_motion(io::parse_json(io::motion_to_json(e3, nullptr).dump(), "rt"), "rt"));
    for (std::size_t i = 0; i < ctrl.size(); ++i) EXPECT_EQ(eback.curve.ctrl()[i], ctrl[i]);
  }
}

TEST(MotionJson, TooManyControlPointsAreRefusedBeforeTheyAreRead) {
  nlohmann::json doc{
      {"type", "q-motion"}, {"basis", "bspline"}, {"degree", 3}, {"param_range", {0, 1}}};
  doc["control_points"] = nlohmann::json::array();
  for (std::size_t i = 0; i <= io::kMaxMotionControlPoints; ++i) doc["control_points"].push_back(0);
  EXPECT_TRUE(throws_error([&] { io::parse_motion(doc, "huge.json"); }, Errc::invalid_input,
                           {"huge.json", "control_points", "more than 1000000"}));
}

TEST(MotionJson, EveryBadMotionIsRefusedWithItsReason) {
  const std::vector<std::pair<std::string, std::vector<std::string>>> cases = {
      {"wrong_type.json", {"type"}},
      {"bad_basis.json", {"basis"}},
      {"negative_degree.json", {"degree"}},
      {"wrong_count.json", {"needs 4 control points"}},
      {"seven_numbers.json", {"control_points[1]", "expected 8"}},
      {"range_reversed.json", {"param_range"}},
      {"range_mismatch.json", {"param_range", "knot"}},
      {"zero_real_part.json", {"rotational"}},
      {"bspline_no_knots.json", {"knots"}},
      {"bspline_bad_knots.json", {"knots", "decrease"}},
      {"missing_control_points.json", {"control_points"}},
      {"nan_string.json", {"control_points[1][3]", "finite"}},
      {"quaternion_spline.json", {"quaternion-spline"}},
  };
  for (const auto& [name, needles] : cases) {
    const std::string path = kData + "/bad_motions/" + name;
    try {
      io::read_motion(path);
      ADD_FAILURE() << name << " was accepted";
    } catch (const Error& e) {
      EXPECT_EQ(e.code(), Errc::invalid_input) << name;
      EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
      for (const auto& n : needles)
        EXPECT_NE(std::string(e.what()).find(n), std::string::npos) << e.what() << " lacks " << n;
    }
  }
}

/// The motion files both readers must agree on: the examples, the versioned samples, and
/// an interpolated B-spline motion written by the library (method block and all).
std::vector<std::pair<std::string, std::string>> motion_texts() {
  std::vector<std::pair<std::string, std::string>> out;
  for (const auto& f :
       {kExamples + "/motions/bezier_tr.json", kExamples + "/motions/bspline_tr.json"})
    out.emplace_back(f, io::read_text_file(f));
  for (const auto& e : std::filesystem::directory_iterator(kData + "/motions_v1"))
    out.emplace_back(e.path().string(), io::read_text_file(e.path().string()));
  io::InterpolateOptions opt;
  opt.form = "bspline";
  const auto m = io::interpolate(io::read_poses(kData + "/helix_10.json"), opt);
  out.emplace_back("interpolated.json", m.document.dump(1));
  return out;
}

TEST(MotionJson, TheFastReaderReadsWhatTheDomReaderReads) {
  int fast = 0;
  for (const auto& [name, text] : motion_texts()) {
    const auto a = io::parse_motion_fast(text, name);
    const io::MotionFile b = io::parse_motion(io::parse_json(text, name, "method"), name);
    if (!a) {
      // Only exact "p/q" files need the DOM reader.
      EXPECT_NE(text.find('/'), std::string::npos) << name << " was left to the DOM reader";
      continue;
    }
    ++fast;
    EXPECT_EQ(a->basis, b.basis) << name;
    EXPECT_EQ(a->degree, b.degree) << name;
    EXPECT_EQ(a->units, b.units) << name;
    EXPECT_EQ(a->method, b.method) << name;
    ASSERT_EQ(a->ctrl.size(), b.ctrl.size()) << name;
    ASSERT_EQ(a->knots.size(), b.knots.size()) << name;
    for (std::size_t i = 0; i < b.ctrl.size(); ++i)
      for (std::size_t k = 0; k < 8; ++k) {
        EXPECT_EQ(a->ctrl[i][k].text, b.ctrl[i][k].text) << name << " " << i << " " << k;
        EXPECT_EQ(a->ctrl[i][k].value, b.ctrl[i][k].value) << name << " " << i << " " << k;
      }
    for (std::size_t i = 0; i < b.knots.size(); ++i) {
      EXPECT_EQ(a->knots[i].text, b.knots[i].text) << name;
      EXPECT_EQ(a->knots[i].value, b.knots[i].value) << name;
    }
    for (std::size_t i = 0; i < 2; ++i) EXPECT_EQ(a->range[i].text, b.range[i].text) << name;
    // Without the method block the curve is the same.
    const auto c = io::parse_motion_fast(text, name, /*with_method=*/false);
    ASSERT_TRUE(c.has_value()) << name;
    EXPECT_TRUE(c->method.is_null()) << name;
    EXPECT_EQ(io::to_motion_double(*c).curve.ctrl(), io::to_motion_double(b).curve.ctrl()) << name;
  }
  EXPECT_GE(fast, 5);  // the fast reader did read the ordinary files
}

TEST(MotionJson, BadMotionsGetTheDomReadersMessageThroughTheFastReader) {
  int refused = 0;
  for (const auto& e : std::filesystem::directory_iterator(kData + "/bad_motions")) {
    const std::string path = e.path().string();
    const std::string text = io::read_text_file(path);
    std::string via_dom, via_file;
    try {
      io::parse_motion(io::parse_json(text, path, "method"), path);
    } catch (const Error& err) {
      via_dom = err.what();
    }
    try {
      io::read_motion(path);  // the fast reader first
    } catch (const Error& err) {
      via_file = err.what();
    }
    EXPECT_EQ(via_file, via_dom) << path;
    refused += !via_dom.empty();
  }
  EXPECT_GE(refused, 12);
}

TEST(MotionJson, TheFastReaderValidatesWhatItDoesNotKeep) {
  const std::string good = R"({"type": "q-motion", "basis": "bezier", "degree": 1,
    "param_range": [0, 1], "control_points": [[1,0,0,0,0,0,0,0],[1,0,0,0,0,1,0,0]])";
  ASSERT_TRUE(io::parse_motion_fast(good + "}", "g.json", false).has_value());
  // Invalid JSON in a block eval skips, in an unknown field, or after the root: refused.
  const std::vector<std::string> bads = {good + R"(, "method": {"form": tru}})",
                                         good + R"(, "note": [1, 01]})", good + "} []",
                                         good + R"(, "method": {"a": 1e999}})"};
  for (const auto& bad : bads) {
    EXPECT_FALSE(io::parse_motion_fast(bad, "b.json", false).has_value()) << bad;
    EXPECT_TRUE(throws_error([&] { io::parse_motion_text(bad, "b.json"); }, Errc::invalid_input,
                             {"b.json"}))
        << bad;
  }
}

}  // namespace
}  // namespace qmotion::test
