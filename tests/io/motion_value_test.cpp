// tests/io/motion_value_test.cpp: the motion value type (kernel/motion_value.hpp) through
// its file (io/motion_json.hpp): every interpolator's Motion survives save and load, files
// written before the type existed still read, malformed method blocks are refused.
#include <filesystem>
#include <qmotion/api/interpolate.hpp>
#ifdef QMOTION_WITH_CGAL
#include <qmotion/io/exact_number.hpp>
#endif
#include <qmotion/io/motion_json.hpp>
#include <qmotion/io/poses.hpp>
#include <qmotion/io/qspline_file.hpp>
#include <qmotion/kernel/interpolation.hpp>
#include <qmotion/kernel/parametrization.hpp>
#include <qmotion/kernel/spline_interpolation.hpp>
#include <qmotion/sweep/surface.hpp>
#include <random>

#include "io_test_util.hpp"

namespace qmotion::test {
namespace {

namespace fs = std::filesystem;
using kernel::Form;
using kernel::Motion;
using kernel::RotationMethod;
using kernel::TranslationMethod;
using V3 = Eigen::Vector3d;

template <typename Coef>
void expect_same_spline(const kernel::BSpline<Coef>& a, const kernel::BSpline<Coef>& b,
                        const std::string& what, double rel_tol = 0) {
  ASSERT_EQ(a.degree(), b.degree()) << what;
  ASSERT_EQ(a.knots(), b.knots()) << what;
  ASSERT_EQ(a.ctrl().size(), b.ctrl().size()) << what;
  const int n = std::is_same_v<Coef, kernel::DualQuaternion<double>> ? 8
                : std::is_same_v<Coef, V3>                           ? 3
                                                                     : 4;
  double scale = 0;  // of the spline's poles
  for (const auto& q : b.ctrl())
    for (int c = 0; c < n; ++c) scale = std::max(scale, std::abs(double(q[c])));
  for (std::size_t i = 0; i < a.ctrl().size(); ++i)
    for (int c = 0; c < n; ++c) {
      const double x = a.ctrl()[i][c], y = b.ctrl()[i][c];
      if (rel_tol == 0) {
        EXPECT_EQ(x, y) << what << " pole " << i;
      } else {
        EXPECT_NEAR(x, y, rel_tol * scale) << what << " pole " << i;
      }
    }
}

/// The method a provenance records.
void expect_method(const kernel::Provenance<double>& p, Form form, RotationMethod rotation,
                   TranslationMethod translation, int k, int l, int l2) {
  EXPECT_EQ(p.form, form);
  EXPECT_EQ(p.rotation, rotation);
  EXPECT_EQ(p.translation, translation);
  EXPECT_EQ(p.rotation_degree, k);
  EXPECT_EQ(p.translation_degree, l);
  EXPECT_EQ(p.translation_degree2, l2);
}

/// Equality of two double motions field by field: bit for bit, or the poles within
/// rel_tol of each spline's largest pole (a computation repeated by a later kernel may round
/// differently).
void expect_same(const Motion<double>& a, const Motion<double>& b, double rel_tol = 0) {
  EXPECT_EQ(a.curve.basis, b.curve.basis);
  expect_same_spline(a.curve.curve, b.curve.curve, "curve", rel_tol);
  EXPECT_EQ(a.units, b.units);
  ASSERT_EQ(a.factors.has_value(), b.factors.has_value());
  if (a.factors) {
    EXPECT_EQ(a.factors->method, b.factors->method);
    expect_same_spline(a.factors->rotation, b.factors->rotation, "Q_rot", rel_tol);
    expect_same_spline(a.factors->translation, b.factors->translation, "translation", rel_tol);
    ASSERT_EQ(a.factors->translation2.has_value(), b.factors->translation2.has_value());
    if (a.factors->translation2)
      expect_same_spline(*a.factors->translation2, *b.factors->translation2, "translation2",
                         rel_tol);
  }
  ASSERT_EQ(a.provenance.has_value(), b.provenance.has_value());
  if (!a.provenance) return;
  const auto &p = *a.provenance, &q = *b.provenance;
  expect_method(p, q.form, q.rotation, q.translation, q.rotation_degree, q.translation_degree,
                q.translation_degree2);
  EXPECT_EQ(p.param, q.param);
  EXPECT_EQ(p.parameters, q.parameters);
  EXPECT_EQ(p.near_inaccessible, q.near_inaccessible);
  // Reading normalises pose quaternions again: an already unit quaternion may move by an
  // ulp, and the residuals (recomputed on reading) by as little.
  ASSERT_EQ(p.residuals.size(), q.residuals.size());
  for (std::size_t i = 0; i < p.residuals.size(); ++i)
    EXPECT_NEAR(p.residuals[i], q.residuals[i], 1e-15) << "pose " << i;
  ASSERT_EQ(p.poses.size(), q.poses.size());
  for (std::size_t i = 0; i < p.poses.size(); ++i) {
    EXPECT_EQ(p.poses[i].position, q.poses[i].position) << "pose " << i;
    for (int c = 0; c < 4; ++c)
      EXPECT_NEAR(p.poses[i].rotation[c], q.poses[i].rotation[c], 4e-16) << "pose " << i;
  }
}

/// A motion document without the numbers reading may move by an ulp (see expect_same).
nlohmann::json stable_part(nlohmann::json doc) {
  if (doc.contains("method")) {
    doc["method"].erase("input_poses");
    doc["method"].erase("max_interpolation_residual");
  }
  return doc;
}

/// Checks the provenance against the motion independently: the curve passes through every
/// recorded pose at its recorded parameter, and the factors multiply to the curve.
void expect_consistent(const Motion<double>& m) {
  ASSERT_TRUE(m.provenance);
  ASSERT_TRUE(m.factors);
  const auto& p = *m.provenance;
  ASSERT_EQ(p.parameters.size(), p.poses.size());
  ASSERT_EQ(p.residuals.size(), p.poses.size());
  for (std::size_t i = 0; i < p.poses.size(); ++i)
    EXPECT_LE(
        kernel::pose_residual(kernel::evaluate(m, p.parameters[i]), p.poses[i].dual_quaternion()),
        1e-10)
        << "pose " << i;
  EXPECT_EQ(p.parameters.front(), m.a());
  EXPECT_EQ(p.parameters.back(), m.b());
  EXPECT_TRUE(kernel::factors_match(*m.factors, m.curve));
  EXPECT_EQ(m.factors->rotation.degree(), p.rotation_degree);
  EXPECT_EQ(m.factors->translation.degree(), p.translation_degree);
}

std::vector<kernel::Pose<double>> poses_of(const std::string& rel) {
  return io::to_poses_double(io::read_poses(test_data(rel)));
}

TEST(MotionValue, EveryInterpolatorsMotionSurvivesSaveAndLoad) {
  const auto five = poses_of("poses/five_positions.json");
  const auto t5 = kernel::parametrize(five, kernel::ParamRule::given);
  const auto helix = poses_of("poses/helix_40.json");
  const auto th = kernel::parametrize(helix, kernel::ParamRule::chordal);
  std::vector<Motion<double>> motions;
  for (auto r : {RotationMethod::elliptic, RotationMethod::affine, RotationMethod::projective})
    for (auto tr : {TranslationMethod::tr, TranslationMethod::trt, TranslationMethod::minimal}) {
      kernel::InterpolationOptions o;
      o.rotation = r;
      o.translation = tr;
      motions.push_back(kernel::interpolate_bezier(five, t5, o));
    }
  for (auto tr : {TranslationMethod::tr, TranslationMethod::minimal}) {
    kernel::SplineOptions o;
    o.translation = tr;
    o.k = 2;
    o.l = 4;
    motions.push_back(kernel::interpolate_bspline(helix, th, o));
    motions.push_back(kernel::interpolate_c1(helix, th, tr));
  }
  int i = 0;
  for (auto& m : motions) {
    SCOPED_TRACE("motion " + std::to_string(i));
    m.units = "cm";
    m.provenance->param = "chordal";
    expect_consistent(m);
    const std::string path =
        scratch_path("motion_value", "m" + std::to_string(i++) + ".json").string();
    io::save_motion(m, path);
    const Motion<double> back = io::load_motion(path).rational();
    EXPECT_EQ(back.name, path);
    expect_same(m, back);
    // Saving what was read writes the same document.
    EXPECT_TRUE(stable_part(io::motion_document(back)) == stable_part(io::motion_document(m)));
  }
  // The kernel records each interpolator's form.
  EXPECT_EQ(motions.front().provenance->form, Form::bezier);
  EXPECT_EQ(motions[9].provenance->form, Form::bspline);
  EXPECT_EQ(motions[10].provenance->form, Form::c1);
  EXPECT_EQ(motions[9].provenance->rotation_degree, 2);
  EXPECT_EQ(motions[9].provenance->translation_degree, 4);
}

TEST(MotionValue, FilesWrittenBeforeTheTypeStillRead) {
  // Written by `qmotion interpolate` before Motion existed (tests/data/motions_v1).
  struct Case {
    std::string file;
    Form form;
    RotationMethod rotation;
    TranslationMethod translation;
    int k, l, l2;
  };
  const std::vector<Case> cases = {
      {"bezier_affine_trt.json", Form::bezier, RotationMethod::affine, TranslationMethod::trt, 4, 3,
       0},
      {"bspline_minimal.json", Form::bspline, RotationMethod::elliptic, TranslationMethod::minimal,
       3, 3, -1},
      {"c1_tr.json", Form::c1, RotationMethod::elliptic, TranslationMethod::tr, 3, 3, -1},
      {"exact_bezier.json", Form::bezier, RotationMethod::elliptic, TranslationMethod::tr, 3, 3,
       -1},
      {"exact_bspline.json", Form::bspline, RotationMethod::elliptic, TranslationMethod::tr, 3, 3,
       -1},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(c.file);
    const std::string path = test_data("motions_v1/") + c.file;
    const Motion<double> m = io::load_motion(path).rational();
    expect_consistent(m);
    const auto& p = *m.provenance;
    expect_method(p, c.form, c.rotation, c.translation, c.k, c.l, c.l2);
    EXPECT_EQ(m.units, "mm");
    // Interpolating the recorded poses at the recorded parameters again gives the curve the
    // file holds (double files; the exact ones were computed in rationals), to rounding: the
    // files were written by an earlier kernel, whose Bezier decomposition took other steps.
    if (c.file.rfind("exact", 0) == 0) continue;
    Motion<double> again = [&] {
      if (p.form == Form::bezier) {
        kernel::InterpolationOptions o;
        o.rotation = p.rotation;
        o.translation = p.translation;
        o.trt_degrees = std::make_pair(p.translation_degree, p.translation_degree2);
        return kernel::interpolate_bezier(p.poses, p.parameters, o);
      }
      if (p.form == Form::c1) return kernel::interpolate_c1(p.poses, p.parameters, p.translation);
      kernel::SplineOptions o;
      o.translation = p.translation;
      return kernel::interpolate_bspline(p.poses, p.parameters, o);
    }();
    again.units = m.units;
    again.provenance->param = p.param;
    expect_same(again, m, 1e-14);
  }
}

#ifdef QMOTION_WITH_CGAL
TEST(MotionValue, ExactMotionsWriteExactDocuments) {
  const auto P = io::to_poses_exact(io::read_poses(test_data("poses/rational_exact.json")));
  std::vector<kernel::Rational> t;
  for (const auto& p : P) t.push_back(*p.t);
  kernel::SplineOptions so;
  so.k = 2;
  so.l = 2;
  for (const auto& m : {kernel::interpolate_bezier(P, t, kernel::InterpolationOptions{}),
                        kernel::interpolate_bspline(P, t, so)}) {
    const auto doc = io::motion_document(m);
    const io::MotionFile f = io::parse_motion(io::parse_json(doc.dump(), "exact"), "exact");
    const auto curve = io::to_motion_exact(f);
    ASSERT_EQ(curve.curve.ctrl().size(), m.curve.curve.ctrl().size());
    for (std::size_t i = 0; i < curve.curve.ctrl().size(); ++i)
      for (int c = 0; c < 8; ++c) EXPECT_EQ(curve.curve.ctrl()[i][c], m.curve.curve.ctrl()[i][c]);
    const auto factors = io::factors_exact(f, curve);  // exactly proportional, or absent
    ASSERT_TRUE(factors);
    for (std::size_t i = 0; i < factors->rotation.ctrl().size(); ++i)
      for (int c = 0; c < 4; ++c)
        EXPECT_EQ(factors->rotation.ctrl()[i][c], m.factors->rotation.ctrl()[i][c]);
    EXPECT_TRUE(doc["method"]["exact"].get<bool>());
    // The double reading carries the provenance, residuals recomputed from the file.
    const Motion<double> d = io::to_motion(f);
    ASSERT_TRUE(d.provenance);
    for (double r : d.provenance->residuals) EXPECT_LE(r, 1e-15);
  }
}
#endif

TEST(MotionValue, HandWrittenMotionsHaveNeitherFactorsNorProvenance) {
  const Motion<double> m =
      io::load_motion(std::string(QMOTION_EXAMPLES) + "/motions/bezier_tr.json").rational();
  EXPECT_FALSE(m.factors);
  EXPECT_FALSE(m.provenance);
  EXPECT_FALSE(io::motion_document(m).contains("method"));
  // The sweep calls take it all the same: exact, through the motion's own curve.
  const auto c = sweep::trajectory_curve(m, V3(1, 2, 3));
  for (int i = 0; i <= 20; ++i) {
    const double s = i / 20.0;
    EXPECT_LE(
        (sweep::evaluate(c, s) - kernel::apply_point(kernel::evaluate(m, s), V3(1, 2, 3))).norm(),
        1e-12);
  }
}

TEST(MotionValue, SweepOfAMotionIsExactOnEveryEdge) {
  const auto five = poses_of("poses/five_positions.json");
  const auto m = kernel::interpolate_bezier(
      five, kernel::parametrize(five, kernel::ParamRule::given), kernel::InterpolationOptions{});
  const auto profile = sweep::rect(4.0, 2.0);
  const auto faces = sweep::sweep(m, profile);
  ASSERT_EQ(faces.size(), profile.edges.size());
  std::mt19937 g(5);
  std::uniform_real_distribution<double> u(m.a(), m.b()), v(0, 1);
  double dev = 0;
  for (std::size_t e = 0; e < faces.size(); ++e) {
    const auto& edge = profile.edges[e];
    std::uniform_real_distribution<double> ve(edge.knots.front(), edge.knots.back());
    for (int i = 0; i < 200; ++i) {
      const double s = u(g), w = ve(g);
      dev = std::max(dev, (sweep::evaluate(faces[e], s, w) -
                           kernel::apply_point(kernel::evaluate(m, s), sweep::evaluate(edge, w)))
                              .norm());
    }
  }
  EXPECT_LE(dev, 1e-11 * 100);  // the motion spans about 100 mm
}

TEST(MotionValue, MalformedMethodBlocksAreRefusedWithHowToRegenerate) {
  for (const auto& [file, field] : std::vector<std::pair<std::string, std::string>>{
           {"method_bad_form.json", "method.form"},
           {"method_parameters_count.json", "method.parameters"},
           {"method_bad_input_poses.json", "method.input_poses"},
           {"method_bad_degree.json", "method.rotation_degree"}}) {
    const std::string path = test_data("bad_motions/") + file;
    try {
      io::load_motion(path);
      ADD_FAILURE() << file << " was accepted";
    } catch (const Error& e) {
      EXPECT_EQ(e.code(), Errc::invalid_input);
      const std::string w = e.what();
      EXPECT_NE(w.find(path), std::string::npos) << w;
      EXPECT_NE(w.find(field), std::string::npos) << w;
      if (field != "method.input_poses") {
        EXPECT_NE(w.find("qmotion interpolate"), std::string::npos) << w;
      }
    }
  }
}

TEST(MotionValue, FactorRowsOfTheWrongWidthGetOneMessageFromBothReaders) {
  // The fast reader reads the factors' control points as rows; the tree reader words what is
  // wrong. Both name the row, and say the same.
  for (const auto& [file, field] : std::vector<std::pair<std::string, std::string>>{
           {"method_factor_row_short.json", "method.rotation_control_points[1]: expected 4"},
           {"method_factor_rows_of_three.json", "method.rotation_control_points[0]: expected 4"}}) {
    const std::string path = test_data("bad_motions/") + file;
    const std::string text = io::read_text_file(path);
    std::string fast, tree;
    try {
      io::load_motion(path);
      ADD_FAILURE() << file << " was accepted";
    } catch (const Error& e) {
      EXPECT_EQ(e.code(), Errc::invalid_input);
      fast = e.what();
    }
    try {
      io::to_motion(io::parse_motion(io::parse_json_reference(text, path), path));
      ADD_FAILURE() << file << " was accepted by the tree reader";
    } catch (const Error& e) {
      tree = e.what();
    }
    EXPECT_EQ(fast, tree);
    EXPECT_NE(fast.find(path), std::string::npos) << fast;
    EXPECT_NE(fast.find(field), std::string::npos) << fast;
  }
}

}  // namespace
}  // namespace qmotion::test
