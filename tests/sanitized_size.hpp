// tests/sanitized_size.hpp: the sizes a heavy test runs at in each tree (docs/testing.md,
// "The sanitized tree").
#pragma once
#include <initializer_list>
#include <vector>

namespace qmotion::test {

#ifdef QMOTION_TEST_SANITIZED
inline constexpr bool kSanitized = true;
#else
inline constexpr bool kSanitized = false;
#endif

/// The settings a test steps through, from cheap to costly (tolerances, deflections): all of
/// them in the Release tree, which holds every figure; under the sanitizers all but the
/// costliest, which runs the same code paths at a size where instrumented code takes minutes
/// (the finest of three tolerances was 80 % of such a test's time there).
template <typename T>
std::vector<T> steps(std::initializer_list<T> cheap_to_costly) {
  std::vector<T> v(cheap_to_costly);
  if (kSanitized && v.size() > 1) v.pop_back();
  return v;
}

/// A count of random cases: `full` in the Release tree, `sanitized` under the sanitizers.
template <typename T>
constexpr T sized(T full, T sanitized) {
  return kSanitized ? sanitized : full;
}

}  // namespace qmotion::test
