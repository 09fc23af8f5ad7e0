// tests/io/atomic_file_test.cpp mirrors io/atomic_file.hpp
#include <filesystem>
#include <fstream>
#include <qmotion/io/atomic_file.hpp>
#include <qmotion/io/json_number.hpp>

#include "io_test_util.hpp"

namespace qmotion::test {
namespace {
namespace fs = std::filesystem;

fs::path scratch(const std::string& name) {
  const fs::path d = fs::temp_directory_path() / ("qmotion_atomic_" + name);
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

TEST(AtomicFile, WritesCompleteFileAndNoTemporary) {
  const auto d = scratch("ok");
  io::write_file_atomic((d / "a.json").string(), "{\"x\": 1}");
  EXPECT_EQ(io::read_text_file((d / "a.json").string()), "{\"x\": 1}");
  EXPECT_EQ(std::distance(fs::directory_iterator(d), fs::directory_iterator()), 1);
}

TEST(AtomicFile, UncommittedOutputLeavesNothing) {
  const auto d = scratch("abort");
  {
    io::AtomicOutput out((d / "b.step").string());
    std::ofstream(out.temp_path()) << "partial";
    // no commit: as when a writer throws halfway
  }
  EXPECT_TRUE(fs::is_empty(d));
}

TEST(AtomicFile, AWriterInPiecesAppearsWholeOnCommitAndNotBefore) {
  const auto d = scratch("pieces");
  const auto path = (d / "c.json").string();
  {
    io::AtomicWriter w(path);
    w.append("{\"x\": ");
    w.append(std::string(100000, '1'));
    EXPECT_FALSE(fs::exists(path));
    w.append("}");
    w.commit();
  }
  EXPECT_EQ(io::read_text_file(path), "{\"x\": " + std::string(100000, '1') + "}");
  EXPECT_EQ(std::distance(fs::directory_iterator(d), fs::directory_iterator()), 1);
  {
    io::AtomicWriter w((d / "d.json").string());
    w.append("partial");  // no commit: as when a writer throws halfway
  }
  EXPECT_FALSE(fs::exists(d / "d.json"));
  EXPECT_EQ(std::distance(fs::directory_iterator(d), fs::directory_iterator()), 1);
  EXPECT_TRUE(throws_error([] { io::AtomicWriter w("/nonexistent-dir/out.json"); },
                           Errc::invalid_input, {"/nonexistent-dir/out.json", "cannot create"}));
}

TEST(AtomicFile, UnwritableFolderIsBadInputNamingThePath) {
  EXPECT_TRUE(throws_error([] { io::write_file_atomic("/nonexistent-dir/out.json", "x"); },
                           Errc::invalid_input, {"/nonexistent-dir/out.json"}));
  const auto d = scratch("dir");
  EXPECT_TRUE(throws_error([&] { io::write_file_atomic(d.string(), "x"); }, Errc::invalid_input,
                           {"directory"}));
}

}  // namespace
}  // namespace qmotion::test
