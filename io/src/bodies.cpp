// io/src/bodies.cpp: bodies given as text or mesh files (docs/formats.md, "Bodies").
#include <cmath>
#include <cstring>
#include <map>
#include <memory>
#include <qmotion/cam/stock.hpp>
#include <qmotion/io/atomic_file.hpp>
#include <qmotion/io/bodies.hpp>
#include <qmotion/io/json_number.hpp>
#include <qmotion/io/occt.hpp>
#include <qmotion/io/point_text.hpp>
#include <qmotion/kernel/error.hpp>
#include <sstream>
#include <utility>

namespace qmotion::io {
namespace {

using sweep::Body;
using sweep::TriangleMesh;

void expect_count(const std::vector<double>& v, std::size_t n, const std::string& spec,
                  const char* form) {
  if (v.size() != n)
    throw Error(Errc::invalid_input, "body '" + spec + "': expected " + form + ", found " +
                                         std::to_string(v.size()) + " numbers");
}

/// Welds vertices with identical coordinates (STL repeats them per triangle).
class Welder {
 public:
  int add(const Eigen::Vector3d& p) {
    const auto key = std::make_tuple(p.x(), p.y(), p.z());
    const auto [it, fresh] = index_.emplace(key, static_cast<int>(mesh.vertices.size()));
    if (fresh) mesh.vertices.push_back(p);
    return it->second;
  }
  TriangleMesh mesh;

 private:
  std::map<std::tuple<double, double, double>, int> index_;
};

[[noreturn]] void bad(const std::string& path, const std::string& why) {
  throw Error(Errc::invalid_input, path + ": " + why);
}

Eigen::Vector3d finite_point(double x, double y, double z, const std::string& path,
                             const std::string& where) {
  if (!std::isfinite(x) || !std::isfinite(y) || !std::isfinite(z))
    bad(path, where + ": coordinates must be finite numbers");
  return {x, y, z};
}

float le_f32(const char* p) {
  float f;
  std::memcpy(&f, p, 4);
  return f;
}
std::uint32_t le_u32(const char* p) {
  std::uint32_t v;
  std::memcpy(&v, p, 4);
  return v;
}

TriangleMesh read_stl(const std::string& path, const std::string& text) {
  Welder w;
  // Binary when its size is what its triangle count says (an ASCII file may start "solid").
  if (text.size() >= 84 && 84 + 50ull * le_u32(text.data() + 80) == text.size()) {
    const std::uint32_t n = le_u32(text.data() + 80);
    for (std::uint32_t i = 0; i < n; ++i) {
      const char* t = text.data() + 84 + 50ull * i + 12;
      std::array<int, 3> tri{};
      for (int k = 0; k < 3; ++k)
        tri[static_cast<std::size_t>(k)] =
            w.add(finite_point(le_f32(t + 12 * k), le_f32(t + 12 * k + 4), le_f32(t + 12 * k + 8),
                               path, "triangle " + std::to_string(i)));
      w.mesh.triangles.push_back(tri);
    }
    return w.mesh;
  }
  std::istringstream in(text);
  std::string word;
  std::vector<int> corners;
  while (in >> word) {
    if (word != "vertex") continue;
    double x, y, z;
    if (!(in >> x >> y >> z)) bad(path, "ASCII STL: a vertex without three numbers");
    corners.push_back(w.add(finite_point(x, y, z, path, "vertex")));
    if (corners.size() == 3) {
      w.mesh.triangles.push_back({corners[0], corners[1], corners[2]});
      corners.clear();
    }
  }
  if (!corners.empty()) bad(path, "ASCII STL: a facet without three vertices");
  return w.mesh;
}

TriangleMesh read_obj(const std::string& path, const std::string& text) {
  TriangleMesh m;
  std::istringstream in(text);
  std::string line;
  int number = 0;
  while (std::getline(in, line)) {
    ++number;
    std::istringstream ls(line);
    std::string tag;
    ls >> tag;
    const std::string where = "line " + std::to_string(number);
    if (tag == "v") {
      double x, y, z;
      if (!(ls >> x >> y >> z)) bad(path, where + ": a vertex needs three numbers");
      m.vertices.push_back(finite_point(x, y, z, path, where));
    } else if (tag == "f") {
      std::vector<int> f;
      std::string item;
      while (ls >> item) {
        const long v = std::strtol(item.c_str(), nullptr, 10);  // "v", "v/vt", "v//vn"
        const long n = static_cast<long>(m.vertices.size());
        const long i = v < 0 ? n + v : v - 1;
        if (v == 0 || i < 0 || i >= n) bad(path, where + ": a face names no vertex read");
        f.push_back(static_cast<int>(i));
      }
      if (f.size() < 3) bad(path, where + ": a face needs three vertices");
      for (std::size_t k = 1; k + 1 < f.size(); ++k) m.triangles.push_back({f[0], f[k], f[k + 1]});
    }
  }
  return m;
}

TriangleMesh read_ply(const std::string& path, const std::string& text) {
  const std::size_t end = text.find("end_header");
  if (text.rfind("ply", 0) != 0 || end == std::string::npos) bad(path, "not a PLY file");
  std::istringstream head(text.substr(0, end));
  std::string line, format;
  std::size_t nv = 0, nf = 0;
  std::vector<std::string> vprops;  // types of the vertex properties
  std::string element;
  std::string count_type, index_type;
  while (std::getline(head, line)) {
    std::istringstream ls(line);
    std::string w;
    ls >> w;
    if (w == "format") ls >> format;
    if (w == "element") {
      std::size_t n = 0;
      ls >> element >> n;
      if (element == "vertex") nv = n;
      if (element == "face") nf = n;
    }
    if (w == "property") {
      std::string type;
      ls >> type;
      if (element == "vertex") vprops.push_back(type);
      if (element == "face" && type == "list") ls >> count_type >> index_type;
    }
  }
  if (vprops.size() < 3) bad(path, "PLY: the vertices need x, y and z");
  TriangleMesh m;
  std::vector<std::vector<long>> faces;
  if (format == "ascii") {
    std::istringstream in(text.substr(text.find('\n', end) + 1));
    for (std::size_t i = 0; i < nv; ++i) {
      std::vector<double> v(vprops.size());
      for (auto& x : v)
        if (!(in >> x)) bad(path, "PLY: vertex " + std::to_string(i) + " is short");
      m.vertices.push_back(finite_point(v[0], v[1], v[2], path, "vertex " + std::to_string(i)));
    }
    for (std::size_t i = 0; i < nf; ++i) {
      std::size_t n = 0;
      if (!(in >> n)) bad(path, "PLY: face " + std::to_string(i) + " is short");
      std::vector<long> f(n);
      for (auto& x : f)
        if (!(in >> x)) bad(path, "PLY: face " + std::to_string(i) + " is short");
      faces.push_back(f);
    }
  } else if (format == "binary_little_endian") {
    auto size_of = [&](const std::string& t) -> std::size_t {
      if (t == "double" || t == "float64") return 8;
      if (t == "float" || t == "float32" || t == "int" || t == "uint" || t == "int32" ||
          t == "uint32")
        return 4;
      if (t == "short" || t == "ushort" || t == "int16" || t == "uint16") return 2;
      if (t == "char" || t == "uchar" || t == "int8" || t == "uint8") return 1;
      bad(path, "PLY: unknown property type '" + t + "'");
    };
    auto read_value = [&](const char* p, const std::string& t) -> double {
      const std::size_t s = size_of(t);
      if (t == "double" || t == "float64") {
        double d;
        std::memcpy(&d, p, 8);
        return d;
      }
      if (s == 4 && (t == "float" || t == "float32")) return le_f32(p);
      std::uint32_t u = 0;
      std::memcpy(&u, p, s);
      if (t[0] != 'u' && s < 4 && (u >> (8 * s - 1)))  // sign-extend
        u |= ~std::uint32_t(0) << (8 * s);
      return t[0] == 'u' ? double(u) : double(static_cast<std::int32_t>(u));
    };
    std::size_t at = text.find('\n', end) + 1;
    auto need = [&](std::size_t n) {
      if (at + n > text.size()) bad(path, "PLY: the file ends inside its data");
    };
    for (std::size_t i = 0; i < nv; ++i) {
      double c[3];
      for (std::size_t k = 0; k < vprops.size(); ++k) {
        need(size_of(vprops[k]));
        if (k < 3) c[k] = read_value(text.data() + at, vprops[k]);
        at += size_of(vprops[k]);
      }
      m.vertices.push_back(finite_point(c[0], c[1], c[2], path, "vertex " + std::to_string(i)));
    }
    if (nf && count_type.empty()) bad(path, "PLY: the faces have no index list");
    for (std::size_t i = 0; i < nf; ++i) {
      need(size_of(count_type));
      const auto n = static_cast<std::size_t>(read_value(text.data() + at, count_type));
      at += size_of(count_type);
      std::vector<long> f(n);
      for (auto& x : f) {
        need(size_of(index_type));
        x = static_cast<long>(read_value(text.data() + at, index_type));
        at += size_of(index_type);
      }
      faces.push_back(f);
    }
  } else {
    bad(path, "PLY: format '" + format + "' (expected ascii or binary_little_endian)");
  }
  for (std::size_t i = 0; i < faces.size(); ++i) {
    const auto& f = faces[i];
    for (long v : f)
      if (v < 0 || v >= static_cast<long>(m.vertices.size()))
        bad(path, "PLY: face " + std::to_string(i) + " names no vertex read");
    if (f.size() < 3) bad(path, "PLY: face " + std::to_string(i) + " has fewer than 3 vertices");
    for (std::size_t k = 1; k + 1 < f.size(); ++k)
      m.triangles.push_back(
          {static_cast<int>(f[0]), static_cast<int>(f[k]), static_cast<int>(f[k + 1])});
  }
  return m;
}

Body mesh_file_body(const std::string& path) {
  const std::string text = read_text_file(path);
  const std::string e = lower_extension(path);
  return mesh_body(e == ".stl"   ? read_stl(path, text)
                   : e == ".obj" ? read_obj(path, text)
                                 : read_ply(path, text),
                   path);
}

/// A STEP or IGES solid as OpenCASCADE meshes it within `deflection`, its faces' nodes
/// welded where they coincide (the mesher shares a boundary edge's nodes between its faces).
Body cad_file_body(const std::string& path, double deflection) {
  const CadMesh c = mesh_cad(path, deflection);
  Welder w;
  for (const auto& t : c.triangles) {
    const std::array<int, 3> v{w.add(t[0]), w.add(t[1]), w.add(t[2])};
    if (v[0] != v[1] && v[1] != v[2] && v[0] != v[2]) w.mesh.triangles.push_back(v);
  }
  return mesh_body(std::move(w.mesh), path);
}

}  // namespace

bool is_cad_file(const std::string& spec) {
  const std::string e = lower_extension(spec);
  return spec.find(':') == std::string::npos &&
         (e == ".step" || e == ".stp" || e == ".igs" || e == ".iges");
}

Body mesh_body(sweep::TriangleMesh mesh, const std::string& label) {
  const int n = static_cast<int>(mesh.vertices.size());
  for (std::size_t i = 0; i < mesh.vertices.size(); ++i)
    if (!mesh.vertices[i].allFinite())
      bad(label, "vertex " + std::to_string(i) + " (counted from 0) is not finite");
  for (std::size_t i = 0; i < mesh.triangles.size(); ++i)
    for (int v : mesh.triangles[i])
      if (v < 0 || v >= n)
        bad(label, "triangle " + std::to_string(i) + " (counted from 0) names vertex " +
                       std::to_string(v) + ", outside 0.." + std::to_string(n - 1));
  Body b;
  b.kind = Body::Kind::mesh;
  b.spec = label;
  b.mesh = std::move(mesh);
  require_closed_oriented(b.mesh, label);
  sweep::index_mesh(b);  // closed and oriented: the pseudonormals' sign holds
  return b;
}

void require_closed_oriented(const TriangleMesh& m, const std::string& label) {
  if (m.triangles.empty()) bad(label, "the mesh has no triangles");
  std::map<std::pair<int, int>, int> directed;
  for (const auto& t : m.triangles) {
    if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2])
      bad(label, "the mesh has a degenerate triangle (a vertex repeated)");
    for (int k = 0; k < 3; ++k) {
      const std::pair<int, int> e{t[static_cast<std::size_t>(k)],
                                  t[static_cast<std::size_t>((k + 1) % 3)]};
      if (++directed[e] > 1)
        bad(label, "the mesh is not a consistently oriented 2-manifold: the edge from vertex " +
                       std::to_string(e.first) + " to vertex " + std::to_string(e.second) +
                       " (counted from 0) is used twice in one direction");
    }
  }
  for (const auto& [e, n] : directed)
    if (!directed.count({e.second, e.first}))
      bad(label, "the mesh is open: the edge from vertex " + std::to_string(e.first) +
                     " to vertex " + std::to_string(e.second) +
                     " (counted from 0) bounds one triangle only");
  // Outward: the signed volume (divergence theorem, sum of det(v0, v1, v2) / 6) is positive
  // for counter-clockwise triangles seen from outside, negative for an inside-out mesh.
  double six_volume = 0;
  for (const auto& t : m.triangles)
    six_volume += m.vertices[static_cast<std::size_t>(t[0])].dot(
        m.vertices[static_cast<std::size_t>(t[1])].cross(
            m.vertices[static_cast<std::size_t>(t[2])]));
  if (!(six_volume > 0))
    bad(label, "the mesh is inside out or flat: its signed volume is " +
                   kernel::detail::format_double(six_volume / 6) +
                   " (triangles must turn counter-clockwise seen from outside; reverse them)");
}

Body read_body(const std::string& spec, double cad_deflection) {
  const auto colon = spec.find(':');
  const std::string kind = spec.substr(0, colon);
  const std::string rest = colon == std::string::npos ? "" : spec.substr(colon + 1);
  Body b;
  b.spec = spec;
  const std::string e = lower_extension(spec);
  if (colon == std::string::npos && (e == ".stl" || e == ".obj" || e == ".ply"))
    return mesh_file_body(spec);
  if (is_cad_file(spec)) return cad_file_body(spec, cad_deflection);
  // The shorthands: a name, then the sizes in the order the form gives them.
  struct Form {
    const char *name, *usage;
    Body::Kind kind;
    std::vector<double Body::*> sizes;
  };
  using K = Body::Kind;
  static const Form forms[] = {
      {"sphere", "sphere:r", K::sphere, {&Body::r}},
      {"box", "box:a,b,c", K::box, {&Body::a, &Body::b, &Body::c}},
      {"cylinder", "cylinder:r,h", K::cylinder, {&Body::r, &Body::h}},
      {"cutter:flat", "cutter:flat,D,L", K::flat_cutter, {&Body::D, &Body::L}},
      {"cutter:ball", "cutter:ball,D,L", K::ball_cutter, {&Body::D, &Body::L}},
      {"cutter:bull", "cutter:bull,D,rc,L", K::bull_cutter, {&Body::D, &Body::rc, &Body::L}},
  };
  std::string name = kind, numbers = rest;
  if (kind == "cutter") {
    const auto c = rest.find(',');
    name = "cutter:" + rest.substr(0, c);
    numbers = c == std::string::npos ? "" : rest.substr(c + 1);
  }
  const Form* form = nullptr;
  for (const auto& f : forms)
    if (name == f.name) form = &f;
  if (!form && kind == "cutter")
    throw Error(Errc::invalid_input, "body '" + spec + "': unknown cutter '" + name.substr(7) +
                                         "' (expected flat, ball or bull)");
  if (!form)
    throw Error(Errc::invalid_input,
                "body '" + spec +
                    "': unknown body (expected sphere:r, box:a,b,c, cylinder:r,h, "
                    "cutter:flat,D,L, cutter:ball,D,L, cutter:bull,D,rc,L, an .stl, .obj or "
                    ".ply mesh file, or a STEP or IGES solid)");
  const auto v = parse_numbers(numbers, "body '" + spec + "'");
  expect_count(v, form->sizes.size(), spec, form->usage);
  b.kind = form->kind;
  for (std::size_t i = 0; i < v.size(); ++i) b.*(form->sizes[i]) = v[i];
  sweep::validate(b);
  return b;
}

cam::Stock read_stock(const std::string& spec, const std::string& option, double cad_deflection) {
  cam::Stock stock;
  const std::string where = option + " '" + spec + "'";
  if (spec.rfind("box:", 0) == 0) {
    const auto v = parse_numbers(spec.substr(4), where);
    if (v.size() != 6)
      throw Error(Errc::invalid_input, where +
                                           ": expected box:x0,y0,z0,x1,y1,z1 (two opposite "
                                           "corners, mm), got " +
                                           std::to_string(v.size()) + " numbers");
    const Eigen::Vector3d a(v[0], v[1], v[2]), b(v[3], v[4], v[5]);
    stock.box = Eigen::AlignedBox3d(a.cwiseMin(b), a.cwiseMax(b));
    if (!(stock.box.sizes().minCoeff() > 0))
      throw Error(Errc::invalid_input, where + ": the box has an edge of length 0");
    return stock;
  }
  const std::string e = lower_extension(spec);
  if (e != ".stl" && e != ".obj" && e != ".ply" && !is_cad_file(spec))
    throw Error(Errc::invalid_input, where +
                                         ": expected box:x0,y0,z0,x1,y1,z1, a closed .stl, .obj "
                                         "or .ply mesh, or a STEP or IGES solid");
  stock.body = std::make_shared<Body>(read_body(spec, cad_deflection));
  return stock;
}

}  // namespace qmotion::io
