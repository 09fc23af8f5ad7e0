// Tests of <qmotion/io/bodies.hpp>: mesh bodies read from STL (binary and ASCII), OBJ and
// PLY (binary and ASCII) as written by io::write_mesh; open, non-manifold and
// inconsistently oriented meshes refused, naming the file.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <qmotion/io/bodies.hpp>
#include <qmotion/io/mesh.hpp>

namespace qmotion {
namespace {

namespace fs = std::filesystem;

io::Mesh as_io_mesh(const sweep::TriangleMesh& m) {
  io::Mesh out;
  out.vertices = m.vertices;
  out.triangles = m.triangles;
  return out;
}

double volume(const sweep::TriangleMesh& m) {
  double v = 0;
  for (const auto& t : m.triangles)
    v += m.vertices[static_cast<std::size_t>(t[0])].dot(
        m.vertices[static_cast<std::size_t>(t[1])].cross(
            m.vertices[static_cast<std::size_t>(t[2])]));
  return v / 6;
}

TEST(Bodies, MeshFilesReadBackClosedWithTheirVolume) {
  const auto cyl = sweep::triangulate(io::read_body("cylinder:2,5"), 1e-2);
  const std::string dir = fs::temp_directory_path().string();
  for (const char* name : {"b.stl", "a.stl", "b.obj", "b.ply", "a.ply"}) {
    SCOPED_TRACE(name);
    const std::string path = dir + "/qmotion_body_" + name;
    io::write_mesh(path, as_io_mesh(cyl), name[0] == 'a');
    const sweep::Body b = io::read_body(path);
    EXPECT_EQ(b.kind, sweep::Body::Kind::mesh);
    EXPECT_EQ(b.mesh.vertices.size(), cyl.vertices.size());
    EXPECT_EQ(b.mesh.triangles.size(), cyl.triangles.size());
    EXPECT_NEAR(volume(b.mesh), volume(cyl), 1e-5 * volume(cyl));  // STL holds floats
    EXPECT_NEAR(sweep::radius(b), sweep::radius(io::read_body("cylinder:2,5")), 1e-2);
    fs::remove(path);
  }
}

TEST(Bodies, OpenOrInconsistentMeshesAreRefused) {
  const auto box = sweep::triangulate(io::read_body("box:1,1,1"), 1e-2);
  const std::string dir = fs::temp_directory_path().string();
  auto refused = [&](const std::string& name, const sweep::TriangleMesh& m, const char* why) {
    const std::string path = dir + "/qmotion_body_" + name;
    io::write_mesh(path, as_io_mesh(m), true);
    try {
      io::read_body(path);
      ADD_FAILURE() << name << " accepted";
    } catch (const Error& e) {
      EXPECT_EQ(e.code(), Errc::invalid_input);
      EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find(why), std::string::npos) << e.what();
    }
    fs::remove(path);
  };
  auto open = box;
  open.triangles.pop_back();
  refused("open.obj", open, "open");
  auto flipped = box;
  std::swap(flipped.triangles[0][1], flipped.triangles[0][2]);
  refused("flipped.obj", flipped, "oriented");
  auto doubled = box;  // two boxes sharing an edge's worth of faces: a non-manifold edge
  doubled.triangles.insert(doubled.triangles.end(), box.triangles.begin(), box.triangles.end());
  refused("doubled.obj", doubled, "oriented");
  std::ofstream(dir + "/qmotion_body_empty.stl") << "solid x\nendsolid x\n";
  EXPECT_THROW(io::read_body(dir + "/qmotion_body_empty.stl"), Error);
  fs::remove(dir + "/qmotion_body_empty.stl");
}

}  // namespace
}  // namespace qmotion
