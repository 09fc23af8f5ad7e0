// Tests of <qmotion/render/view.hpp> and <qmotion/api/view.hpp>: the page's data says what
// the motion file says (curve, method, poses), its text cannot end the page's scripts, and
// refusals leave no file. What the page does in a browser is interop.viewer's (tests/interop).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <qmotion/api/interpolate.hpp>
#include <qmotion/api/qspline.hpp>
#include <qmotion/api/view.hpp>
#include <qmotion/io/motion_json.hpp>
#include <qmotion/io/poses.hpp>
#include <qmotion/render/view.hpp>
#include <sstream>
#include <string>

#include "io_test_util.hpp"

namespace qmotion {
namespace {

using json = nlohmann::json;
using test::test_data;

/// The text of the page's element that opens with `open` (up to its </script>).
std::string script_text(const std::string& page, const std::string& open) {
  const auto at = page.find(open);
  if (at == std::string::npos) return {};
  const auto begin = at + open.size();
  return page.substr(begin, page.find("</script>", begin) - begin);
}

std::string read(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

InterpolatedMotion five(const InterpolateOptions& o) {
  return interpolate(io::read_poses(test_data("poses/five_positions.json")), o);
}

TEST(ViewData, RecordsTheMethodAndThePosesOfABezierMotion) {
  InterpolateOptions o;
  o.rotation = "affine";
  o.translation = "minimal";
  const auto m = five(o);
  const json d = view_data(m.motion, {});
  EXPECT_EQ(d["method"]["form"], "bezier");
  EXPECT_EQ(d["method"]["rotation"], "affine");
  EXPECT_EQ(d["method"]["translation"], "minimal");
  const auto& input = io::read_poses(test_data("poses/five_positions.json")).poses;
  ASSERT_EQ(d["poses"].size(), input.size());
  const auto& p = m.motion.provenance()->poses;
  for (std::size_t i = 0; i < input.size(); ++i) {
    for (int k = 0; k < 3; ++k)
      EXPECT_EQ(d["poses"][i]["position"][k].get<double>(), p[i].position(k));
    const json q = {p[i].rotation.w(), p[i].rotation.x(), p[i].rotation.y(), p[i].rotation.z()};
    EXPECT_EQ(d["poses"][i]["quaternion"], q);
  }
  // The curve is the file's: the same control points, in the same order.
  const json file = m.document();
  EXPECT_EQ(d["motion"]["degree"], file["degree"]);
  ASSERT_EQ(d["motion"]["control_points"].size(), file["control_points"].size());
  for (std::size_t i = 0; i < file["control_points"].size(); ++i)
    for (int j = 0; j < 8; ++j)
      EXPECT_DOUBLE_EQ(d["motion"]["control_points"][i][j].get<double>(),
                       file["control_points"][i][j].get<double>());
}

TEST(ViewData, RecordsTheDegreesOfASplineMotion) {
  InterpolateOptions o;
  o.form = "bspline";
  o.degree = 2;
  o.translation_degree = 4;
  const json d = view_data(five(o).motion, {});
  EXPECT_EQ(d["method"]["form"], "bspline");
  EXPECT_EQ(d["method"]["k"], 2);
  EXPECT_EQ(d["method"]["l"], 4);
}

TEST(ViewData, AHandWrittenMotionIsShownNotEdited) {
  // The same curve without its method: the key poses are the breakpoints', no method.
  json doc = five({}).document();
  doc.erase("method");
  const Motion m(io::to_motion(io::parse_motion(doc, "hand.json")));
  const json d = view_data(m, {});
  EXPECT_TRUE(d["method"].is_null());
  EXPECT_EQ(d["poses"].size(), 2u);         // a Bezier motion: its two ends
  if (!render::viewer_available()) return;  // the data above need no page; the file does
  const View v =
      view(m, {test::scratch_path("view", "hand.html").string(), "", "", {}, false, std::nullopt});
  EXPECT_FALSE(v.editable);
}

TEST(ViewData, AQuaternionSplineTravelsAsItsFileHoldsIt) {
  const auto poses = io::read_poses(test_data("poses/five_positions.json"));
  for (const char* scheme : {"kks", "quintic", "quartic"}) {
    const Motion m = qspline(poses, {scheme, "", ""}).motion;
    const auto& s = m.spline();
    const json d = view_data(m, {});
    EXPECT_EQ(d["motion"]["kind"], "quaternion-spline");
    EXPECT_EQ(d["motion"]["scheme"], scheme);
    EXPECT_EQ(d["motion"]["knots"].get<std::vector<double>>(), s.knots);
    EXPECT_EQ(d["motion"]["control_quaternions"].size(), s.ctrl.size());  // KKS's solution
    // Edited, it is fitted again at its knots with its scheme and tensions.
    EXPECT_EQ(d["method"]["scheme"], scheme);
    EXPECT_EQ(d["method"]["param"], "given");
    EXPECT_EQ(d["method"]["tension"].get<std::vector<double>>(), s.tension);
    ASSERT_EQ(d["poses"].size(), s.keys.size());
    for (std::size_t i = 0; i < s.keys.size(); ++i) {
      EXPECT_EQ(d["poses"][i]["t"].get<double>(), s.knots[i]);
      EXPECT_EQ(d["poses"][i]["quaternion"][0].get<double>(), s.keys[i].w());
      EXPECT_EQ(d["poses"][i]["position"][2].get<double>(), s.positions[i].z());
    }
  }
}

TEST(ViewData, CarriesProfileBodyAndPoints) {
  ViewOptions o;
  o.profile = "rect:4,2";
  o.body = "box:1,2,3";
  o.points = {Eigen::Vector3d(1, 2, 3)};
  const json d = view_data(five({}).motion, o);
  EXPECT_EQ(d["profile"].size(), 4u);           // four straight edges
  EXPECT_EQ(d["body"]["indices"].size(), 36u);  // 12 triangles
  EXPECT_EQ(d["points"], json::array({json::array({1.0, 2.0, 3.0})}));
}

TEST(ViewPage, TheDataCannotEndItsScript) {
  if (!render::viewer_available()) GTEST_SKIP() << "built with -DQMOTION_VIEWER=OFF";
  const json data = {{"name", "</script><script>alert(1)</script><!--"}, {"n", 1.5}};
  const std::string page = render::viewer_page("a <b> & \"c\"", "s </script>", data);
  EXPECT_EQ(page.find("<script>alert"), std::string::npos);
  const std::string text =
      script_text(page, "<script type=\"application/json\" id=\"qmotion-data\">");
  ASSERT_FALSE(text.empty());
  EXPECT_EQ(json::parse(text), data);
  EXPECT_NE(page.find("<title>a &lt;b&gt; &amp; &quot;c&quot;</title>"), std::string::npos);
  EXPECT_EQ(page.find("@QMOTION_"), std::string::npos);  // every mark filled
}

TEST(ViewPage, IsSelfContained) {
  if (!render::viewer_available()) GTEST_SKIP() << "built with -DQMOTION_VIEWER=OFF";
  const auto out = test::scratch_path("view", "five.html");
  const View v = view(five({}).motion, {out.string(), "circle:3", "", {}, false, std::nullopt});
  const std::string page = read(out);
  EXPECT_EQ(v.bytes, page.size());
  EXPECT_TRUE(v.editable);
  // No address the page could fetch: scripts are inline, modules are data: URLs.
  for (const char* fetch : {"http:", "https:", "src=\"", "href=\"", "//cdn", "import("})
    EXPECT_EQ(page.find(fetch), std::string::npos) << fetch;
  EXPECT_NE(page.find("default-src 'none'"), std::string::npos);  // and its policy says so
  // The WebAssembly module inside is the one the build made, whole.
  const std::string wasm =
      script_text(page, "<script type=\"application/octet-stream\" id=\"qmotion-wasm\">");
  EXPECT_EQ(wasm.size(), 4 * ((v.wasm_bytes + 2) / 3));  // base64
  EXPECT_GT(v.wasm_bytes, 10000u);
  EXPECT_LT(v.wasm_bytes, 4u << 20);
}

TEST(ViewRefusals, LeaveNoFile) {
  const auto m = five({}).motion;
  const auto out = test::scratch_path("view", "refused.html");
  std::filesystem::remove(out);
  EXPECT_TRUE(test::throws_error(
      [&] {
        view(m, {out.string() + ".txt", "", "", {}, false, std::nullopt});
      },
      Errc::invalid_input, {"view writes an .html page"}));
  EXPECT_TRUE(test::throws_error(
      [&] {
        view(m, {out.string(), "circle:0", "", {}, false, std::nullopt});
      },
      Errc::invalid_input, {"circle:0"}));
  EXPECT_TRUE(test::throws_error(
      [&] {
        view(m, {out.string(), "", "cutter:bull,4,3,10", {}, false, std::nullopt});
      },
      Errc::invalid_input, {"cutter:bull,4,3,10"}));
  EXPECT_TRUE(test::throws_error(
      [&] {
        view(m, {out.string(), "", "", {Eigen::Vector3d(0, NAN, 0)}, false, std::nullopt});
      },
      Errc::invalid_input, {"--point"}));
  EXPECT_FALSE(std::filesystem::exists(out));
  EXPECT_FALSE(std::filesystem::exists(out.string() + ".txt"));
}

}  // namespace
}  // namespace qmotion
