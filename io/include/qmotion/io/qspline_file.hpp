// <qmotion/io/qspline_file.hpp>: quaternion-spline motion files (docs/formats.md), and reading
// a motion file of either kind.
#pragma once
#include <nlohmann/json.hpp>
#include <optional>
#include <qmotion/kernel/qspline.hpp>
#include <qmotion/motion.hpp>
#include <string>

namespace qmotion::io {

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
Motion qspline_motion(const nlohmann::json& doc, const std::string& source);

/// A quaternion-spline motion's file document (docs/formats.md) without its method block:
/// type, scheme, units, param_range, knots, keys, positions, and the scheme's own fields
/// (tension; KKS's control quaternions and positions). Errc::invalid_input for a rational
/// motion.
nlohmann::json qspline_document(const Motion& motion);

/// Writes a motion of either kind as its file (atomically): a Q-motion as save_motion does,
/// a quaternion spline as qspline_document; read back by load_motion.
void save_motion(const Motion& motion, const std::string& path);

/// Reads a motion file of either kind (docs/formats.md): a rational Q-motion or a quaternion
/// spline, named by the path. Refusals name the file and the field.
Motion load_motion(const std::string& path);

}  // namespace qmotion::io
