// tests/fuzz/fuzz_util.hpp: what a fuzz target accepts. A reader may succeed or refuse
// (qmotion::Error with invalid_input or numerical_failure: exit 2 or 3); any other
// exception is what the CLI reports as an internal error (exit 1) and is a finding.
#pragma once
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <qmotion/kernel/error.hpp>
#include <string>

namespace qmotion::fuzz {

/// Runs f; returns normally on success or on a refusal, aborts (a libFuzzer finding) on
/// any other exception, printing it.
template <typename F>
void accept_refusals(F&& f) {
  try {
    f();
  } catch (const Error& e) {
    if (e.code() == Errc::invalid_input || e.code() == Errc::numerical_failure) return;
    std::fprintf(stderr, "fuzz: qmotion::Error with exit status 1: %s\n", e.what());
    std::abort();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "fuzz: internal error (exit 1): %s\n", e.what());
    std::abort();
  }
}

/// The input as text.
inline std::string text(const std::uint8_t* data, std::size_t size) {
  return std::string(reinterpret_cast<const char*>(data), size);
}

}  // namespace qmotion::fuzz
