// Radius prior from the tree's own shape: the pipe model's allometry. A branch's cross-section
// carries the wood above it (Shinozaki et al. 1964), so a node's radius grows with the length of
// the sub-tree it carries, r ≈ a · L^b (b = 0.5 for area-preserving pipes). a and b are fitted to
// the tree's own trusted circle fits by a robust regression in log–log space, so the prior follows
// the species and the scan; a fit far from it took in noise, a neighbour or a one-sided arc.
#pragma once

#include <cstdint>
#include <vector>

#include "treesketch/skeleton/skeleton.h"

namespace treesketch::skeleton::detail {

struct Allometry {
  bool valid = false;  ///< false when too few trusted fits to fit it
  double logA = 0, b = 0.5;
  std::vector<double> carried;  ///< per node: length of the sub-tree it carries, world units

  /// Predicted radius of node i.
  double predict(std::size_t i) const;
};

/// Fits the allometry to the radii `r` of the nodes with `trusted[i]`; nodes are parent-first.
Allometry fitAllometry(const std::vector<SkeletonNode>& nodes, const std::vector<double>& r,
                       const std::vector<char>& trusted);

/// In place: the least-squares non-increasing sequence to `values` with `weights` > 0
/// (isotonic regression by pooling adjacent violators): a branch's taper.
void nonIncreasingFit(std::vector<double>& values, const std::vector<double>& weights);

}  // namespace treesketch::skeleton::detail
