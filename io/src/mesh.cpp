// io/src/mesh.cpp
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <map>
#include <qmotion/io/atomic_file.hpp>
#include <qmotion/io/mesh.hpp>
#include <qmotion/io/occt.hpp>
#include <qmotion/kernel/error.hpp>
#include <qmotion/sweep/surface_eval.hpp>
#include <sstream>
#include <unordered_map>

namespace qmotion::io {
namespace {

constexpr double kPi = 3.14159265358979323846;

/// Welds nodes closer than tol (a hash grid of cell tol, the 27 cells around a node).
class Welder {
 public:
  Welder(double tol, std::vector<Eigen::Vector3d>& vertices) : tol_(tol), v_(vertices) {}
  int add(const Eigen::Vector3d& p) {
    const std::array<long long, 3> c = cell(p);
    for (long long dx = -1; dx <= 1; ++dx)
      for (long long dy = -1; dy <= 1; ++dy)
        for (long long dz = -1; dz <= 1; ++dz) {
          const auto it = grid_.find(key({c[0] + dx, c[1] + dy, c[2] + dz}));
          if (it == grid_.end()) continue;
          for (int i : it->second)
            if ((v_[static_cast<std::size_t>(i)] - p).norm() <= tol_) return i;
        }
    v_.push_back(p);
    const int i = static_cast<int>(v_.size()) - 1;
    grid_[key(c)].push_back(i);
    return i;
  }

 private:
  std::array<long long, 3> cell(const Eigen::Vector3d& p) const {
    return {static_cast<long long>(std::floor(p(0) / tol_)),
            static_cast<long long>(std::floor(p(1) / tol_)),
            static_cast<long long>(std::floor(p(2) / tol_))};
  }
  static std::uint64_t key(const std::array<long long, 3>& c) {
    std::uint64_t h = 1469598103934665603ull;
    for (long long x : c) h = (h ^ static_cast<std::uint64_t>(x)) * 1099511628211ull;
    return h;
  }
  double tol_;
  std::vector<Eigen::Vector3d>& v_;
  std::unordered_map<std::uint64_t, std::vector<int>> grid_;
};

/// Welds, measures and checks one meshing of the shell.
Mesh assemble(const sweep::NurbsShell<double>& shell, const std::vector<FaceMesh>& faces,
              double size) {
  Mesh m;
  std::vector<sweep::SurfaceEvaluator> eval;
  for (const auto& f : shell.faces) eval.emplace_back(f);
  Welder weld(1e-9 * std::max(size, 1e-300), m.vertices);
  for (const auto& fm : faces) {
    const auto distance = [&](const Eigen::Vector3d& x, const Eigen::Vector2d& uv) {
      if (fm.face < 0) return std::abs(fm.plane_normal.dot(x - fm.plane_point));
      return eval[static_cast<std::size_t>(fm.face)].distance(x, uv(0), uv(1));
    };
    for (std::size_t i = 0; i < fm.nodes.size(); ++i) {
      const double e =
          fm.face < 0
              ? std::abs(fm.plane_normal.dot(fm.nodes[i] - fm.plane_point))
              : (eval[static_cast<std::size_t>(fm.face)](fm.uv[i](0), fm.uv[i](1)) - fm.nodes[i])
                    .norm();
      m.max_vertex_error = std::max(m.max_vertex_error, e);
    }
    std::vector<int> id;
    id.reserve(fm.nodes.size());
    for (const auto& p : fm.nodes) id.push_back(weld.add(p));
    for (const auto& t : fm.triangles) {
      const auto at = [&](int k) {
        return static_cast<std::size_t>(t[static_cast<std::size_t>(k)]);
      };
      const Eigen::Vector3d c = (fm.nodes[at(0)] + fm.nodes[at(1)] + fm.nodes[at(2)]) / 3;
      const Eigen::Vector2d cu = (fm.uv[at(0)] + fm.uv[at(1)] + fm.uv[at(2)]) / 3;
      m.max_deviation = std::max(m.max_deviation, distance(c, cu));
      for (int k = 0; k < 3; ++k) {
        const std::size_t a = at(k), b = at((k + 1) % 3);
        m.max_deviation = std::max(
            m.max_deviation, distance((fm.nodes[a] + fm.nodes[b]) / 2, (fm.uv[a] + fm.uv[b]) / 2));
      }
      m.deviation_samples += 4;
      const std::array<int, 3> g{id[at(0)], id[at(1)], id[at(2)]};
      if (g[0] != g[1] && g[1] != g[2] && g[0] != g[2]) m.triangles.push_back(g);
    }
  }
  // Closed: every undirected edge twice; oriented: every directed edge once.
  std::map<std::pair<int, int>, int> directed;
  for (const auto& t : m.triangles)
    for (int k = 0; k < 3; ++k)
      ++directed[{t[static_cast<std::size_t>(k)], t[static_cast<std::size_t>((k + 1) % 3)]}];
  m.closed = !m.triangles.empty();
  m.oriented = m.closed;
  for (const auto& [e, n] : directed) {
    const auto back = directed.find({e.second, e.first});
    const int reverse = back == directed.end() ? 0 : back->second;
    if (n + reverse != 2) m.closed = false;
    if (n != 1 || reverse != 1) m.oriented = false;
  }
  return m;
}

void put_u32(std::string& s, std::uint32_t x) {
  for (int i = 0; i < 4; ++i) s.push_back(static_cast<char>((x >> (8 * i)) & 0xff));
}
void put_f32(std::string& s, float f) {
  std::uint32_t x;
  std::memcpy(&x, &f, 4);
  put_u32(s, x);
}
void put_f64(std::string& s, double d) {
  std::uint64_t x;
  std::memcpy(&x, &d, 8);
  for (int i = 0; i < 8; ++i) s.push_back(static_cast<char>((x >> (8 * i)) & 0xff));
}

Eigen::Vector3d normal_of(const Mesh& m, const std::array<int, 3>& t) {
  const auto& a = m.vertices[static_cast<std::size_t>(t[0])];
  const Eigen::Vector3d n = (m.vertices[static_cast<std::size_t>(t[1])] - a)
                                .cross(m.vertices[static_cast<std::size_t>(t[2])] - a);
  return n.norm() > 0 ? Eigen::Vector3d(n.normalized()) : n;
}

}  // namespace

bool is_mesh_path(const std::string& path) {
  const std::string e = lower_extension(path);
  return e == ".stl" || e == ".obj" || e == ".ply";
}

Mesh mesh_shell_within(const sweep::NurbsShell<double>& shell, const MeshOptions& o,
                       const std::string& path) {
  if (!(o.deflection > 0) || !std::isfinite(o.deflection))
    throw Error(Errc::invalid_input, "--deflection: expected a positive length");
  if (!(o.angle_deg > 0) || !(o.angle_deg <= 90))
    throw Error(Errc::invalid_input, "--angle: expected degrees in (0, 90]");
  const double size = sweep::diagonal(shell);
  double d = o.deflection;
  for (int round = 1; round <= 8; ++round) {
    Mesh m = assemble(shell, mesh_shell(shell, d, o.angle_deg * kPi / 180, path), size);
    m.deflection = d;
    m.rounds = round;
    if (m.max_deviation <= o.deflection) return m;
    d *= std::clamp(0.8 * o.deflection / m.max_deviation, 0.1, 0.8);
  }
  std::ostringstream os;
  os << path << ": OpenCASCADE's mesher did not reach the deflection " << o.deflection
     << " in 8 rounds (down to " << d << ")";
  throw Error(Errc::numerical_failure, os.str());
}

void write_mesh(const std::string& path, const Mesh& m, bool ascii) {
  const std::string e = lower_extension(path);
  std::string out;
  std::ostringstream os;
  os.precision(17);
  if (e == ".stl" && !ascii) {
    std::string header = "qmotion mesh (binary STL, float32 coordinates)";
    header.resize(80, ' ');
    out = header;
    put_u32(out, static_cast<std::uint32_t>(m.triangles.size()));
    for (const auto& t : m.triangles) {
      const Eigen::Vector3d n = normal_of(m, t);
      for (int k = 0; k < 3; ++k) put_f32(out, static_cast<float>(n(k)));
      for (int v : t)
        for (int k = 0; k < 3; ++k)
          put_f32(out, static_cast<float>(m.vertices[static_cast<std::size_t>(v)](k)));
      out.append(2, '\0');
    }
  } else if (e == ".stl") {
    os << "solid qmotion\n";
    for (const auto& t : m.triangles) {
      const Eigen::Vector3d n = normal_of(m, t);
      os << " facet normal " << n(0) << " " << n(1) << " " << n(2) << "\n  outer loop\n";
      for (int v : t) {
        const auto& p = m.vertices[static_cast<std::size_t>(v)];
        os << "   vertex " << p(0) << " " << p(1) << " " << p(2) << "\n";
      }
      os << "  endloop\n endfacet\n";
    }
    os << "endsolid qmotion\n";
    out = os.str();
  } else if (e == ".obj") {
    os << "# qmotion mesh: " << m.vertices.size() << " vertices, " << m.triangles.size()
       << " triangles\n";
    for (const auto& p : m.vertices) os << "v " << p(0) << " " << p(1) << " " << p(2) << "\n";
    for (const auto& t : m.triangles)
      os << "f " << t[0] + 1 << " " << t[1] + 1 << " " << t[2] + 1 << "\n";
    out = os.str();
  } else if (e == ".ply") {
    os << "ply\nformat " << (ascii ? "ascii" : "binary_little_endian") << " 1.0\n"
       << "comment qmotion mesh\nelement vertex " << m.vertices.size()
       << "\nproperty double x\nproperty double y\nproperty double z\n";
    const bool coloured = m.colours.size() == m.vertices.size() && !m.vertices.empty();
    if (coloured) os << "property uchar red\nproperty uchar green\nproperty uchar blue\n";
    os << "element face " << m.triangles.size()
       << "\nproperty list uchar int vertex_indices\nend_header\n";
    if (ascii) {
      for (std::size_t i = 0; i < m.vertices.size(); ++i) {
        const auto& p = m.vertices[i];
        os << p(0) << " " << p(1) << " " << p(2);
        if (coloured)
          for (unsigned char c : m.colours[i]) os << " " << int(c);
        os << "\n";
      }
      for (const auto& t : m.triangles) os << "3 " << t[0] << " " << t[1] << " " << t[2] << "\n";
      out = os.str();
    } else {
      out = os.str();
      for (std::size_t i = 0; i < m.vertices.size(); ++i) {
        for (int k = 0; k < 3; ++k) put_f64(out, m.vertices[i](k));
        if (coloured)
          for (unsigned char c : m.colours[i]) out.push_back(static_cast<char>(c));
      }
      for (const auto& t : m.triangles) {
        out.push_back(3);
        for (int v : t) put_u32(out, static_cast<std::uint32_t>(v));
      }
    }
  } else {
    throw Error(Errc::invalid_input, "-o " + path + ": expected a .stl, .obj or .ply mesh");
  }
  write_file_atomic(path, out);
}

}  // namespace qmotion::io
