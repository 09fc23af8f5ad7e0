// <qmotion/io/motion_json.hpp>
#pragma once
#include <array>
#include <nlohmann/json.hpp>
#include <qmotion/io/json_number.hpp>
#include <qmotion/io/paged_text.hpp>
#include <qmotion/io/poses.hpp>
#include <qmotion/kernel/motion.hpp>
#include <qmotion/kernel/motion_value.hpp>
#include <qmotion/sweep/factors.hpp>
#include <string>
#include <variant>
#include <vector>

#ifdef QMOTION_WITH_CGAL
#include <qmotion/kernel/cgal_scalar.hpp>
#endif

namespace qmotion::io {

/// Most control points a motion file may hold: a B-spline motion through the most poses
/// a pose file may hold (10^5) has about 7 x 10^5.
inline constexpr std::size_t kMaxMotionControlPoints = 1000000;
/// Highest degree a motion file may have.
inline constexpr int kMaxMotionDegree = 200;

/// Throws Errc::invalid_input naming `source` when a motion of this degree and number of
/// control points exceeds what a motion file may hold: the reader's check and message, which
/// the writer applies too, so that qmotion never writes a motion it would refuse to read.
void check_motion_limits(long long degree, std::size_t control_points, const std::string& source);

/// A validated motion file (docs/formats.md), numbers with their source text so that exact mode
/// reads them exactly.
struct MotionFile {
  std::string source;  ///< file name, for messages
  kernel::Basis basis = kernel::Basis::bezier;
  int degree = 0;
  std::vector<Number> knots;  ///< full clamped vector (built from param_range for Bezier)
  std::array<Number, 2> range;
  std::vector<std::array<Number, 8>> ctrl;  ///< (w, x, y, z, eps w, eps x, eps y, eps z)
  std::string units = "mm";
  nlohmann::json method;  ///< how the motion was made (null for hand-written files)
  /// method.input_poses when the fast reader has read it (it is then not in `method`):
  /// 10^4 poses without a tree. Read the poses through recorded_input_poses.
  std::optional<PoseSet> input_poses;
  /// Control points of the recorded factors (method.rotation_control_points, ...) when the
  /// fast reader has read them (they are then not in `method`): `width` numbers a row, the
  /// rows one after another, without a tree. factors_double and factors_exact read either.
  struct Rows {
    std::size_t width = 0;
    std::vector<Number> values;
  };
  std::map<std::string, Rows, std::less<>> factor_rows;
};

/// The poses the method block records (input_poses), read from whichever form the reader
/// left them in; std::nullopt when it records none. Throws Errc::invalid_input for
/// malformed poses, naming "SOURCE: method.input_poses".
std::optional<PoseSet> recorded_input_poses(const MotionFile& f);

/// Validates a parsed motion document; throws Errc::invalid_input naming `source` and the
/// field.
MotionFile parse_motion(const nlohmann::json& doc, const std::string& source);
/// The same, taking the method block out of `doc` instead of copying it.
MotionFile parse_motion(nlohmann::json&& doc, const std::string& source);
/// Reads and validates a motion file.
MotionFile read_motion(const std::string& path);
/// The motion file at `path` read by the fast reader (parse_motion_fast) on its paged text,
/// whose pages go as they are read; when the fast reader declines, the file's whole text
/// instead, for a full reader to read or word (a quaternion spline, an exact number, an
/// error). Throws what reading the file and the checks both readers share throw.
std::variant<MotionFile, std::string> read_motion_or_text(const std::string& path,
                                                          bool with_method = true);
/// The same for a motion file's text already read (`source` names it in messages).
MotionFile parse_motion_text(const std::string& text, const std::string& source);
/// The fast path of parse_motion_text: the file read without a DOM when it is an ordinary
/// q-motion file; std::nullopt when anything needs the full reader (another type, exact
/// "p/q" numbers, an error to word). Throws the errors both readers share (knots, counts).
/// `with_method` false leaves MotionFile::method null (still validated as JSON): for readers
/// of the curve alone, such as eval.
std::optional<MotionFile> parse_motion_fast(const std::string& text, const std::string& source,
                                            bool with_method = true);
/// The same on a file's paged text, giving its pages back as the members are read: the
/// text is then no longer whole (PagedText::whole reads it again for the full reader).
std::optional<MotionFile> parse_motion_fast(PagedText& text, const std::string& source,
                                            bool with_method = true);

/// The motion in double precision.
kernel::QMotion<double> to_motion_double(const MotionFile& f);

/// The factors recorded in the file's method (qmotion interpolate writes them), if any and
/// if they reproduce the motion; std::nullopt for hand-written files. Bezier factors cover
/// param_range; "rotation_knots" / "translation_knots" give B-spline factors.
std::optional<sweep::MotionFactors<double>> factors_double(const MotionFile& f,
                                                           const kernel::QMotion<double>& m);

/// A motion file document: numbers at full double precision.
nlohmann::json motion_to_json(const kernel::QMotion<double>& m, const nlohmann::json& method,
                              const std::string& units = "mm");

/// The file as a motion value (double): its curve; the recorded factors when they
/// reproduce it; the provenance when the method block records one completely (form,
/// rotation, translation, degrees, parameters, input_poses), with the residuals at the
/// poses recomputed; its units; `name` = the file name. Hand-written files (no method)
/// give a motion without factors and provenance. A method block that records a field
/// malformed is refused (Errc::invalid_input naming the field, and how to regenerate).
kernel::Motion<double> to_motion(const MotionFile& f);
/// The same, freeing the parts of `f` the motion holds once read (the control points and
/// the factors' rows: a lower peak); f's other members (method, input poses, units, source)
/// stay as they were.
kernel::Motion<double> to_motion(MotionFile&& f);

/// The motion file document of a motion value (docs/formats.md): the curve, and a method block
/// from its provenance and factors (none when it has neither). `input_poses`, when not
/// null, is written as the method's input_poses instead of the provenance's poses (the
/// poses as the user gave them: rotation matrices, axis-angle, exact text).
nlohmann::json motion_document(const kernel::Motion<double>& m,
                               const nlohmann::json& input_poses = nullptr);
/// motion_document(m, input_poses ? poses_to_json(*input_poses) : null) as JSON text,
/// streamed (no tree): one control point a line, shortest round-trip numbers, members in
/// the tree's sorted order. What save_motion and `qmotion interpolate` write.
std::string motion_json_text(const kernel::Motion<double>& m, const PoseSet* input_poses = nullptr);
/// Writes motion_json_text(m, input_poses) to `path` atomically as it is made, never held
/// whole (write_json_atomic).
void write_motion_json(const std::string& path, const kernel::Motion<double>& m,
                       const PoseSet* input_poses = nullptr);
/// write_motion_json(path, m).
void save_motion(const kernel::Motion<double>& m, const std::string& path);

#ifdef QMOTION_WITH_CGAL
/// The exact motion's document: every number an exact "p/q" string.
nlohmann::json motion_document(const kernel::Motion<kernel::Rational>& m,
                               const nlohmann::json& input_poses = nullptr);
/// The motion read exactly (every decimal and "p/q" as the rational it denotes).
kernel::QMotion<kernel::Rational> to_motion_exact(const MotionFile& f);
/// The recorded factors read exactly.
std::optional<sweep::MotionFactors<kernel::Rational>> factors_exact(
    const MotionFile& f, const kernel::QMotion<kernel::Rational>& m);
/// A motion file document with every number an exact "p/q" string.
nlohmann::json motion_to_json(const kernel::QMotion<kernel::Rational>& m,
                              const nlohmann::json& method, const std::string& units = "mm");
#endif

}  // namespace qmotion::io
