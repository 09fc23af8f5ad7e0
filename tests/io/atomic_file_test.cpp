// tests/io/atomic_file_test.cpp mirrors io/atomic_file.hpp
#include <filesystem>
#include <fstream>
#include <functional>
#include <qmotion/io/atomic_file.hpp>
#include <qmotion/io/json_number.hpp>

#include "io_test_util.hpp"

namespace qmotion::test {
namespace {
namespace fs = std::filesystem;

TEST(AtomicFile, WritesCompleteFileAndNoTemporary) {
  const auto d = fresh_dir("atomic", "ok");
  io::write_file_atomic((d / "a.json").string(), "{\"x\": 1}");
  EXPECT_EQ(io::read_text_file((d / "a.json").string()), "{\"x\": 1}");
  EXPECT_EQ(std::distance(fs::directory_iterator(d), fs::directory_iterator()), 1);
}

TEST(AtomicFile, UncommittedOutputLeavesNothing) {
  const auto d = fresh_dir("atomic", "abort");
  {
    io::AtomicOutput out((d / "b.step").string());
    std::ofstream(out.temp_path()) << "partial";
    // no commit: as when a writer throws halfway
  }
  EXPECT_TRUE(fs::is_empty(d));
}

TEST(AtomicFile, AWriterInPiecesAppearsWholeOnCommitAndNotBefore) {
  const auto d = fresh_dir("atomic", "pieces");
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
  const auto d = fresh_dir("atomic", "dir");
  EXPECT_TRUE(throws_error([&] { io::write_file_atomic(d.string(), "x"); }, Errc::invalid_input,
                           {"directory"}));
}

/// The message of the Errc::invalid_input that f throws ("" when it throws none).
std::string refusal(const std::function<void()>& f) {
  try {
    f();
  } catch (const Error& e) {
    if (e.code() == Errc::invalid_input) return e.what();
  }
  return "";
}

// Every file qmotion writes, qmotion reads back (docs/geometry.md, "Limits"): at the limit a
// written file is read back whole; one byte over, the writer refuses with the reader's message
// and leaves nothing, in each of the three ways qmotion writes.
TEST(AtomicFile, WritingRefusesWhatReadingRefusesWithTheSameMessage) {
  const auto d = fresh_dir("atomic", "limit");
  const std::uintmax_t limit = 1000;
  const auto path = (d / "out.json").string();
  const std::string at_limit(limit, 'x');
  io::write_file_atomic(path, at_limit, limit);
  EXPECT_EQ(io::read_text_file(path, limit), at_limit);
  {
    io::AtomicWriter w(path, limit);
    for (std::size_t i = 0; i < limit / 100; ++i) w.append(std::string(100, 'y'));
    w.commit();
  }
  EXPECT_EQ(io::read_text_file(path, limit), std::string(limit, 'y'));

  // The reader's refusal of a file one byte over.
  std::ofstream(path, std::ios::binary) << at_limit << 'z';
  const std::string read_msg = refusal([&] { io::read_text_file(path, limit); });
  ASSERT_NE(read_msg, "");
  EXPECT_NE(read_msg.find(path), std::string::npos) << read_msg;
  fs::remove(path);

  EXPECT_EQ(refusal([&] { io::write_file_atomic(path, at_limit + "z", limit); }), read_msg);
  EXPECT_TRUE(fs::is_empty(d));
  EXPECT_EQ(refusal([&] {
              io::AtomicWriter w(path, limit);
              w.append(at_limit);
              w.append("z");
              w.commit();
            }),
            read_msg);
  EXPECT_TRUE(fs::is_empty(d));
  EXPECT_EQ(refusal([&] {  // as OpenCASCADE's STEP and IGES writers write: a temporary file
              io::AtomicOutput out(path, limit);
              std::ofstream(out.temp_path(), std::ios::binary) << at_limit << 'z';
              out.commit();
            }),
            read_msg);
  EXPECT_TRUE(fs::is_empty(d));
}

// The defaults agree: the real limit, on a sparse file one byte over it.
TEST(AtomicFile, TheDefaultLimitIsOneForReadingAndWriting) {
  const auto d = fresh_dir("atomic", "default_limit");
  const auto path = (d / "big.step").string();
  std::ofstream(path, std::ios::binary).put('x');
  fs::resize_file(path, io::kMaxFileBytes + 1);
  const std::string read_msg = refusal([&] { io::read_text_file(path); });
  ASSERT_NE(read_msg, "");
  fs::remove(path);
  EXPECT_EQ(refusal([&] {
              io::AtomicOutput out(path);
              std::ofstream(out.temp_path(), std::ios::binary).put('x');
              fs::resize_file(out.temp_path(), io::kMaxFileBytes + 1);
              out.commit();
            }),
            read_msg);
  EXPECT_TRUE(fs::is_empty(d));
}

}  // namespace
}  // namespace qmotion::test
