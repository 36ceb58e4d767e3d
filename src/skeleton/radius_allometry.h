// Radius prior from the tree's own shape: the pipe model. A branch's cross-section carries the
// wood above it (Shinozaki et al. 1964), so its area grows with the length of the sub-tree it
// carries: r = a · L^0.5. The scale a is taken where the scan measures a radius best, the stem
// (its slab circle fits, else the fits of the lower trunk), never from the crown's fits: on a
// noisy or sparse crown a circle fitted to a twig's shell of noise is several times the twig, and
// a law fitted to those fits (the exponent fitted too) inherited their inflation — 4–13× the
// volume of other tools' models on unseen scans, twigs nearly as thick as the stem.
#pragma once

#include <cstdint>
#include <vector>

#include "treesketch/skeleton/skeleton.h"

namespace treesketch::skeleton::detail {

struct Allometry {
  bool valid = false;  ///< false when too few trusted fits to fit it
  double logA = 0, b = 0.5;  ///< r = exp(logA) · L^b
  std::vector<double> carried;  ///< per node: length of the sub-tree it carries, world units

  /// Predicted radius of node i.
  double predict(std::size_t i) const;
};

/// The pipe law of `nodes` (parent-first): b = 0.5 and log a the median of log r − 0.5 log L over
/// the nodes with `stem[i]` (a measured stem radius), or, with fewer than three of those, over the
/// `trusted[i]` nodes that carry at least half the tree (the lower trunk), then over all `trusted`
/// nodes. Not valid with fewer than three such radii.
Allometry fitAllometry(const std::vector<SkeletonNode>& nodes, const std::vector<double>& r,
                       const std::vector<char>& trusted, const std::vector<char>& stem);

/// The pipe law through the root: r_i = rootRadius · (L_i / L_root)^0.5, where L is the length a
/// node carries (nodes parent-first; the first root is the root).
std::vector<double> pipeRadii(const std::vector<SkeletonNode>& nodes, double rootRadius);

/// In place: the least-absolute-deviations non-increasing sequence to `values` with `weights` > 0
/// (isotonic regression by pooling adjacent violators, each pool at its members' weighted
/// median): a branch's taper. The median, not the mean: a run of thick fits just below a fork
/// (a slice through the crotch holds both limbs) would raise the whole trunk below it by their
/// mean (adtree_tree1's stem at 1.3 m from 13 to 17.6 cm); its median moves only as far as the
/// majority of the fits.
void nonIncreasingFit(std::vector<double>& values, const std::vector<double>& weights);

}  // namespace treesketch::skeleton::detail
