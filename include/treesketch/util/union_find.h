// Disjoint sets over 0..n-1 (union-find with path halving) and the connected components of a
// graph in compressed rows. Each set's representative is its smallest element, so labels derived
// from representatives do not depend on the order the unions were made in.
#pragma once

#include <cstdint>
#include <numeric>
#include <vector>

namespace treesketch::util {

class UnionFind {
 public:
  explicit UnionFind(std::size_t n) : parent_(n) { std::iota(parent_.begin(), parent_.end(), std::uint32_t{0}); }

  std::size_t size() const { return parent_.size(); }

  /// The representative (smallest element) of `a`'s set.
  std::uint32_t find(std::uint32_t a) {
    while (parent_[a] != a) a = parent_[a] = parent_[parent_[a]];  // path halving
    return a;
  }

  /// Joins the sets of `a` and `b`; the smaller representative stays (e.g. piece 0 stays the main
  /// piece of a graph).
  void unite(std::uint32_t a, std::uint32_t b) {
    a = find(a);
    b = find(b);
    if (a < b)
      parent_[b] = a;
    else if (b < a)
      parent_[a] = b;
  }

 private:
  std::vector<std::uint32_t> parent_;
};

/// Connected components of an undirected graph over vertices 0..n-1 given in compressed rows
/// (`offsets`, size n + 1; the neighbours of v are targets[offsets[v] .. offsets[v+1])). Labels
/// are numbered from 0 in the order of each component's lowest vertex. `count` (optional)
/// receives the number of components.
std::vector<std::int32_t> labelComponents(const std::vector<std::uint32_t>& offsets,
                                          const std::vector<std::uint32_t>& targets, std::int32_t* count = nullptr);

}  // namespace treesketch::util
