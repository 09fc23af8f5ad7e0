// <qmotion/sweep/pipe_approx.hpp>: the exact pipe of a sphere brought to a low degree along
// the path, within a proven distance of it (docs/geometry.md, "Pipes of a low degree").
//
// The pipe faces of a tilting ball cutter have degree 31 to 56 along t, above what STEP and
// IGES take in most systems. Each face's three columns along t (homogeneous curves of the
// exact degree n) are replaced by curves of degree m that keep their end points, fitted by
// least squares; the end rows, the circles the neighbouring pieces and the caps share, stay
// exact, and one piece's four faces are always cut alike, so the faces still meet.
//
// The bound: with the exact face X = P / w and the new one Y = Q / v (homogeneous, about a
// point o), X - Y = (P v - Q w) / (w v). The numerator and the denominator are tensor
// Bernstein polynomials of degree (n + m) x 4; the numerator's largest coefficient over the
// denominator's least bounds |X - Y| over the whole face (a Bernstein polynomial lies in the
// hull of its coefficients). A face whose bound is above the tolerance, or whose new
// weights are not all positive, is halved along t with its piece's other faces.
#pragma once
#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <qmotion/kernel/error.hpp>
#include <qmotion/kernel/interpolation.hpp>
#include <qmotion/sweep/pipe.hpp>
#include <string>
#include <vector>

namespace qmotion::sweep {

/// What pipe_to_degree made: the pipe (its pipe faces of degree at most `degree` along t,
/// the caps as they were, degree_t and volume those of the new faces, the rest the exact
/// pipe's), and its proven distance from the exact pipe.
struct LowDegreePipe {
  PipeShell pipe;
  double bound = 0;  ///< proven: every point of a face within bound of the exact face
  std::size_t halvings = 0;
};

namespace approx_detail {

using Net = std::vector<std::array<Eigen::Vector4d, 3>>;  // rows along t, 3 columns

/// The face's homogeneous net about o: (w, w (x - o)).
inline Net net_of(const NurbsSurface<double>& f, const Eigen::Vector3d& o) {
  Net h(f.points.size());
  for (std::size_t i = 0; i < h.size(); ++i)
    for (std::size_t j = 0; j < 3; ++j) {
      const double w = f.weights[i][j];
      h[i][j] << w, w * (f.points[i][j] - o);
    }
  return h;
}

/// de Casteljau: the net's pieces over [0, s] and [s, 1] along t.
inline std::pair<Net, Net> split(const Net& h, double s) {
  Net c = h, left(h.size()), right(h.size());
  const std::size_t n = h.size() - 1;
  left[0] = c[0];
  right[n] = c[n];
  for (std::size_t r = 1; r <= n; ++r) {
    for (std::size_t i = 0; i + r <= n; ++i)
      for (std::size_t j = 0; j < 3; ++j) c[i][j] = (1 - s) * c[i][j] + s * c[i + 1][j];
    left[r] = c[0];
    right[n - r] = c[n - r];
  }
  return {left, right};
}

inline double binom(int n, int k) {
  double c = 1;
  for (int q = 1; q <= k; ++q) c = c * (n - k + q) / q;
  return c;
}

/// The least-squares fit of degree m to each column, keeping its end points: samples at
/// 3n Chebyshev points of (0, 1).
inline Net fit(const Net& h, int m) {
  const int n = static_cast<int>(h.size()) - 1;
  const int N = 3 * n + 3;
  Eigen::MatrixXd A(N, m - 1);
  std::vector<std::array<Eigen::Vector4d, 3>> rhs(static_cast<std::size_t>(N));
  auto bern = [](int d, int k, double u) {
    return binom(d, k) * std::pow(u, k) * std::pow(1 - u, d - k);
  };
  for (int s = 0; s < N; ++s) {
    const double u = 0.5 - 0.5 * std::cos(M_PI * (s + 0.5) / N);
    for (int k = 1; k < m; ++k) A(s, k - 1) = bern(m, k, u);
    for (std::size_t j = 0; j < 3; ++j) {
      Eigen::Vector4d c = Eigen::Vector4d::Zero();
      for (int i = 0; i <= n; ++i) c += bern(n, i, u) * h[static_cast<std::size_t>(i)][j];
      rhs[static_cast<std::size_t>(s)][j] =
          c - bern(m, 0, u) * h.front()[j] - bern(m, m, u) * h.back()[j];
    }
  }
  const auto qr = A.colPivHouseholderQr();
  Net out(static_cast<std::size_t>(m + 1));
  out.front() = h.front();
  out.back() = h.back();
  for (std::size_t j = 0; j < 3; ++j) {
    Eigen::MatrixXd b(N, 4);
    for (int s = 0; s < N; ++s) b.row(s) = rhs[static_cast<std::size_t>(s)][j].transpose();
    const Eigen::MatrixXd x = qr.solve(b);
    for (int k = 1; k < m; ++k) out[static_cast<std::size_t>(k)][j] = x.row(k - 1).transpose();
  }
  return out;
}

/// The proven bound of |X - Y| over the face (see the file's comment); HUGE_VAL when the
/// denominator's coefficients are not all positive.
inline double bound(const Net& exact, const Net& low) {
  const int n = static_cast<int>(exact.size()) - 1, m = static_cast<int>(low.size()) - 1;
  const int d = n + m;
  std::vector<std::array<Eigen::Vector3d, 5>> num(static_cast<std::size_t>(d + 1));
  std::vector<std::array<double, 5>> den(static_cast<std::size_t>(d + 1));
  for (auto& r : num) r.fill(Eigen::Vector3d::Zero());
  for (auto& r : den) r.fill(0.0);
  for (int i = 0; i <= n; ++i)
    for (int k = 0; k <= m; ++k) {
      const double cu = binom(n, i) * binom(m, k) / binom(d, i + k);
      for (int j = 0; j < 3; ++j)
        for (int l = 0; l < 3; ++l) {
          const double c = cu * binom(2, j) * binom(2, l) / binom(4, j + l);
          const Eigen::Vector4d &e =
                                    exact[static_cast<std::size_t>(i)][static_cast<std::size_t>(j)],
                                &a = low[static_cast<std::size_t>(k)][static_cast<std::size_t>(l)];
          const auto ii = static_cast<std::size_t>(i + k), jj = static_cast<std::size_t>(j + l);
          num[ii][jj] += c * (e.tail<3>() * a(0) - a.tail<3>() * e(0));
          den[ii][jj] += c * e(0) * a(0);
        }
    }
  double top = 0, low_den = HUGE_VAL;
  for (std::size_t i = 0; i < num.size(); ++i)
    for (std::size_t j = 0; j < 5; ++j) {
      top = std::max(top, num[i][j].norm());
      low_den = std::min(low_den, den[i][j]);
    }
  if (!(low_den > 0)) return HUGE_VAL;
  return top / low_den;
}

inline NurbsSurface<double> face_of(const Net& h, const Eigen::Vector3d& o, double u0, double u1,
                                    const NurbsSurface<double>& like) {
  NurbsSurface<double> f;
  f.degree_u = static_cast<int>(h.size()) - 1;
  f.degree_v = like.degree_v;
  f.knots_u.assign(static_cast<std::size_t>(f.degree_u + 1), u0);
  f.knots_u.insert(f.knots_u.end(), static_cast<std::size_t>(f.degree_u + 1), u1);
  f.knots_v = like.knots_v;
  for (const auto& row : h) {
    std::vector<Eigen::Vector3d> pts;
    std::vector<double> ws;
    for (const auto& c : row) {
      pts.emplace_back(c.tail<3>() / c(0) + o);
      ws.push_back(c(0));
    }
    f.points.push_back(std::move(pts));
    f.weights.push_back(std::move(ws));
  }
  return f;
}

}  // namespace approx_detail

/// The pipe's faces brought to degree at most `degree` (>= 2) along t, each within `tol` of
/// the exact face it replaces (proven; see the file's comment); faces of that degree or less
/// and the caps are kept. The pipe faces of one piece are the four consecutive faces with
/// the same t-interval, as pipe_shell makes them. Errc::numerical_failure when a face still
/// misses tol after 16 halvings.
inline LowDegreePipe pipe_to_degree(const PipeShell& exact, int degree, double tol,
                                    const std::string& where) {
  using namespace approx_detail;
  LowDegreePipe out;
  out.pipe = exact;
  NurbsShell<double>& shell = out.pipe.shell;
  shell.faces.clear();
  Eigen::AlignedBox3d box;
  for (const auto& f : exact.shell.faces)
    for (const auto& row : f.points)
      for (const auto& x : row) box.extend(x);
  const Eigen::Vector3d o = box.center();
  const auto& faces = exact.shell.faces;
  // Every pipe face cut at every face's ends along t, so that faces which share a column
  // along t share its interval too; then each interval's faces are brought down together.
  std::vector<double> cuts;
  for (std::size_t k = 0; k < exact.pipe_faces; ++k)
    cuts.insert(cuts.end(), {faces[k].knots_u.front(), faces[k].knots_u.back()});
  std::sort(cuts.begin(), cuts.end());
  cuts.erase(std::unique(cuts.begin(), cuts.end()), cuts.end());
  struct Part {
    std::vector<Net> nets;
    std::vector<std::size_t> from;  // the exact face each net comes from
    double u0 = 0, u1 = 0;
    int depth = 0;
  };
  std::vector<Part> parts(cuts.size() > 0 ? cuts.size() - 1 : 0);
  for (std::size_t q = 0; q + 1 < cuts.size(); ++q) {
    parts[q].u0 = cuts[q];
    parts[q].u1 = cuts[q + 1];
  }
  for (std::size_t k = 0; k < exact.pipe_faces; ++k) {
    const auto& f = faces[k];
    if (f.degree_u <= degree) {
      shell.faces.push_back(f);
      continue;
    }
    Net rest = net_of(f, o);
    double a = f.knots_u.front();
    const double b = f.knots_u.back();
    std::size_t q =
        static_cast<std::size_t>(std::lower_bound(cuts.begin(), cuts.end(), a) - cuts.begin());
    for (; cuts[q + 1] < b; ++q) {  // cut off [a, cuts[q + 1]]
      auto [l, r] = split(rest, (cuts[q + 1] - a) / (b - a));
      parts[q].nets.push_back(std::move(l));
      parts[q].from.push_back(k);
      rest = std::move(r);
      a = cuts[q + 1];
    }
    parts[q].nets.push_back(std::move(rest));
    parts[q].from.push_back(k);
  }
  std::vector<Part> todo;
  for (auto it = parts.rbegin(); it != parts.rend(); ++it)
    if (!it->nets.empty()) todo.push_back(std::move(*it));
  while (!todo.empty()) {
    Part p = std::move(todo.back());
    todo.pop_back();
    std::vector<Net> low;
    double worst = 0;
    for (const auto& h : p.nets) {
      low.push_back(fit(h, degree));
      worst = std::max(worst, bound(h, low.back()) * (1 + 1e-9));
    }
    if (worst <= tol) {
      out.bound = std::max(out.bound, worst);
      for (std::size_t q = 0; q < low.size(); ++q)
        shell.faces.push_back(face_of(low[q], o, p.u0, p.u1, faces[p.from[q]]));
      continue;
    }
    if (p.depth >= 16)
      throw Error(Errc::numerical_failure,
                  where + ": the pipe could not be brought to degree " + std::to_string(degree) +
                      " within " + kernel::detail::format_double(tol) +
                      " near t = " + kernel::detail::format_double(0.5 * (p.u0 + p.u1)));
    ++out.halvings;
    const double um = 0.5 * (p.u0 + p.u1);
    Part a{{}, p.from, p.u0, um, p.depth + 1}, b{{}, p.from, um, p.u1, p.depth + 1};
    for (const auto& h : p.nets) {
      auto [l, r] = split(h, 0.5);
      a.nets.push_back(std::move(l));
      b.nets.push_back(std::move(r));
    }
    todo.push_back(std::move(b));
    todo.push_back(std::move(a));
  }
  out.pipe.pipe_faces = shell.faces.size();
  for (std::size_t k = exact.pipe_faces; k < faces.size(); ++k) shell.faces.push_back(faces[k]);
  out.pipe.degree_t = 0;
  for (std::size_t k = 0; k < out.pipe.pipe_faces; ++k)
    out.pipe.degree_t = std::max(out.pipe.degree_t, shell.faces[k].degree_u);
  // The enclosed volume, (1/3) sum of the integrals of (X - o) . dA (faces face outward).
  out.pipe.volume = 0;
  for (const auto& f : shell.faces)
    pipe_detail::gauss_points(f, [&](double, const Eigen::Vector3d& X, const Eigen::Vector3d& Xu,
                                     const Eigen::Vector3d& Xv, double w) {
      out.pipe.volume += w * (X - o).dot(Xu.cross(Xv)) / 3;
    });
  return out;
}

}  // namespace qmotion::sweep
