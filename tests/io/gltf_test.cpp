// Tests of <qmotion/io/gltf.hpp>: the file holds what was given, byte for byte, in a layout
// glTF 2.0 requires (GLB chunks and alignment, accessor bounds, the y-up root); refusals
// leave no file.
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <qmotion/io/gltf.hpp>
#include <qmotion/kernel/error.hpp>
#include <sstream>

#include "io_test_util.hpp"

namespace qmotion {
namespace {

namespace fs = std::filesystem;

std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

std::uint32_t u32(const std::string& s, std::size_t at) {
  std::uint32_t v;
  std::memcpy(&v, s.data() + at, 4);
  return v;
}

io::GltfAnimation sample() {
  io::GltfAnimation a;
  a.name = "tetra";
  a.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1.5f}};
  a.triangles = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  a.times = {0, 0.25f, 1};
  a.translations = {{0, 0, 0}, {1, 2, 3}, {-1, 0.5f, 2}};
  a.rotations = {{0, 0, 0, 1}, {0, 0, 0.38268343f, 0.92387953f}, {0, 0, 0.70710677f, 0.70710677f}};
  a.extras = {{"tolerance", 0.001}};
  return a;
}

/// The bytes an accessor covers.
std::string accessor_bytes(const nlohmann::json& g, const std::string& bin, int i,
                           std::size_t width) {
  const auto& acc = g["accessors"][static_cast<std::size_t>(i)];
  const auto& view = g["bufferViews"][acc["bufferView"].get<std::size_t>()];
  const std::size_t offset = view["byteOffset"], length = view["byteLength"];
  EXPECT_EQ(offset % 4, 0u);
  EXPECT_EQ(length, acc["count"].get<std::size_t>() * width * 4);
  EXPECT_LE(offset + length, bin.size());
  return bin.substr(offset, length);
}

template <typename T, std::size_t N>
std::string raw(const std::vector<std::array<T, N>>& v) {
  return std::string(reinterpret_cast<const char*>(v.data()), v.size() * N * sizeof(T));
}

void check_content(const nlohmann::json& g, const std::string& bin, const io::GltfAnimation& a) {
  EXPECT_EQ(g["asset"]["version"], "2.0");
  EXPECT_EQ(g["asset"]["extras"]["tolerance"], 0.001);
  // The root turns z-up into y-up: (x, y, z) -> (x, z, -y), column-major.
  const std::vector<double> m = g["nodes"][0]["matrix"];
  EXPECT_EQ(m, (std::vector<double>{1, 0, 0, 0, 0, 0, -1, 0, 0, 1, 0, 0, 0, 0, 0, 1}));
  const auto& prim = g["meshes"][0]["primitives"][0];
  const int pos = prim["attributes"]["POSITION"], idx = prim["indices"];
  EXPECT_EQ(accessor_bytes(g, bin, pos, 3), raw(a.positions));
  EXPECT_EQ(accessor_bytes(g, bin, idx, 1), raw(a.triangles));
  EXPECT_EQ(g["accessors"][static_cast<std::size_t>(pos)]["min"], (std::vector<float>{0, 0, 0}));
  EXPECT_EQ(g["accessors"][static_cast<std::size_t>(pos)]["max"], (std::vector<float>{1, 1, 1.5f}));
  const auto& anim = g["animations"][0];
  for (const auto& ch : anim["channels"]) {
    const auto& s = anim["samplers"][ch["sampler"].get<std::size_t>()];
    EXPECT_EQ(s["interpolation"], "LINEAR");
    EXPECT_EQ(ch["target"]["node"], 1);
    std::vector<std::array<float, 1>> t;
    for (float x : a.times) t.push_back({x});
    EXPECT_EQ(accessor_bytes(g, bin, s["input"], 1), raw(t));
    EXPECT_EQ(g["accessors"][s["input"].get<std::size_t>()]["max"], std::vector<float>{1});
    if (ch["target"]["path"] == "translation")
      EXPECT_EQ(accessor_bytes(g, bin, s["output"], 3), raw(a.translations));
    else
      EXPECT_EQ(accessor_bytes(g, bin, s["output"], 4), raw(a.rotations));
  }
}

TEST(Gltf, BinaryHoldsTheChunksAndTheNumbersAsGiven) {
  const std::string path = test::scratch_path("gltf", "animation.glb").string();
  const auto a = sample();
  io::write_gltf(path, a);
  const std::string f = slurp(path);
  ASSERT_GE(f.size(), 28u);
  EXPECT_EQ(f.substr(0, 4), "glTF");
  EXPECT_EQ(u32(f, 4), 2u);
  EXPECT_EQ(u32(f, 8), f.size());
  const std::uint32_t jlen = u32(f, 12);
  EXPECT_EQ(f.substr(16, 4), "JSON");
  EXPECT_EQ(jlen % 4, 0u);
  const auto g = nlohmann::json::parse(f.substr(20, jlen));
  const std::uint32_t blen = u32(f, 20 + jlen);
  EXPECT_EQ(f.substr(24 + jlen, 4), std::string("BIN\0", 4));
  EXPECT_EQ(28 + jlen + blen, f.size());
  EXPECT_EQ(g["buffers"][0]["byteLength"], blen);
  check_content(g, f.substr(28 + jlen), a);
  fs::remove(path);
}

TEST(Gltf, TextInlinesTheBufferAsBase64) {
  const std::string path = test::scratch_path("gltf", "animation.gltf").string();
  const auto a = sample();
  io::write_gltf(path, a);
  const auto g = nlohmann::json::parse(slurp(path));
  const std::string uri = g["buffers"][0]["uri"];
  const std::string head = "data:application/octet-stream;base64,";
  ASSERT_EQ(uri.substr(0, head.size()), head);
  // Decoded here, independently of the writer.
  std::string bin;
  unsigned acc = 0;
  int bits = 0;
  for (char c : uri.substr(head.size())) {
    if (c == '=') break;
    const char* table = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    acc = (acc << 6) | static_cast<unsigned>(std::strchr(table, c) - table);
    if ((bits += 6) >= 8) {
      bits -= 8;
      bin.push_back(static_cast<char>((acc >> bits) & 0xFF));
    }
  }
  EXPECT_EQ(bin.size(), g["buffers"][0]["byteLength"].get<std::size_t>());
  check_content(g, bin, a);
  fs::remove(path);
}

TEST(Gltf, RefusalsWriteNothing) {
  auto refused = [&](const std::string& name, const io::GltfAnimation& a) {
    const std::string path = test::scratch_path("gltf", name).string();
    fs::remove(path);
    EXPECT_TRUE(test::throws_error([&] { io::write_gltf(path, a); }, Errc::invalid_input, {name}))
        << name;
    EXPECT_FALSE(fs::exists(path));
  };
  refused("qmotion_gltf_test.fbx", sample());
  auto a = sample();
  a.times[1] = 0;
  refused("qmotion_gltf_test_times.glb", a);
  a = sample();
  a.rotations.pop_back();
  refused("qmotion_gltf_test_count.glb", a);
  a = sample();
  a.triangles[0][0] = 9;
  refused("qmotion_gltf_test_index.glb", a);
}

}  // namespace
}  // namespace qmotion
