// tests/io_test_util.hpp: test data folder, scratch files, error-message checks and mesh
// volumes for the tests of io and of what reads files.
#pragma once
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <functional>
#include <qmotion/kernel/error.hpp>
#include <string>
#include <vector>

namespace qmotion::test {

/// A file of the repository's test data (tests/data), whose path the build defines.
inline std::string test_data(const std::string& rel) {
  return std::string(QMOTION_TEST_DATA) + "/" + rel;
}

/// `name` in this test process's scratch folder, <tmp>/qmotion_<tag>_<pid> (made when
/// missing; a process's files never meet another's).
inline std::filesystem::path scratch_path(const std::string& tag, const std::string& name) {
  const auto d = std::filesystem::temp_directory_path() /
                 ("qmotion_" + tag + "_" + std::to_string(::getpid()));
  std::filesystem::create_directories(d);
  return d / name;
}

/// An empty folder `name` in the scratch folder of `tag` (emptied when it exists).
inline std::filesystem::path fresh_dir(const std::string& tag, const std::string& name) {
  const auto d = scratch_path(tag, name);
  std::filesystem::remove_all(d);
  std::filesystem::create_directories(d);
  return d;
}

/// Runs f, expecting a qmotion::Error with `code` whose message contains every needle.
inline ::testing::AssertionResult throws_error(const std::function<void()>& f, Errc code,
                                               const std::vector<std::string>& needles) {
  try {
    f();
  } catch (const Error& e) {
    if (e.code() != code) return ::testing::AssertionFailure() << "wrong error kind: " << e.what();
    const std::string msg = e.what();
    for (const auto& n : needles)
      if (msg.find(n) == std::string::npos)
        return ::testing::AssertionFailure() << "message '" << msg << "' lacks '" << n << "'";
    return ::testing::AssertionSuccess();
  }
  return ::testing::AssertionFailure() << "no qmotion::Error thrown";
}

/// The volume a closed, outward-oriented triangle mesh encloses (divergence theorem); any
/// mesh with `vertices` (Eigen 3-vectors) and `triangles` (three indices each).
template <typename Mesh>
double enclosed_volume(const Mesh& m) {
  double v = 0;
  for (const auto& t : m.triangles)
    v += m.vertices[static_cast<std::size_t>(t[0])].dot(
        m.vertices[static_cast<std::size_t>(t[1])].cross(
            m.vertices[static_cast<std::size_t>(t[2])]));
  return v / 6;
}

}  // namespace qmotion::test
