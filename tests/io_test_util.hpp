// tests/io_test_util.hpp: test data folder and error-message checks for io tests.
#pragma once
#include <gtest/gtest.h>

#include <functional>
#include <qmotion/kernel/error.hpp>
#include <string>
#include <vector>

namespace qmotion::test {

/// A file of the repository's test data (tests/data), whose path the build defines.
inline std::string test_data(const std::string& rel) {
  return std::string(QMOTION_TEST_DATA) + "/" + rel;
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

}  // namespace qmotion::test
