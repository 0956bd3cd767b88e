// Disjoint sets over the indices 0..n-1, with path halving. unite() keeps the
// smaller root, so the root of a set is its smallest member and results do
// not depend on the order of the unions.
#pragma once

#include <algorithm>
#include <cstdint>
#include <numeric>
#include <vector>

namespace xroute {

class UnionFind {
 public:
  UnionFind() = default;
  explicit UnionFind(size_t n) { reset(n); }

  // n singleton sets, dropping any earlier unions.
  void reset(size_t n) {
    parent_.resize(n);
    std::iota(parent_.begin(), parent_.end(), 0);
  }
  size_t size() const { return parent_.size(); }

  int32_t find(int32_t x) {
    while (parent_[x] != x) x = parent_[x] = parent_[parent_[x]];
    return x;
  }
  // Merges the sets of a and b; the smaller root survives.
  void unite(int32_t a, int32_t b) {
    a = find(a), b = find(b);
    if (a != b) parent_[std::max(a, b)] = std::min(a, b);
  }
  // Merges the sets of a and b under b's root (the caller picks the survivor).
  void attach(int32_t a, int32_t b) { parent_[find(a)] = find(b); }

 private:
  std::vector<int32_t> parent_;  // index of the parent element; a root is its own parent
};

}  // namespace xroute
