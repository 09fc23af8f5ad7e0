// api/src/toolpath_nurbs.cpp: `toolpath --nurbs`, the trajectory as G06.2 NURBS blocks.
#include <qmotion/cam/cam_nurbs.hpp>
#include <qmotion/kernel/error.hpp>

#include "toolpath_detail.hpp"

namespace qmotion::toolpath_detail {

/// `--nurbs`: the trajectory as a NURBS of degree <= 3 (cam::cam_nurbs) within the
/// tolerance `tol` (the motion's unit) less the quaternion spline's fit, certified for the
/// numbers as written; measured against the exact motion at 64 points per span; Fanuc
/// G06.2 blocks into os.
void nurbs_toolpath(Toolpath& tp, const cam::ToolTrajectories& src, double k, double tol,
                    const cam::PathMode& mode, std::ostringstream& os) {
  cam::CamNurbsOptions no;
  no.tol = tol - src.fit_error;
  no.written = [k](const Eigen::Vector4d& v) {
    const double w = rounded(v(0), kNurbsDigits);
    Eigen::Vector3d x = v.tail<3>() / v(0) * k;
    for (int i = 0; i < 3; ++i) x(i) = rounded(x(i), kNurbsDigits);
    Eigen::Vector4d r;
    r << w, w * x / k;
    return r;
  };
  const cam::CamNurbs cn = cam::cam_nurbs(src.h, src.exact_point, src.breaks, src.continuity, no);
  NurbsToolpath nt;
  nt.curve = kernel::map_coeffs(cn.curve, [k](const Eigen::Vector4d& v) {
    Eigen::Vector4d r;
    r << v(0), v.tail<3>() * k;
    return r;
  });
  nt.t_knots = cn.t_knots;
  nt.exact = cn.exact;
  nt.spans = cn.spans;
  nt.max_deviation_bound = (cn.bound + src.fit_error) * k;
  for (const auto& v : nt.curve.ctrl())
    if (!(v(0) >= 1e-4 && v(0) <= 99.9999))
      throw Error(Errc::internal, "a NURBS weight outside 0.0001..99.9999: " + io::fixed(v(0)));
  // Dense confirmation and the path length, span by span (span j of the curve stands for
  // span j of t_knots).
  std::vector<double> xt = cn.t_knots;
  xt.erase(std::unique(xt.begin(), xt.end()), xt.end());
  const std::vector<double> xc = nt.curve.breakpoints();
  for (std::size_t j = 0; j + 1 < xt.size(); ++j) {
    const auto piece = kernel::bezier_piece(nt.curve, xc[j], xc[j + 1]);
    for (int s = 0; s <= 64; ++s) {
      const Eigen::Vector4d c = kernel::evaluate(piece, xc[j] + (xc[j + 1] - xc[j]) * s / 64);
      const Eigen::Vector3d e = src.exact_point(xt[j] + (xt[j + 1] - xt[j]) * s / 64) * k;
      nt.max_deviation_measured =
          std::max(nt.max_deviation_measured, (Eigen::Vector3d(c.tail<3>() / c(0)) - e).norm());
    }
    for (int s = 0; s < 4; ++s)
      tp.path_length += k * arc_length(src, xt[j] + (xt[j + 1] - xt[j]) * s / 4,
                                       xt[j] + (xt[j + 1] - xt[j]) * (s + 1) / 4);
  }
  io::NurbsHeader nh;
  nh.spans = nt.spans;
  nh.exact = nt.exact;
  nh.bound = nt.max_deviation_bound;
  io::write_nurbs_gcode(os, header(tp), nt.curve, nh, mode);
  tp.nurbs = std::move(nt);
}

}  // namespace qmotion::toolpath_detail
