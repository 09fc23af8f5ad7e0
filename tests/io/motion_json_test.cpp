// tests/io/motion_json_test.cpp mirrors io/motion_json.hpp
#include <tbb/task_arena.h>
#include <unistd.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <qmotion/api/interpolate.hpp>
#ifdef QMOTION_WITH_CGAL
#include <qmotion/io/exact_number.hpp>
#endif
#include <qmotion/io/motion_json.hpp>
#include <qmotion/io/poses.hpp>
#include <qmotion/io/qspline_file.hpp>
#include <random>
#include <sstream>

#include "io_test_util.hpp"

namespace qmotion::test {
namespace {

const std::string kExamples = QMOTION_EXAMPLES;

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
#ifdef QMOTION_WITH_CGAL
  // Exactly: the Plucker residual of the exact reading is zero.
  EXPECT_EQ(kernel::plucker_residual(
                io::to_motion_exact(io::read_motion(kExamples + "/motions/bspline_tr.json"))),
            kernel::Rational(0));
#endif
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
#ifdef QMOTION_WITH_CGAL
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
#endif
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
    const std::string path = test_data("bad_motions/") + name;
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
  for (const auto& e : std::filesystem::directory_iterator(test_data("motions_v1")))
    out.emplace_back(e.path().string(), io::read_text_file(e.path().string()));
  qmotion::InterpolateOptions opt;
  opt.form = "bspline";
  const auto m = qmotion::interpolate(io::read_poses(test_data("helix_10.json")), opt);
  out.emplace_back("interpolated.json", m.text());
  out.emplace_back("interpolated_tree.json", m.document().dump(1));
  return out;
}

TEST(MotionJson, StreamedTextIsTheTreesDocumentAndReadsBackBitForBit) {
  // Every rotation form as given, a 20-digit t and a "p/q" kept as text, a name to escape.
  const std::string mixed = R"({"units": "in", "poses": [
    {"t": 0, "position": [0, 0, 0], "rotation": {"matrix": [[1,0,0],[0,1,0],[0,0,1]]}},
    {"t": 0.33333333333333333333, "position": [1.5, -0.0, 2e-7],
     "rotation": {"axis_angle": {"axis": [0, 0, 1], "angle_deg": 40}}},
    {"t": "2/3", "position": [3, 1, 0.1], "rotation": {"quaternion": [0.9, 0.1, 0.2, 0.3]}},
    {"t": 1, "position": [4, 2, -1], "rotation": {"quaternion": [1, 0, 0.25, 0]}}]})";
  struct Case {
    std::string poses, form, rotation, translation;
  };
  const std::vector<Case> cases{
      {test_data("poses/five_positions.json"), "bezier", "elliptic", "tr"},
      {test_data("poses/five_positions.json"), "bezier", "affine", "trt"},
      {test_data("poses/screw_three.json"), "bezier", "projective", "minimal"},
      {test_data("poses/helix_40.json"), "bspline", "elliptic", "tr"},
      {test_data("poses/helix_40.json"), "c1", "elliptic", "minimal"},
      {"", "bspline", "elliptic", "minimal"},
      {"", "bezier", "elliptic", "trt"}};
  for (const auto& c : cases) {
    SCOPED_TRACE(c.poses + " " + c.form + " " + c.rotation + " " + c.translation);
    qmotion::InterpolateOptions o;
    o.form = c.form;
    o.rotation = c.rotation;
    o.translation = c.translation;
    const io::PoseSet set =
        c.poses.empty() ? io::parse_poses_json(mixed, "mixed\t\"poses\"") : io::read_poses(c.poses);
    const qmotion::InterpolatedMotion made = qmotion::interpolate(set, o);
    // nlohmann compares numbers by value: every double of the text reads back bit for bit.
    const std::string text = made.text();
    EXPECT_EQ(nlohmann::json::parse(text), made.document());
    EXPECT_EQ(nlohmann::json::parse(io::motion_json_text(made.motion.rational())),
              io::motion_document(made.motion.rational()));
    // One control point a line.
    const std::size_t rows = made.motion.rational().curve.curve.ctrl().size();
    EXPECT_GE(static_cast<std::size_t>(std::count(text.begin(), text.end(), '\n')), rows);
    // Through the file readers: the same curve, factors and provenance come back.
    const kernel::Motion<double> back = io::to_motion(io::parse_motion_text(text, "streamed"));
    ASSERT_EQ(back.curve.curve.ctrl().size(), rows);
    for (std::size_t i = 0; i < rows; ++i)
      for (int k = 0; k < 8; ++k)
        ASSERT_EQ(back.curve.curve.ctrl()[i][k], made.motion.rational().curve.curve.ctrl()[i][k]);
    EXPECT_EQ(back.curve.curve.knots(), made.motion.rational().curve.curve.knots());
    ASSERT_TRUE(back.factors && back.provenance);
    EXPECT_EQ(back.provenance->parameters, made.motion.rational().provenance->parameters);
    EXPECT_EQ(back.units, set.units);
    EXPECT_EQ(back.factors->rotation.ctrl().size(),
              made.motion.rational().factors->rotation.ctrl().size());
  }
  // A hand-written motion (no method block) streams to its own document.
  const kernel::Motion<double> hand =
      io::load_motion(kExamples + "/motions/bspline_tr.json").rational();
  EXPECT_EQ(nlohmann::json::parse(io::motion_json_text(hand)), io::motion_document(hand));
}

TEST(MotionJson, LongMotionsAreWrittenInBlocksWithTheBytesOfOneCore) {
  // 3000 poses: the control points, the knots and the echoed poses are long enough to be
  // formatted in blocks on every core; the text must be the one-thread text, the file
  // save() streams must be that text, and it must read back to the same motion.
  std::ostringstream os;
  os.precision(17);
  os << R"({"units": "mm", "poses": [)";
  const int n = 3000;
  for (int i = 0; i < n; ++i) {
    const double t = double(i) / (n - 1), a = t * 20 * M_PI, h = a / 2 + 0.3 * std::sin(7 * t);
    os << (i ? "," : "") << R"({"position": [)" << 60 * std::cos(a) << ", " << 60 * std::sin(a)
       << ", " << 400 * t << R"(], "rotation": {"quaternion": [)" << std::cos(h / 2) << ", "
       << std::sin(h / 2) * 0.6 << ", 0, " << std::sin(h / 2) * 0.8 << "]}}";
  }
  os << "]}";
  qmotion::InterpolateOptions o;
  o.form = "bspline";
  const qmotion::InterpolatedMotion made =
      qmotion::interpolate(io::parse_poses_json(os.str(), "helix"), o);
  const std::string text = made.text();
  tbb::task_arena one(1);
  EXPECT_TRUE(one.execute([&] { return made.text(); }) == text);
  namespace fs = std::filesystem;
  const fs::path d = fs::temp_directory_path() / ("qmotion_mblocks_" + std::to_string(::getpid()));
  fs::create_directories(d);
  made.save((d / "m.json").string());
  EXPECT_TRUE(io::read_text_file((d / "m.json").string()) == text);
  io::save_motion(made.motion.rational(), (d / "plain.json").string());
  EXPECT_TRUE(io::read_text_file((d / "plain.json").string()) ==
              io::motion_json_text(made.motion.rational()));
  fs::remove_all(d);
  EXPECT_EQ(nlohmann::json::parse(text), made.document());
  const kernel::Motion<double> back = io::to_motion(io::parse_motion_text(text, "long"));
  EXPECT_EQ(back.curve.curve.ctrl(), made.motion.rational().curve.curve.ctrl());
  EXPECT_EQ(back.curve.curve.knots(), made.motion.rational().curve.curve.knots());
  const auto poses = io::recorded_input_poses(io::parse_motion_text(text, "long"));
  ASSERT_TRUE(poses);
  ASSERT_EQ(poses->poses.size(), std::size_t(n));
  EXPECT_EQ(poses->poses.back().position[0].value, made.input.poses.back().position[0].value);
}

#ifdef QMOTION_WITH_CGAL
TEST(MotionJson, ControlPointsReadLeanKeepTheirExactDecimals) {
  // The fast reader keeps no text for a number written as its shortest round-trip text;
  // exact mode still reads the decimal written, not the double nearest it.
  const std::string text = R"({"type": "q-motion", "basis": "bezier", "degree": 1,
    "param_range": [0, 1], "control_points": [[1, 0, 0, 0, 0, 0.1, -0.0, 2.5e-300],
                                              [1, 0, 0, 0, 0, 0.10000000000000001, 0, 1]]})";
  const auto f = io::parse_motion_fast(text, "lean.json");
  ASSERT_TRUE(f);
  EXPECT_TRUE(f->ctrl[0][5].text.empty());
  EXPECT_EQ(f->ctrl[0][5].source(), "0.1");
  EXPECT_EQ(f->ctrl[0][6].source(), "-0.0");  // "-0" would be another number's text
  EXPECT_EQ(f->ctrl[1][5].text, "0.10000000000000001");
  EXPECT_EQ(f->ctrl[1][5].value, 0.1);
#ifdef QMOTION_WITH_CGAL
  const auto exact = io::to_motion_exact(*f);
  EXPECT_EQ(exact.curve.ctrl()[0][5], kernel::Rational(1) / kernel::Rational(10));
  EXPECT_EQ(exact.curve.ctrl()[1][5], io::exact_from_text("10000000000000001/100000000000000000"));
  EXPECT_EQ(exact.curve.ctrl()[0][7] * io::exact_from_text("4e300"), kernel::Rational(10));
#endif
}
#endif

/// The fast reader reads no key with a parser: a key JSON forbids (a control character,
/// bytes that are not UTF-8) leaves the file to the full reader, which refuses it, as it
/// refuses it inside a member (found by fuzz_nurbs through the shared member scanner).
TEST(MotionJson, AKeyJsonForbidsIsLeftToTheFullReader) {
  const std::string good = R"({"type": "q-motion", "basis": "bezier", "degree": 1,
    "param_range": [0, 1], "control_points": [[1, 0, 0, 0, 0, 0, 0, 0], [1, 0, 0, 0, 0, 0, 0, 1]],
    "note": 1})";
  ASSERT_TRUE(io::parse_motion_fast(good, "good.json"));
  for (const std::string& bad :
       {std::string("no\x01te"), std::string("no\xfete"), std::string("no\0te", 5)}) {
    std::string text = good;
    text.replace(text.find("note"), 4, bad);
    EXPECT_FALSE(io::parse_motion_fast(text, "bad.json"));
    EXPECT_TRUE(
        throws_error([&] { io::parse_json(text, "bad.json"); }, Errc::invalid_input, {"bad.json"}));
  }
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
    // The method block, its input poses read straight into a pose set by the fast reader.
    nlohmann::json am = a->method, bm = b.method;
    if (bm.is_object())
      for (const char* key : {"input_poses", "rotation_control_points",
                              "translation_control_points", "translation2_control_points"})
        bm.erase(key);
    EXPECT_EQ(am, bm) << name;
    // The factors' control points read as rows, without a tree: the same factors, bit for bit.
    const auto af = io::to_motion(*a).factors, bf = io::to_motion(b).factors;
    ASSERT_EQ(af.has_value(), bf.has_value()) << name;
    if (af) {
      EXPECT_FALSE(a->factor_rows.empty()) << name;
      EXPECT_EQ(af->method, bf->method) << name;
      EXPECT_TRUE(af->rotation.ctrl() == bf->rotation.ctrl()) << name;
      EXPECT_EQ(af->rotation.knots(), bf->rotation.knots()) << name;
      EXPECT_EQ(af->translation.ctrl(), bf->translation.ctrl()) << name;
      EXPECT_EQ(af->translation.knots(), bf->translation.knots()) << name;
      ASSERT_EQ(af->translation2.has_value(), bf->translation2.has_value()) << name;
      if (af->translation2) {
        EXPECT_EQ(af->translation2->ctrl(), bf->translation2->ctrl()) << name;
      }
    }
    EXPECT_EQ(a->input_poses.has_value(), b.method.is_object() && b.method.contains("input_poses"))
        << name;
    const auto ap = io::recorded_input_poses(*a), bp = io::recorded_input_poses(b);
    ASSERT_EQ(ap.has_value(), bp.has_value()) << name;
    if (ap) {
      EXPECT_EQ(ap->units, bp->units) << name;
      const auto x = io::to_poses_double(*ap), y = io::to_poses_double(*bp);
      ASSERT_EQ(x.size(), y.size()) << name;
      for (std::size_t i = 0; i < x.size(); ++i) {
        EXPECT_EQ(x[i].position, y[i].position) << name << " pose " << i;
        EXPECT_TRUE(x[i].rotation == y[i].rotation) << name << " pose " << i;
        EXPECT_EQ(x[i].t, y[i].t) << name << " pose " << i;
      }
    }
    ASSERT_EQ(a->ctrl.size(), b.ctrl.size()) << name;
    ASSERT_EQ(a->knots.size(), b.knots.size()) << name;
    for (std::size_t i = 0; i < b.ctrl.size(); ++i)
      for (std::size_t k = 0; k < 8; ++k) {
        EXPECT_EQ(a->ctrl[i][k].source(), b.ctrl[i][k].source()) << name << " " << i << " " << k;
        EXPECT_EQ(a->ctrl[i][k].value, b.ctrl[i][k].value) << name << " " << i << " " << k;
      }
    for (std::size_t i = 0; i < b.knots.size(); ++i) {
      EXPECT_EQ(a->knots[i].source(), b.knots[i].source()) << name;
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

/// A cubic B-spline motion text of n control points whose numbers take the forms `form(i, k)`
/// gives, rows separated by `sep`.
template <typename Form>
std::string spline_text(std::size_t n, const Form& form, const std::string& sep = ",\n  ") {
  const std::string last = std::to_string(n - 3);
  std::string t = R"({"type": "q-motion", "basis": "bspline", "degree": 3, "param_range": [0, )" +
                  last + "],\n\"knots\": [0, 0, 0";
  for (std::size_t i = 0; i <= n - 3; ++i) t += ", " + std::to_string(i);
  t += ", " + last + ", " + last + ", " + last + "],\n\"control_points\": [";
  for (std::size_t i = 0; i < n; ++i) {
    t += (i ? sep : std::string()) + "[";
    for (std::size_t k = 0; k < 8; ++k) t += (k ? ", " : "") + form(i, k);
    t += "]";
  }
  return t + "]}";
}

void expect_same_control_points(const io::MotionFile& a, const io::MotionFile& b,
                                const std::string& what) {
  ASSERT_EQ(a.ctrl.size(), b.ctrl.size()) << what;
  for (std::size_t i = 0; i < b.ctrl.size(); ++i)
    for (std::size_t k = 0; k < 8; ++k) {
      ASSERT_EQ(a.ctrl[i][k].source(), b.ctrl[i][k].source()) << what << " " << i << " " << k;
      ASSERT_EQ(std::signbit(a.ctrl[i][k].value), std::signbit(b.ctrl[i][k].value)) << what;
      ASSERT_EQ(a.ctrl[i][k].value, b.ctrl[i][k].value) << what << " " << i << " " << k;
    }
}

TEST(MotionJson, TheRowScannerReadsEveryNumberFormAsTheDomReaderOnEveryCore) {
  // The fast reader cuts long control point arrays at row ends and reads the parts on every
  // core with a scanner of its own; whatever it reads must be what the DOM reader reads, and
  // what it declines (a numeric string, a big integer) simdjson reads instead.
  const std::vector<std::string> forms{"0",
                                       "-0",
                                       "1",
                                       "-12",
                                       "0.1",
                                       "-0.0",
                                       "1E+2",
                                       "2.50e-3",
                                       "0.10000000000000001",
                                       "123456789012345678",
                                       "-98765432109876543",
                                       "3.141592653589793",
                                       "1e-300",
                                       "7.0",
                                       "0.30000000000000004",
                                       "-1.5E-7",
                                       "2.2250738585072014e-308",
                                       "1.7976931348623157e308"};
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1e3, 1e3);
  std::vector<std::string> shortest;
  for (int i = 0; i < 997; ++i) {
    char b[32];
    shortest.emplace_back(b, std::to_chars(b, b + 32, u(rng)).ptr);
  }
  const auto mixed = [&](std::size_t i, std::size_t k) {
    const std::size_t j = i * 8 + k;
    return j % 3 == 0 ? forms[j % forms.size()] : shortest[j % shortest.size()];
  };
  struct Case {
    std::string name, text;
  };
  const std::size_t n = 6000;  // about 0.8 MB of rows: a dozen parts
  const std::vector<Case> cases{
      {"mixed", spline_text(n, mixed)},
      {"one line", spline_text(n, mixed, ",")},
      {"spaced", spline_text(n, mixed, " \t,\r\n\n ")},
      {"a numeric string", spline_text(n,
                                       [&](std::size_t i, std::size_t k) {
                                         return i == n / 2 && k == 3 ? std::string("\"0.25\"")
                                                                     : mixed(i, k);
                                       })},
      {"a 19-digit integer", spline_text(n,
                                         [&](std::size_t i, std::size_t k) {
                                           return i == n - 1 && k == 0
                                                      ? std::string("1234567890123456789")
                                                      : mixed(i, k);
                                         })},
      {"short", spline_text(5, mixed)}};
  for (const auto& c : cases) {
    const io::MotionFile dom = io::parse_motion(io::parse_json(c.text, c.name, "method"), c.name);
    const auto fast = io::parse_motion_fast(c.text, c.name);
    ASSERT_TRUE(fast.has_value()) << c.name;
    expect_same_control_points(*fast, dom, c.name);
    tbb::task_arena one(1);
    one.execute([&] {
      const auto single = io::parse_motion_fast(c.text, c.name);
      ASSERT_TRUE(single.has_value()) << c.name;
      expect_same_control_points(*single, dom, c.name + " on one core");
    });
  }
  // Bad rows are refused (by the DOM reader's words) wherever the scanner meets them.
  const auto bad = [&](std::size_t row, const std::string& number) {
    return spline_text(
        n, [&](std::size_t i, std::size_t k) { return i == row && k == 4 ? number : mixed(i, k); });
  };
  for (const auto& [what, text] : std::vector<std::pair<std::string, std::string>>{
           {"leading zero", bad(n / 3, "01")},
           {"bare point", bad(2, "1.")},
           {"plus sign", bad(n - 2, "+1")},
           {"missing number", bad(n / 2, "")},
           {"nested array", bad(n / 4, "[1]")},
           {"infinite", bad(7, "1e400")},
           {"seven numbers", spline_text(n, [&](std::size_t i, std::size_t k) {
              return i == n / 5 && k == 7 ? std::string("1], [2") : mixed(i, k);
            })}}) {
    bool refused = false;
    try {
      (void)io::parse_motion_text(text, what);
    } catch (const Error& e) {
      refused = true;
      EXPECT_EQ(e.code(), Errc::invalid_input) << what;
      EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
    }
    EXPECT_TRUE(refused) << what;
  }
}

TEST(MotionJson, BadMotionsGetTheDomReadersMessageThroughTheFastReader) {
  int refused = 0;
  for (const auto& e : std::filesystem::directory_iterator(test_data("bad_motions"))) {
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

// qmotion never writes a motion file it would refuse to read: a degree above the limit is
// refused on the way out with the reader's message, and no file is left.
TEST(MotionJson, AMotionAboveTheReadersLimitsIsNotWritten) {
  const int n = io::kMaxMotionDegree + 1;
  std::vector<double> knots(static_cast<std::size_t>(n + 1), 0.0);
  knots.insert(knots.end(), static_cast<std::size_t>(n + 1), 1.0);
  using DQ = kernel::DualQuaternion<double>;
  std::vector<DQ> ctrl(static_cast<std::size_t>(n + 1), DQ::translation(Eigen::Vector3d(1, 2, 3)));
  const kernel::Motion<double> m(kernel::QMotion<double>{
      kernel::Basis::bezier, kernel::BSpline<DQ>::make(n, std::move(knots), std::move(ctrl))});
  const auto dir = std::filesystem::temp_directory_path() / "qmotion_motion_limit";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const std::string path = (dir / "m.json").string();
  std::string written;
  try {
    io::write_motion_json(path, m);
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), Errc::invalid_input);
    written = e.what();
  }
  EXPECT_TRUE(std::filesystem::is_empty(dir));
  // The same text, with the degree edited, is what the reader refuses.
  std::string text = io::motion_json_text(kernel::Motion<double>(kernel::QMotion<double>{
      kernel::Basis::bezier, kernel::BSpline<DQ>::from_bezier(kernel::Bernstein<DQ>(
                                 std::vector<DQ>(3, DQ::translation(Eigen::Vector3d(1, 2, 3)))))}));
  const std::string degree2 = "\"degree\": 2";
  const auto at = text.find(degree2);
  ASSERT_NE(at, std::string::npos) << text;
  text.replace(at, degree2.size(), "\"degree\": " + std::to_string(n));
  std::string read;
  try {
    io::parse_motion_text(text, path);
  } catch (const Error& e) {
    read = e.what();
  }
  EXPECT_NE(written, "");
  EXPECT_EQ(written, read);
}

TEST(MotionJson, TheMemberScannerFindsEachValueWhateverItsStringsHold) {
  // The fast reader cuts the file into members by brackets and quotes alone; strings holding
  // brackets, quotes and backslashes, nesting and odd spacing must not move a cut.
  const std::string head = R"({ "type" :"q-motion" , "basis":
    "bezier","degree" :1,"param_range":[0,1] ,
    "control_points": [[1,0,0,0,0,0,0,0],[1,0,0,0,0,1,0,0]])";
  const std::string method =
      R"(, "method": {"note": "] } \" [ { \\", "deep": {"a": [1, {"b": "]}"}, []]},
         "form": "bezier", "empty": "", "slash": "a\\\\"}, "extra": ["{", "\\\"]"]})";
  const std::string text = head + method;
  const auto fast = io::parse_motion_fast(text, "s.json");
  ASSERT_TRUE(fast.has_value());
  const io::MotionFile dom = io::parse_motion(io::parse_json(text, "s.json", "method"), "s.json");
  EXPECT_EQ(fast->method, dom.method);
  EXPECT_EQ(fast->method["note"], "] } \" [ { \\");
  EXPECT_EQ(fast->method["slash"], "a\\\\");
  EXPECT_EQ(fast->ctrl.size(), 2u);
  EXPECT_EQ(fast->degree, 1);

  // A key with an escape: declined by the scanner, read by the full reader.
  const std::string escaped = head + R"(, "n\u006fte": 1})";
  EXPECT_FALSE(io::parse_motion_fast(escaped, "e.json").has_value());
  EXPECT_EQ(io::parse_motion_text(escaped, "e.json").ctrl.size(), 2u);

  // Broken structure the scanner's cuts alone would pass: each is refused by both readers.
  for (const std::string& bad :
       {head + R"(, "note": [1, 2}})", head + R"(, "note": "open})", head,
        head + R"(, "note": 1 2})", head + R"(, : 1})", head + R"(,})", head + "}}"}) {
    EXPECT_FALSE(io::parse_motion_fast(bad, "b.json").has_value()) << bad;
    EXPECT_TRUE(throws_error([&] { io::parse_motion_text(bad, "b.json"); }, Errc::invalid_input,
                             {"b.json"}))
        << bad;
  }
}

}  // namespace
}  // namespace qmotion::test
