// io/svg.cpp
#include <qmotion/io/svg.hpp>
#include <qmotion/kernel/motion.hpp>
#include <sstream>
#include <vector>

namespace qmotion::io {

/// An isometric SVG of the trajectories and of the profile at nine instants.
std::string render_demo_svg(const kernel::Motion<double>& lm,
                            const sweep::NurbsCurve<double>& profile) {
  auto proj = [](const Eigen::Vector3d& p) {
    return Eigen::Vector2d((p.x() - p.y()) * 0.8660254037844386, -(p.x() + p.y()) * 0.5 - p.z());
  };
  std::vector<std::vector<Eigen::Vector2d>> lines;
  std::vector<std::string> colors;
  for (const Eigen::Vector3d& x :
       std::vector<Eigen::Vector3d>{Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(0, 0, 20)}) {
    lines.emplace_back();
    colors.push_back(lines.size() == 1 ? "#c0392b" : "#2471a3");
    for (int i = 0; i <= 200; ++i)
      lines.back().push_back(proj(kernel::apply_point(
          kernel::evaluate(lm.curve, lm.curve.a() + (lm.curve.b() - lm.curve.a()) * i / 200.0),
          x)));
  }
  for (int k = 0; k <= 8; ++k) {
    const auto q =
        kernel::evaluate(lm.curve, lm.curve.a() + (lm.curve.b() - lm.curve.a()) * k / 8.0);
    lines.emplace_back();
    colors.push_back("#555555");
    for (int j = 0; j <= 40; ++j)
      lines.back().push_back(proj(kernel::apply_point(q, sweep::evaluate(profile, j / 40.0))));
  }
  Eigen::Vector2d lo = lines[0][0], hi = lines[0][0];
  for (const auto& l : lines)
    for (const auto& p : l) {
      lo = lo.cwiseMin(p);
      hi = hi.cwiseMax(p);
    }
  const double pad = 10, scale = std::min(760.0 / std::max(hi.x() - lo.x(), 1e-9),
                                          700.0 / std::max(hi.y() - lo.y(), 1e-9));
  std::ostringstream os;
  os << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\""
     << static_cast<int>((hi.x() - lo.x()) * scale + 2 * pad) << "\" height=\""
     << static_cast<int>((hi.y() - lo.y()) * scale + 2 * pad + 30)
     << "\">\n<text x=\"10\" y=\"18\" font-family=\"sans-serif\" font-size=\"11\">elliptic + TR "
        "motion, five poses. red: origin; "
        "blue: (0,0,20); grey: parabola at t = k/8</text>\n";
  for (std::size_t i = 0; i < lines.size(); ++i) {
    os << "<polyline fill=\"none\" stroke=\"" << colors[i] << "\" stroke-width=\"1.5\" points=\"";
    for (const auto& p : lines[i])
      os << (p.x() - lo.x()) * scale + pad << "," << (p.y() - lo.y()) * scale + pad + 30 << " ";
    os << "\"/>\n";
  }
  os << "</svg>\n";
  return os.str();
}

}  // namespace qmotion::io
