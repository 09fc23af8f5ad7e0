// Tests of <qmotion/io/bodies.hpp>: mesh bodies read from STL (binary and ASCII), OBJ and
// PLY (binary and ASCII) as written by io::write_mesh; open, non-manifold and
// inconsistently oriented meshes refused, naming the file.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <qmotion/io/bodies.hpp>
#include <qmotion/io/mesh.hpp>

#include "io_test_util.hpp"

namespace qmotion {
namespace {

namespace fs = std::filesystem;

io::Mesh as_io_mesh(const sweep::TriangleMesh& m) {
  io::Mesh out;
  out.vertices = m.vertices;
  out.triangles = m.triangles;
  return out;
}

TEST(Bodies, MeshFilesReadBackClosedWithTheirVolume) {
  const auto cyl = sweep::triangulate(io::read_body("cylinder:2,5"), 1e-2);
  for (const char* name : {"b.stl", "a.stl", "b.obj", "b.ply", "a.ply"}) {
    SCOPED_TRACE(name);
    const std::string path = test::scratch_path("bodies", name).string();
    io::write_mesh(path, as_io_mesh(cyl), name[0] == 'a');
    const sweep::Body b = io::read_body(path);
    EXPECT_EQ(b.kind, sweep::Body::Kind::mesh);
    EXPECT_EQ(b.mesh.vertices.size(), cyl.vertices.size());
    EXPECT_EQ(b.mesh.triangles.size(), cyl.triangles.size());
    EXPECT_NEAR(test::enclosed_volume(b.mesh), test::enclosed_volume(cyl),
                1e-5 * test::enclosed_volume(cyl));  // STL holds floats
    EXPECT_NEAR(sweep::radius(b), sweep::radius(io::read_body("cylinder:2,5")), 1e-2);
    fs::remove(path);
  }
}

TEST(Bodies, OpenOrInconsistentMeshesAreRefused) {
  const auto box = sweep::triangulate(io::read_body("box:1,1,1"), 1e-2);
  auto refused = [&](const std::string& name, const sweep::TriangleMesh& m, const char* why) {
    const std::string path = test::scratch_path("bodies", name).string();
    io::write_mesh(path, as_io_mesh(m), true);
    EXPECT_TRUE(test::throws_error([&] { io::read_body(path); }, Errc::invalid_input, {path, why}))
        << name;
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
  const std::string empty = test::scratch_path("bodies", "empty.stl").string();
  std::ofstream(empty) << "solid x\nendsolid x\n";
  EXPECT_THROW(io::read_body(empty), Error);
  fs::remove(empty);
}

}  // namespace
}  // namespace qmotion
