// The peers of `qmotion verify` (tests/bench/verify_peers.cpp): each table's function prints
// a Markdown table and returns how many times qmotion's certified answer was wrong (0).
#pragma once
#include <chrono>
#include <cstdio>

namespace qmotion::peers {

inline double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

/// The holder's first contact against FCL's continuous collision detection, over n moves.
int fcl_holder_table(int n, std::FILE* out);

}  // namespace qmotion::peers
