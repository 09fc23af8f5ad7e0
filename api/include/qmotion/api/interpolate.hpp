// <qmotion/api/interpolate.hpp>: poses -> a motion file's document, with every option of the CLI's
// `interpolate` (the library call behind it).
#pragma once
#include <nlohmann/json.hpp>
#include <qmotion/io/motion_json.hpp>
#include <qmotion/io/poses.hpp>
#include <qmotion/kernel/parametrization.hpp>
#include <qmotion/motion.hpp>
#include <string>
#include <vector>

namespace qmotion {

/// The options of `qmotion interpolate`, by their CLI names (docs/formats.md). Empty strings and
/// negative degrees take the defaults: elliptic + TR, `--param given` when every pose has
/// t (else uniform), Bezier up to six poses and B-spline beyond, cubic spline factors.
struct InterpolateOptions {
  std::string rotation = "elliptic";  ///< elliptic, affine, projective
  std::string translation = "tr";     ///< tr, trt, minimal
  std::string trt_degrees;            ///< "L1,L2" (TRT)
  std::string param;                  ///< given, uniform, chordal, star-chordal, ...
  std::string form;                   ///< bezier, bspline, c1
  int degree = -1;                    ///< B-spline rotational degree K
  int translation_degree = -1;        ///< B-spline translational degree L
  bool exact = false;                 ///< CGAL::Exact_rational (quaternion rotations)
};

/// A new motion: the motion value, a one-line summary, the poles on its interval (zeros of
/// the rotational part; trajectories cannot be exported through them), and what its file
/// needs (docs/formats.md: the curve, the factors it is the product of, the method with the input
/// poses as given). The file is made on demand: document() as a tree, text() streamed.
struct InterpolatedMotion {
  Motion motion;  ///< the rational motion (converted to double under --exact)
  std::string summary;
  std::vector<double> poles;
  io::PoseSet input;              ///< the poses as given, written as the method's input_poses
  nlohmann::json exact_document;  ///< under --exact: the file with exact "p/q" numbers; else null

  /// The motion file's document; exact numbers under --exact.
  nlohmann::json document() const;
  /// The same document as JSON text (what `qmotion interpolate` writes): streamed without a
  /// tree (motion_json_text) for double motions.
  std::string text() const;
  /// Writes text() to `path` atomically; the streamed text is never held whole.
  void save(const std::string& path) const;
};

/// The parametrisation rule `name` (`--param`) for the poses; empty: `given` when every
/// pose has t, else `uniform`. Errc::invalid_input for unknown names and for `given`
/// without t.
kernel::ParamRule param_rule(const io::PoseSet& poses, const std::string& name);

/// A Q-motion through the poses (Jüttler 1994; docs/interpolation.md). Throws Errc::invalid_input
/// for bad options (naming the option, as the CLI does) and Errc::numerical_failure for refused
/// systems. `result.motion` is what the sweep and export calls take.
InterpolatedMotion interpolate(const io::PoseSet& poses, const InterpolateOptions& options);

#ifdef QMOTION_WITH_CGAL
/// The same motion in CGAL::Exact_rational (options.exact is implied): poses read exactly
/// from their text (quaternion rotations only), parameters exact for the given and
/// uniform rules. Units and the parametrisation name are recorded.
kernel::Motion<kernel::Rational> interpolate_exact(const io::PoseSet& poses,
                                                   InterpolateOptions options);
#endif

}  // namespace qmotion
