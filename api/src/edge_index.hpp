// api/src/edge_index.hpp: a hash map from 64-bit keys to ints with open addressing, for the
// lattice route's surface vertices by lattice edge (volume_lattice.cpp).
#pragma once
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

namespace qmotion::detail {

/// Open addressing with linear probing (the standard map's nodes cost more than the search
/// here).
class EdgeIndex {
 public:
  /// The value of key, or nullptr when it is absent.
  const int* find(std::uint64_t key) const {
    if (keys_.empty()) return nullptr;
    for (std::size_t i = slot(key); keys_[i] != kEmpty; i = (i + 1) & (keys_.size() - 1))
      if (keys_[i] == key) return &values_[i];
    return nullptr;
  }

  /// The slot of key: {index, true} when it was absent (its value is then to be set).
  std::pair<int*, bool> try_emplace(std::uint64_t key) {
    if (2 * (used_ + 1) > keys_.size()) grow();
    std::size_t i = slot(key);
    while (keys_[i] != kEmpty) {
      if (keys_[i] == key) return {&values_[i], false};
      i = (i + 1) & (keys_.size() - 1);
    }
    keys_[i] = key;
    ++used_;
    return {&values_[i], true};
  }

 private:
  static constexpr std::uint64_t kEmpty = ~std::uint64_t(0);
  std::size_t slot(std::uint64_t key) const {
    return static_cast<std::size_t>((key * 0x9E3779B97F4A7C15ull) >> shift_);
  }
  void grow() {
    std::vector<std::uint64_t> keys = std::move(keys_);
    std::vector<int> values = std::move(values_);
    const std::size_t n = keys.empty() ? std::size_t(1) << 16 : 2 * keys.size();
    keys_.assign(n, kEmpty);
    values_.assign(n, 0);
    shift_ = 64;
    for (std::size_t m = n; m > 1; m >>= 1) --shift_;
    for (std::size_t i = 0; i < keys.size(); ++i)
      if (keys[i] != kEmpty) {
        std::size_t j = slot(keys[i]);
        while (keys_[j] != kEmpty) j = (j + 1) & (n - 1);
        keys_[j] = keys[i];
        values_[j] = values[i];
      }
  }
  std::vector<std::uint64_t> keys_;
  std::vector<int> values_;
  std::size_t used_ = 0;
  int shift_ = 64;
};

}  // namespace qmotion::detail
