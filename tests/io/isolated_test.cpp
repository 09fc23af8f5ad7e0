// tests/io/isolated_test.cpp mirrors io/isolated.hpp
#include "isolated.hpp"

#include <signal.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <qmotion/io/json_number.hpp>
#include <stdexcept>

#include "io_test_util.hpp"

namespace qmotion::test {
namespace {

int touched = 0;  // what the work changes: in the child's copy, never here

TEST(Isolated, TheWorkRunsInAnotherProcessAndItsBytesComeBackWhole) {
  const pid_t here = getpid();
  // More than a pipe holds (64 KiB), so that the parent must read while the child writes.
  const std::string answer = io::run_isolated("f.step", "STEP", [&](std::string& out) {
    ++touched;
    io::ByteWriter w(out);
    w.put(static_cast<int>(getpid() != here));
    std::vector<double> v(1 << 20);
    for (std::size_t i = 0; i < v.size(); ++i) v[i] = 0.1 * static_cast<double>(i);
    w.put_vector(v);
    w.put_string("end");
  });
  EXPECT_EQ(touched, 0);
  io::ByteReader r(answer);
  EXPECT_EQ(r.get<int>(), 1);
  const auto v = r.get_vector<double>();
  ASSERT_EQ(v.size(), std::size_t(1) << 20);
  for (std::size_t i = 0; i < v.size(); ++i) {
    ASSERT_EQ(v[i], 0.1 * static_cast<double>(i));
  }
  EXPECT_EQ(r.get_string(), "end");
  EXPECT_TRUE(r.done());
  EXPECT_TRUE(throws_error([&] { (void)r.get<int>(); }, Errc::internal, {"cut short"}));
}

TEST(Isolated, TheCallersStandardOutputIsWrittenOnceAndTheChildsNever) {
  // The caller's stdout goes to a file; it leaves text unwritten in its buffers when the
  // child starts, and the child flushes (as OpenCASCADE's readers do) and prints.
  const std::string file = ::testing::TempDir() + "qmotion_isolated_stdout.txt";
  std::fflush(stdout);
  std::cout.flush();
  const int saved = ::dup(STDOUT_FILENO);
  ASSERT_GE(saved, 0);
  FILE* f = std::fopen(file.c_str(), "w");
  ASSERT_NE(f, nullptr);
  ::dup2(::fileno(f), STDOUT_FILENO);
  std::fclose(f);
  std::printf("caller's text, ");  // no line end: unwritten, whatever the buffering
  std::cout << "caller's stream";
  io::run_isolated("x.step", "STEP", [](std::string&) {
    std::fflush(stdout);
    std::cout.flush();
    std::printf("child's line\n");
    std::cout << "child's stream" << std::endl;
    std::fflush(stdout);
  });
  std::fflush(stdout);
  std::cout.flush();
  ::dup2(saved, STDOUT_FILENO);
  ::close(saved);
  EXPECT_EQ(io::read_text_file(file), "caller's text, caller's stream");
}

TEST(Isolated, ACrashInTheChildIsARefusalNamingTheFileAndThisProcessGoesOn) {
  for (const int sig : {SIGSEGV, SIGBUS, SIGFPE, SIGABRT}) {
    SCOPED_TRACE(sig);
    EXPECT_TRUE(throws_error(
        [&] { io::run_isolated("part.igs", "IGES", [&](std::string&) { ::raise(sig); }); },
        Errc::invalid_input, {"part.igs", "a damaged IGES file", "crashed", "separate process"}));
  }
  // A null dereference the compiler cannot see through, as in a parser.
  EXPECT_TRUE(throws_error(
      [&] {
        io::run_isolated("part.step", "STEP", [&](std::string& out) {
          volatile int* volatile p = nullptr;
          out.push_back(static_cast<char>(*p));
        });
      },
      Errc::invalid_input, {"part.step", "a damaged STEP file", "crashed"}));
  // A child that ends before its answer is whole (an exit inside a library).
  EXPECT_TRUE(throws_error(
      [&] { io::run_isolated("part.step", "STEP", [&](std::string&) { ::_exit(0); }); },
      Errc::invalid_input, {"part.step", "without an answer"}));
  // And the next read works.
  const auto again = io::run_isolated("p.step", "STEP", [](std::string& out) { out = "ok"; });
  EXPECT_EQ(again, "ok");
}

TEST(Isolated, TheChildsErrorsComeBackWithTheirKindAndMessage) {
  EXPECT_TRUE(throws_error(
      [&] {
        io::run_isolated("a.step", "STEP", [](std::string&) {
          throw Error(Errc::numerical_failure, "a.step: a weight of zero");
        });
      },
      Errc::numerical_failure, {"a.step: a weight of zero"}));
  EXPECT_TRUE(throws_error(
      [&] {
        io::run_isolated("a.step", "STEP", [](std::string&) { throw Error(Errc::internal, ""); });
      },
      Errc::internal, {}));
  EXPECT_TRUE(throws_error(
      [&] {
        io::run_isolated("b.igs", "IGES",
                         [](std::string&) { throw std::out_of_range("index 7 of 3"); });
      },
      Errc::invalid_input, {"b.igs", "index 7 of 3"}));
}

}  // namespace
}  // namespace qmotion::test
