// tests/io/refusal_expect.hpp: the robot-program tests' check that a call is refused as bad
// input (exit 2) with a message holding the given words.
#pragma once
#include <gtest/gtest.h>

#include <functional>
#include <qmotion/kernel/error.hpp>
#include <string>

namespace qmotion::test {

inline void expect_refused(const std::function<void()>& f, const std::string& words) {
  try {
    f();
    FAIL() << "accepted; expected a refusal naming " << words;
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), Errc::invalid_input) << e.what();
    EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
  }
}

}  // namespace qmotion::test
