// io/src/gltf.cpp: glTF 2.0 writing (docs/formats.md, "glTF").
#include <algorithm>
#include <cstring>
#include <limits>
#include <qmotion/io/atomic_file.hpp>
#include <qmotion/io/gltf.hpp>
#include <qmotion/kernel/error.hpp>

namespace qmotion::io {
namespace {

constexpr int kFloat = 5126, kUint = 5125;
constexpr int kArrayBuffer = 34962, kElementArrayBuffer = 34963;

/// The binary buffer and the views and accessors into it.
struct Buffer {
  std::string bytes;
  nlohmann::json views = nlohmann::json::array(), accessors = nlohmann::json::array();

  /// Appends the values as one view (4-byte aligned) and one accessor; returns its index.
  template <typename T, std::size_t N>
  int add(const std::vector<std::array<T, N>>& v, int component, const char* type, int target,
          bool bounds) {
    while (bytes.size() % 4) bytes.push_back('\0');
    const std::size_t offset = bytes.size(), length = v.size() * sizeof(T) * N;
    bytes.resize(offset + length);
    if (length) std::memcpy(&bytes[offset], v.data(), length);
    nlohmann::json view = {{"buffer", 0}, {"byteOffset", offset}, {"byteLength", length}};
    if (target) view["target"] = target;
    views.push_back(view);
    nlohmann::json acc = {{"bufferView", views.size() - 1},
                          {"componentType", component},
                          {"count", v.size()},
                          {"type", type}};
    if (bounds) {
      std::array<T, N> lo, hi;
      lo.fill(std::numeric_limits<T>::max());
      hi.fill(std::numeric_limits<T>::lowest());
      for (const auto& x : v)
        for (std::size_t k = 0; k < N; ++k) {
          lo[k] = std::min(lo[k], x[k]);
          hi[k] = std::max(hi[k], x[k]);
        }
      acc["min"] = lo;
      acc["max"] = hi;
    }
    accessors.push_back(acc);
    return static_cast<int>(accessors.size()) - 1;
  }
};

std::string base64(const std::string& in) {
  static const char* t = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((in.size() + 2) / 3 * 4);
  std::size_t i = 0;
  for (; i + 2 < in.size(); i += 3) {
    const auto n = (std::uint32_t(std::uint8_t(in[i])) << 16) |
                   (std::uint32_t(std::uint8_t(in[i + 1])) << 8) | std::uint8_t(in[i + 2]);
    for (int s = 18; s >= 0; s -= 6) out.push_back(t[(n >> s) & 63]);
  }
  if (i < in.size()) {
    std::uint32_t n = std::uint32_t(std::uint8_t(in[i])) << 16;
    if (i + 1 < in.size()) n |= std::uint32_t(std::uint8_t(in[i + 1])) << 8;
    out.push_back(t[(n >> 18) & 63]);
    out.push_back(t[(n >> 12) & 63]);
    out.push_back(i + 1 < in.size() ? t[(n >> 6) & 63] : '=');
    out.push_back('=');
  }
  return out;
}

void put_u32(std::string& s, std::uint32_t v) {
  for (int k = 0; k < 4; ++k) s.push_back(static_cast<char>((v >> (8 * k)) & 0xFF));
}

void check(const std::string& path, const GltfAnimation& a) {
  auto refuse = [&](const std::string& why) {
    throw Error(Errc::invalid_input, path + ": cannot write glTF: " + why);
  };
  if (a.positions.empty() || a.triangles.empty()) refuse("the body's mesh is empty");
  if (a.times.empty()) refuse("no keyframes");
  if (a.translations.size() != a.times.size() || a.rotations.size() != a.times.size())
    refuse("the keyframes' times, translations and rotations differ in number");
  for (std::size_t i = 1; i < a.times.size(); ++i)
    if (!(a.times[i] > a.times[i - 1])) refuse("keyframe times do not increase strictly");
  for (const auto& t : a.triangles)
    for (auto v : t)
      if (v >= a.positions.size()) refuse("a triangle names a vertex the mesh does not have");
}

}  // namespace

bool is_gltf_path(const std::string& path) {
  const std::string e = lower_extension(path);
  return e == ".glb" || e == ".gltf";
}

void write_gltf(const std::string& path, const GltfAnimation& a) {
  if (!is_gltf_path(path))
    throw Error(Errc::invalid_input, path + ": unknown glTF extension (expected .glb or .gltf)");
  check(path, a);
  Buffer buf;
  const int pos = buf.add(a.positions, kFloat, "VEC3", kArrayBuffer, true);
  const int idx = buf.add(a.triangles, kUint, "SCALAR", kElementArrayBuffer, false);
  buf.accessors[static_cast<std::size_t>(idx)]["count"] = 3 * a.triangles.size();
  std::vector<std::array<float, 1>> times;
  for (float t : a.times) times.push_back({t});
  const int tin = buf.add(times, kFloat, "SCALAR", 0, true);
  const int tr = buf.add(a.translations, kFloat, "VEC3", 0, false);
  const int rot = buf.add(a.rotations, kFloat, "VEC4", 0, false);
  while (buf.bytes.size() % 4) buf.bytes.push_back('\0');

  nlohmann::json g;
  g["asset"] = {{"version", "2.0"}, {"generator", "qmotion animate"}, {"extras", a.extras}};
  g["scene"] = 0;
  g["scenes"] = nlohmann::json::array({{{"name", a.name}, {"nodes", {0}}}});
  // Root: qmotion's frame (z up) in glTF's (y up): (x, y, z) -> (x, z, -y), exact in floats
  // as a column-major matrix.
  g["nodes"] = {{{"name", "z-up"},
                 {"matrix", {1, 0, 0, 0, 0, 0, -1, 0, 0, 1, 0, 0, 0, 0, 0, 1}},
                 {"children", {1}}},
                {{"name", a.name},
                 {"mesh", 0},
                 {"translation", a.translations.front()},
                 {"rotation", a.rotations.front()}}};
  using J = nlohmann::json;
  J primitive = J::object();
  primitive["attributes"] = {{"POSITION", pos}};
  primitive["indices"] = idx;
  J mesh = J::object();
  mesh["name"] = a.name + " body";
  mesh["primitives"] = J::array({primitive});
  g["meshes"] = J::array({mesh});
  J samplers = J::array();
  J channels = J::array();
  const std::pair<int, const char*> outputs[] = {{tr, "translation"}, {rot, "rotation"}};
  for (const auto& [output, target] : outputs) {
    J sampler = J::object();
    sampler["input"] = tin;
    sampler["output"] = output;
    sampler["interpolation"] = "LINEAR";
    J channel = J::object();
    channel["sampler"] = samplers.size();
    channel["target"] = {{"node", 1}, {"path", target}};
    samplers.push_back(sampler);
    channels.push_back(channel);
  }
  J animation = J::object();
  animation["name"] = a.name + " motion";
  animation["samplers"] = samplers;
  animation["channels"] = channels;
  g["animations"] = J::array({animation});
  g["bufferViews"] = buf.views;
  g["accessors"] = buf.accessors;
  const bool binary = lower_extension(path) == ".glb";
  if (!binary) {
    g["buffers"] = {{{"byteLength", buf.bytes.size()},
                     {"uri", "data:application/octet-stream;base64," + base64(buf.bytes)}}};
    write_file_atomic(path, g.dump(1) + "\n");
    return;
  }
  g["buffers"] = {{{"byteLength", buf.bytes.size()}}};
  std::string json = g.dump();
  while (json.size() % 4) json.push_back(' ');
  std::string out = "glTF";
  put_u32(out, 2);
  put_u32(out, static_cast<std::uint32_t>(12 + 8 + json.size() + 8 + buf.bytes.size()));
  put_u32(out, static_cast<std::uint32_t>(json.size()));
  out += "JSON";
  out += json;
  put_u32(out, static_cast<std::uint32_t>(buf.bytes.size()));
  out += "BIN";
  out.push_back('\0');
  out += buf.bytes;
  write_file_atomic(path, out);
}

}  // namespace qmotion::io
