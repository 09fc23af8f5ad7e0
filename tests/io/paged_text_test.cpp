// tests/io/paged_text_test.cpp: PagedText, a file's text whose pages go back as it is read
// (io/paged_text.hpp), and the motion reader that gives them back.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <fstream>
#include <qmotion/io/json_number.hpp>
#include <qmotion/io/motion_json.hpp>
#include <qmotion/io/paged_text.hpp>
#include <string>
#include <thread>

#include "io_test_util.hpp"

namespace qmotion {
namespace {
using test::scratch_path;
using test::throws_error;

/// This process's resident memory in bytes, as the kernel counts it (/proc/self/statm).
std::size_t resident_bytes() {
  std::ifstream in("/proc/self/statm");
  std::size_t pages = 0, resident = 0;
  in >> pages >> resident;
  return resident * static_cast<std::size_t>(sysconf(_SC_PAGESIZE));
}

std::string write_file(const std::string& name, const std::string& text) {
  const std::string path = scratch_path("paged", name).string();
  std::ofstream(path, std::ios::binary) << text;
  return path;
}

/// Characters that are not zero anywhere: a given-back page reads as zeros.
std::string pattern(std::size_t n) {
  std::string s(n, ' ');
  for (std::size_t i = 0; i < n; ++i) s[i] = static_cast<char>('a' + i % 26);
  return s;
}

TEST(PagedText, HoldsTheFileAndGivesItsPagesBack) {
  const std::size_t n = std::size_t(6) << 20;
  const std::string text = pattern(n);
  const std::string path = write_file("big.txt", text);
  io::PagedText t = io::PagedText::read(path);
  ASSERT_EQ(t.view(), text);
  // The padding a JSON reader reads past the end is there to read.
  for (std::size_t i = 0; i < io::kReadPadding; ++i) (void)*(t.view().data() + n + i);
  EXPECT_FALSE(t.released());
  const std::size_t before = resident_bytes();
  t.release_before(n - 4096);
  const std::size_t after = resident_bytes();
  EXPECT_TRUE(t.released());
  // The pages are gone from this process (not merely freed into a heap): 4 MB at least of
  // the 6 MB held, whatever the page size and the huge pages.
  EXPECT_GE(before, after + (std::size_t(4) << 20)) << before << " -> " << after;
  EXPECT_EQ(t.view()[0], '\0');             // a page given back reads as zeros
  EXPECT_EQ(t.view().back(), text.back());  // the last page is kept
  EXPECT_EQ(t.whole(path), text);           // read again from the file
  // Moved, the text goes with it.
  io::PagedText moved = std::move(t);
  EXPECT_EQ(moved.view().back(), text.back());
  EXPECT_TRUE(moved.released());
}

TEST(PagedText, ReadsAPipeIntoAStringAndRefusesWhatReadingRefuses) {
  const std::string fifo = scratch_path("paged", "fifo").string();
  ::unlink(fifo.c_str());
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  const std::string text = pattern(100000);
  std::thread writer([&] { std::ofstream(fifo, std::ios::binary) << text; });
  io::PagedText t = io::PagedText::read(fifo);
  writer.join();
  EXPECT_EQ(t.view(), text);
  t.release_before(text.size());  // held in a string: nothing is given back
  EXPECT_FALSE(t.released());
  EXPECT_EQ(t.view(), text);
  EXPECT_EQ(t.whole(fifo), text);  // the copy, not a second read of the spent pipe

  // The limit and the messages are read_text_file's.
  const std::string path = write_file("limit.txt", pattern(5000));
  std::string expected;
  try {
    (void)io::read_text_file(path, 4096);
  } catch (const Error& e) {
    expected = e.what();
  }
  ASSERT_FALSE(expected.empty());
  EXPECT_TRUE(throws_error([&] { (void)io::PagedText::read(path, 4096); }, Errc::invalid_input,
                           {expected}));
  EXPECT_EQ(io::PagedText::read(path, 5000).view().size(), 5000u);
  EXPECT_TRUE(throws_error([&] { (void)io::PagedText::read(path + ".missing"); },
                           Errc::invalid_input, {path + ".missing"}));
}

TEST(PagedText, TheMotionReaderGivesTheTextBackAsItReadsAndFallsBackWhole) {
  // A motion of 3 x 10^4 control points (about 4 MB of text) read from its file: the same
  // motion as from the string, and the text's pages given back by the time it is read.
  const std::size_t n = 30000;
  std::string t = R"({"type": "q-motion", "basis": "bspline", "degree": 3, "param_range": [0, )" +
                  std::to_string(n - 3) + "],\n\"control_points\": [";
  for (std::size_t i = 0; i < n; ++i)
    t += std::string(i ? ",\n" : "") + "[1, 0.25, 0, 0, 0, " + std::to_string(i) +
         ".125, -3.0625, 0.001]";
  t += "],\n\"knots\": [0, 0, 0";
  for (std::size_t i = 0; i <= n - 3; ++i) t += ", " + std::to_string(i);
  t += ", " + std::to_string(n - 3) + ", " + std::to_string(n - 3) + ", " + std::to_string(n - 3) +
       "]}";
  const std::string path = write_file("motion.json", t);
  const io::MotionFile from_string = io::parse_motion_text(t, "m");
  io::PagedText paged = io::PagedText::read(path);
  const auto fast = io::parse_motion_fast(paged, path);
  ASSERT_TRUE(fast.has_value());
  EXPECT_TRUE(paged.released());
  EXPECT_EQ(paged.view()[0], '\0');
  ASSERT_EQ(fast->ctrl.size(), n);
  for (std::size_t i = 0; i < n; i += 997)
    for (std::size_t k = 0; k < 8; ++k)
      EXPECT_EQ(fast->ctrl[i][k].value, from_string.ctrl[i][k].value) << i << " " << k;
  EXPECT_EQ(fast->knots.size(), from_string.knots.size());

  // Declined past the control points (an exact "p/q" knot, the last field): their pages are
  // gone, so the whole text comes back from the file, and the full reader reads it.
  std::string exact = t;
  const std::string last = std::to_string(n - 3);
  exact.replace(exact.rfind(last), last.size(), "\"" + last + "/1\"");
  const std::string exact_path = write_file("exact.json", exact);
  auto read = io::read_motion_or_text(exact_path);
  ASSERT_TRUE(std::holds_alternative<std::string>(read));
  EXPECT_EQ(std::get<std::string>(read), exact);
  const io::MotionFile whole = io::read_motion(exact_path);
  EXPECT_EQ(whole.ctrl.size(), n);
  EXPECT_EQ(whole.knots.back().source(), last + "/1");
}

}  // namespace
}  // namespace qmotion
