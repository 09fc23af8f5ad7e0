// <qmotion/kernel/methods.hpp>
#pragma once
#include <optional>
#include <string>

namespace qmotion::kernel {

/// Rotation interpolation of section 3 (docs/interpolation.md).
enum class RotationMethod { elliptic, affine, projective };
/// Translation of section 4-5 (docs/interpolation.md).
enum class TranslationMethod { tr, trt, minimal };
/// How the motion is assembled (docs/formats.md --form): one Bezier polynomial, a B-spline
/// through all poses (section 6), Algorithm 2's local C^1 spline, or a B-spline fitted near
/// the poses within tolerances (`qmotion fit`, docs/fitting.md).
enum class Form { bezier, bspline, c1, fit };

inline const char* to_string(RotationMethod m) {
  return m == RotationMethod::elliptic ? "elliptic"
         : m == RotationMethod::affine ? "affine"
                                       : "projective";
}
inline const char* to_string(TranslationMethod m) {
  return m == TranslationMethod::tr ? "tr" : m == TranslationMethod::trt ? "trt" : "minimal";
}
inline const char* to_string(Form f) {
  return f == Form::bezier    ? "bezier"
         : f == Form::bspline ? "bspline"
         : f == Form::c1      ? "c1"
                              : "fit";
}
/// The method of a name as to_string spells it (the one place names are parsed).
inline std::optional<RotationMethod> rotation_method_from_string(const std::string& s) {
  for (auto m : {RotationMethod::elliptic, RotationMethod::affine, RotationMethod::projective})
    if (s == to_string(m)) return m;
  return std::nullopt;
}
inline std::optional<TranslationMethod> translation_method_from_string(const std::string& s) {
  for (auto m : {TranslationMethod::tr, TranslationMethod::trt, TranslationMethod::minimal})
    if (s == to_string(m)) return m;
  return std::nullopt;
}
inline std::optional<Form> form_from_string(const std::string& s) {
  for (auto f : {Form::bezier, Form::bspline, Form::c1, Form::fit})
    if (s == to_string(f)) return f;
  return std::nullopt;
}

}  // namespace qmotion::kernel
