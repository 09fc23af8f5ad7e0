// <qmotion/io/qspline_file.hpp>: quaternion-spline motion files (docs/formats.md), and a
// motion file of either kind.
#pragma once
#include <nlohmann/json.hpp>
#include <optional>
#include <qmotion/kernel/motion_value.hpp>
#include <qmotion/kernel/qspline.hpp>
#include <string>
#include <variant>

namespace qmotion::io {

/// A quaternion-spline motion as a value: the spline, its file document, a one-line
/// summary, its length unit and where it came from (a file name; empty when built here).
struct QSplineMotion {
  kernel::QuaternionSpline spline;
  nlohmann::json document;
  std::string summary;
  std::string units = "mm";
  std::string name;

  /// The name for messages: the file name, or "motion" for one built in memory.
  std::string label() const { return name.empty() ? std::string("motion") : name; }
};

/// The scheme named `s` (kks, quintic, quartic), if it is one.
std::optional<kernel::QSplineScheme> qspline_scheme(const std::string& s);

/// Whether a parsed document is a quaternion-spline motion file.
bool is_qspline_document(const nlohmann::json& doc);

/// The spline a quaternion-spline document describes: quartic and quintic rebuilt from their
/// keys, KKS from its recorded control quaternions and points. Errc::invalid_input names the
/// field.
kernel::QuaternionSpline qspline_from_document(const nlohmann::json& doc,
                                               const std::string& source);

/// The motion a quaternion-spline document describes (qspline_from_document, with its unit
/// checked), named `source`.
QSplineMotion qspline_motion(const nlohmann::json& doc, const std::string& source);

/// A motion file of either kind: a rational q-motion or a quaternion spline.
using AnyMotion = std::variant<kernel::Motion<double>, QSplineMotion>;

/// Reads a motion file of either kind (docs/formats.md), refusals naming the file and field.
AnyMotion load_any_motion(const std::string& path);

/// The length unit of either kind.
const std::string& units_of(const AnyMotion& m);

}  // namespace qmotion::io
