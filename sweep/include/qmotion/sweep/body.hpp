// <qmotion/sweep/body.hpp>: solids of the moving space (docs/formats.md, "Bodies"): the
// sphere, box and cylinder, the CAM cutters with their tip at the moving origin and their
// axis along moving +z, and closed triangle meshes; their triangulations and their radius
// about the moving origin.
#pragma once
#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <qmotion/kernel/error.hpp>
#include <qmotion/sweep/mesh_distance.hpp>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace qmotion::sweep {

namespace detail {
/// A size in a message: 6 significant digits.
inline std::string size_text(double v) {
  std::ostringstream os;
  os << v;
  return os.str();
}

}  // namespace detail

/// A body of the moving space. Sizes are in the motion's length unit.
struct Body {
  enum class Kind { sphere, box, cylinder, flat_cutter, ball_cutter, bull_cutter, mesh };
  Kind kind = Kind::box;
  double r = 0;                 ///< sphere and cylinder radius
  double a = 0, b = 0, c = 0;   ///< box edges along moving x, y, z
  double h = 0;                 ///< cylinder height (moving z from 0 to h)
  double D = 0, L = 0, rc = 0;  ///< cutters: diameter, length, corner radius (bull)
  TriangleMesh mesh;            ///< Kind::mesh, in the moving space
  /// Kind::mesh: its distance index (index_mesh), shared by the body's copies; without it
  /// the signed distance scans every triangle.
  std::shared_ptr<const detail::MeshIndex> index;
  std::string spec;  ///< as given, for messages and reports

  static Body box(double a, double b, double c, std::string spec = {}) {
    Body x;
    x.kind = Kind::box;
    x.a = a;
    x.b = b;
    x.c = c;
    x.spec = spec.empty() ? "box:" + detail::size_text(a) + "," + detail::size_text(b) + "," +
                                detail::size_text(c)
                          : std::move(spec);
    return x;
  }
};

namespace detail {

inline void require_positive(const Body& body, double v, const char* what) {
  if (!(v > 0) || !std::isfinite(v))
    throw Error(Errc::invalid_input, "body '" + body.spec + "': " + what +
                                         " must be a positive finite length, got " + size_text(v));
}

/// The surface of revolution about z of the profile (radius, z), from a point on the axis
/// to a point on the axis, with n sectors: closed, outward when the profile runs from the
/// bottom pole up to the top pole.
inline TriangleMesh revolve(const std::vector<std::pair<double, double>>& profile, int n) {
  TriangleMesh m;
  const double pi = 3.14159265358979323846;
  // Vertex rings: one vertex for a point on the axis, n otherwise.
  std::vector<int> first;
  for (const auto& [r, z] : profile) {
    first.push_back(static_cast<int>(m.vertices.size()));
    if (r == 0) {
      m.vertices.emplace_back(0, 0, z);
      continue;
    }
    for (int k = 0; k < n; ++k) {
      const double phi = 2 * pi * k / n;
      m.vertices.emplace_back(r * std::cos(phi), r * std::sin(phi), z);
    }
  }
  for (std::size_t i = 0; i + 1 < profile.size(); ++i) {
    const bool p0 = profile[i].first == 0, p1 = profile[i + 1].first == 0;
    const int f0 = first[i], f1 = first[i + 1];
    for (int k = 0; k < n; ++k) {
      const int k1 = (k + 1) % n;
      if (p0 && !p1) {
        m.triangles.push_back({f0, f1 + k1, f1 + k});
      } else if (!p0 && p1) {
        m.triangles.push_back({f0 + k, f0 + k1, f1});
      } else if (!p0 && !p1) {
        m.triangles.push_back({f0 + k, f1 + k1, f1 + k});
        m.triangles.push_back({f0 + k, f0 + k1, f1 + k1});
      }
    }
  }
  return m;
}

/// Sectors of a circle of radius r whose inscribed polygon stays within tol of it.
inline int sectors(double r, double tol) {
  const double pi = 3.14159265358979323846;
  if (!(tol < r)) return 8;
  const double n = pi / std::acos(1 - tol / r);
  return std::clamp(static_cast<int>(std::ceil(n)), 8, 256);
}

/// A quarter arc of radius rho about (r0, z0) from angle a0 to a1 (radians, from +r).
inline void arc(std::vector<std::pair<double, double>>& p, double r0, double z0, double rho,
                double a0, double a1, int n) {
  for (int k = 1; k <= n; ++k) {
    const double a = a0 + (a1 - a0) * k / n;
    p.emplace_back(std::max(0.0, r0 + rho * std::cos(a)), z0 + rho * std::sin(a));
  }
}

}  // namespace detail

/// Refuses (Errc::invalid_input, naming the body) a size that is not a positive finite
/// length, a corner radius above D/2, a cutter shorter than its corner, and a mesh that
/// is not closed, 2-manifold and consistently oriented.
inline void validate(const Body& body) {
  using K = Body::Kind;
  switch (body.kind) {
    case K::sphere:
      detail::require_positive(body, body.r, "the radius r");
      return;
    case K::box:
      detail::require_positive(body, body.a, "the edge a");
      detail::require_positive(body, body.b, "the edge b");
      detail::require_positive(body, body.c, "the edge c");
      return;
    case K::cylinder:
      detail::require_positive(body, body.r, "the radius r");
      detail::require_positive(body, body.h, "the height h");
      return;
    case K::flat_cutter:
    case K::ball_cutter:
    case K::bull_cutter: {
      detail::require_positive(body, body.D, "the diameter D");
      detail::require_positive(body, body.L, "the length L");
      const double corner = body.kind == K::ball_cutter   ? body.D / 2
                            : body.kind == K::bull_cutter ? body.rc
                                                          : 0.0;
      if (body.kind == K::bull_cutter) {
        detail::require_positive(body, body.rc, "the corner radius rc");
        if (body.rc > body.D / 2)
          throw Error(Errc::invalid_input, "body '" + body.spec + "': the corner radius rc = " +
                                               detail::size_text(body.rc) +
                                               " exceeds D/2 = " + detail::size_text(body.D / 2));
      }
      if (body.L < corner)
        throw Error(Errc::invalid_input,
                    "body '" + body.spec + "': the length L = " + detail::size_text(body.L) +
                        " is shorter than the corner radius " + detail::size_text(corner));
      return;
    }
    case K::mesh:
      return;  // checked where it is read (io::read_body)
  }
}

/// The body's boundary as a closed triangle mesh whose vertices lie on it, within tol of it
/// (tol > 0; the mesh itself for Kind::mesh).
inline TriangleMesh triangulate(const Body& body, double tol) {
  using K = Body::Kind;
  validate(body);
  const double pi = 3.14159265358979323846;
  std::vector<std::pair<double, double>> p;  // (radius, z) from the bottom pole up
  switch (body.kind) {
    case K::mesh:
      return body.mesh;
    case K::box: {
      TriangleMesh m;
      for (int k = 0; k < 8; ++k)
        m.vertices.emplace_back((k & 1 ? 0.5 : -0.5) * body.a, (k & 2 ? 0.5 : -0.5) * body.b,
                                (k & 4 ? 0.5 : -0.5) * body.c);
      // Two triangles per face, counter-clockwise from outside.
      const int q[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                           {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
      for (const auto& f : q) {
        m.triangles.push_back({f[0], f[1], f[2]});
        m.triangles.push_back({f[0], f[2], f[3]});
      }
      return m;
    }
    case K::sphere: {
      const int n = detail::sectors(body.r, tol);
      p.emplace_back(0.0, -body.r);
      detail::arc(p, 0, 0, body.r, -pi / 2, pi / 2, std::max(4, n / 2));
      p.back().first = 0;
      return detail::revolve(p, n);
    }
    case K::cylinder: {
      const int n = detail::sectors(body.r, tol);
      p = {{0.0, 0.0}, {body.r, 0.0}, {body.r, body.h}, {0.0, body.h}};
      return detail::revolve(p, n);
    }
    case K::flat_cutter:
    case K::ball_cutter:
    case K::bull_cutter: {
      const double R = body.D / 2;
      const double rc = body.kind == K::flat_cutter   ? 0.0
                        : body.kind == K::ball_cutter ? R
                                                      : body.rc;
      const int n = detail::sectors(R, tol);
      p.emplace_back(0.0, 0.0);
      if (rc < R) p.emplace_back(R - rc, 0.0);
      if (rc > 0) detail::arc(p, R - rc, rc, rc, -pi / 2, 0, std::max(2, n / 4));
      if (body.L > rc) p.emplace_back(R, body.L);
      p.emplace_back(0.0, body.L);
      return detail::revolve(p, n);
    }
  }
  return {};
}

/// The largest distance of a point of the body from the moving origin: the radius of every
/// point's lever arm under the motion's rotation.
inline double radius(const Body& body) {
  using K = Body::Kind;
  switch (body.kind) {
    case K::sphere:
      return body.r;
    case K::box:
      return 0.5 * std::sqrt(body.a * body.a + body.b * body.b + body.c * body.c);
    case K::cylinder:
      return std::hypot(body.r, body.h);
    case K::flat_cutter:
    case K::ball_cutter:
    case K::bull_cutter:
      return std::hypot(body.D / 2, body.L);
    case K::mesh: {
      double r = 0;
      for (const auto& v : body.mesh.vertices) r = std::max(r, v.norm());
      return r;
    }
  }
  return 0;
}

namespace detail {

/// The signed distance from (rho, z), rho >= 0, to the meridian section of a solid of
/// revolution about z: 0 <= z <= L, radius R, and the bottom corner rounded with radius rc
/// (0: a cylinder; R: a ball end). The section is convex and holds the axis, so the distance
/// in the half-plane is the distance in space. Outside, the nearest point is on the top
/// edge, its outer corner, the side, the bottom or the corner arc, by the zone of (rho, z);
/// inside, the depth is the least distance to the section's supporting lines (convex): the
/// top, the side, the bottom and, in the corner's quadrant, the arc's tangents.
/// `grad`, when given, receives the derivatives along rho and z of the piece that gives the
/// value: the unit vector from the nearest point outside, the outward normal of the nearest
/// supporting line inside.
inline double revolved_distance(double rho, double z, double R, double rc, double L,
                                double* grad = nullptr) {
  auto with = [grad](double v, double dr, double dz) {
    if (grad) {
      grad[0] = dr;
      grad[1] = dz;
    }
    return v;
  };
  const double cx = R - rc, cz = rc;  // the corner arc's centre
  const bool corner = rho > cx && z < cz;
  const double dc = corner ? std::sqrt((rho - cx) * (rho - cx) + (z - cz) * (z - cz)) : 0.0;
  if (z > L) {
    if (rho <= R) return with(z - L, 0, 1);
    const double d = std::sqrt((rho - R) * (rho - R) + (z - L) * (z - L));
    return with(d, (rho - R) / d, (z - L) / d);
  }
  if (corner) {
    if (dc > rc) return with(dc - rc, (rho - cx) / dc, (z - cz) / dc);
  } else if (z < 0) {
    return with(-z, 0, -1);
  } else if (rho > R) {
    return with(rho - R, 1, 0);
  }
  double depth = L - z, dr = 0, dz = 1;
  if (R - rho < depth) {
    depth = R - rho;
    dr = 1;
    dz = 0;
  }
  if (z < depth) {
    depth = z;
    dr = 0;
    dz = -1;
  }
  if (corner && rc - dc < depth) {  // dc > 0: rho > cx
    depth = rc - dc;
    dr = (rho - cx) / dc;
    dz = (z - cz) / dc;
  }
  return with(-depth, dr, dz);
}

}  // namespace detail

/// The signed distance from the point x of the moving space to the body: negative inside,
/// exact for the sphere, box, cylinder and cutters (up to rounding); for a mesh, the distance
/// to its nearest triangle with the sign of its winding number (linear in its size).
inline double signed_distance(const Body& body, const Eigen::Vector3d& x) {
  using K = Body::Kind;
  switch (body.kind) {
    case K::sphere:
      return x.norm() - body.r;
    case K::box: {
      const Eigen::Vector3d q = x.cwiseAbs() - 0.5 * Eigen::Vector3d(body.a, body.b, body.c);
      return q.cwiseMax(0.0).norm() + std::min(q.maxCoeff(), 0.0);
    }
    case K::cylinder:
      return detail::revolved_distance(std::sqrt(x.x() * x.x() + x.y() * x.y()), x.z(), body.r, 0,
                                       body.h);
    case K::flat_cutter:
    case K::ball_cutter:
    case K::bull_cutter: {
      const double R = body.D / 2;
      const double rc = body.kind == K::flat_cutter   ? 0.0
                        : body.kind == K::ball_cutter ? R
                                                      : body.rc;
      return detail::revolved_distance(std::sqrt(x.x() * x.x() + x.y() * x.y()), x.z(), R, rc,
                                       body.L);
    }
    case K::mesh:
      return body.index ? body.index->signed_distance(x) : detail::mesh_distance(body.mesh, x);
  }
  return HUGE_VAL;
}

/// Gives a mesh body its distance index (a closed, consistently oriented mesh: validate()).
inline void index_mesh(Body& body) {
  if (body.kind == Body::Kind::mesh) body.index = std::make_shared<detail::MeshIndex>(body.mesh);
}

/// Whether the body is convex: every kind but the mesh (which may be, but is not assumed).
inline bool is_convex(const Body& body) { return body.kind != Body::Kind::mesh; }

/// The signed distance from x to a convex body (is_convex), and a subgradient g of it at x
/// (a mesh: see below):
/// sd(y) >= sd(x) + g . (y - x) for every y, since the signed distance to a convex set is a
/// convex function. g is the unit vector from the nearest point outside, the outward normal
/// of the nearest face (or supporting plane) inside, and 0 where every direction is a
/// subgradient's (the centre of a sphere, the axis of a revolved body). Up to rounding.
/// `near_within`, when the caller knows the distance is below it, lets a mesh search only
/// that far (and all of it when it was wrong).
inline double signed_distance(const Body& body, const Eigen::Vector3d& x, Eigen::Vector3d& g,
                              double near_within = HUGE_VAL) {
  using K = Body::Kind;
  g.setZero();
  switch (body.kind) {
    case K::sphere: {
      const double n = x.norm();
      if (n > 0) g = x / n;
      return n - body.r;
    }
    case K::box: {
      const Eigen::Vector3d half = 0.5 * Eigen::Vector3d(body.a, body.b, body.c);
      const Eigen::Vector3d q = x.cwiseAbs() - half;
      const Eigen::Vector3d s(x.x() < 0 ? -1.0 : 1.0, x.y() < 0 ? -1.0 : 1.0,
                              x.z() < 0 ? -1.0 : 1.0);
      const Eigen::Vector3d out = q.cwiseMax(0.0);
      const double n = out.norm();
      if (n > 0) {
        g = s.cwiseProduct(out) / n;
        return n;
      }
      Eigen::Index i = 0;
      const double m = q.maxCoeff(&i);
      g(i) = s(i);
      return m;
    }
    case K::cylinder:
    case K::flat_cutter:
    case K::ball_cutter:
    case K::bull_cutter: {
      const bool cyl = body.kind == K::cylinder;
      const double R = cyl ? body.r : body.D / 2;
      const double rc = cyl || body.kind == K::flat_cutter ? 0.0
                        : body.kind == K::ball_cutter      ? R
                                                           : body.rc;
      const double rho = std::sqrt(x.x() * x.x() + x.y() * x.y());
      double d[2];
      const double v = detail::revolved_distance(rho, x.z(), R, rc, cyl ? body.h : body.L, d);
      if (rho > 0) {
        g.x() = d[0] * x.x() / rho;
        g.y() = d[0] * x.y() / rho;
      }
      g.z() = d[1];
      return v;
    }
    case K::mesh: {
      // Not convex: g, the unit vector from the nearest point (negated inside), is a
      // direction to try, not a subgradient.
      if (!body.index) return signed_distance(body, x);
      Eigen::Vector3d near;
      double d = body.index->signed_distance(x, &near, near_within);
      if (!(d < HUGE_VAL)) d = body.index->signed_distance(x, &near);
      if (std::abs(d) > 0 && std::isfinite(d)) g = (x - near) / d;
      return d;
    }
  }
  return HUGE_VAL;
}

}  // namespace qmotion::sweep
