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
#include "treesketch/util/non_increasing_fit.h"

namespace treesketch::skeleton::detail {

/// Fewer anchoring radii than this do not set the law's scale.
inline constexpr std::size_t kMinAllometryAnchors = 3;

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

/// Length carried by each node (parent-first): its own segment (from its parent) and every
/// segment above it, plus the median segment (a tip's wood goes on a little past its last node).
std::vector<double> carriedLengths(const std::vector<SkeletonNode>& nodes);

/// Nodes `from` on (parent-first; a grafted part's): each no thicker than its parent, and with no
/// more cross-section than the pipe model gives the length it carries, r ≤ r_parent · √(L / L_parent).
/// A part grafted beside a limb is fitted on a few points against the limb's side: its circles
/// can be as thick as the limb (knotted thick tubes in a real crown's picture).
void capByPipeModel(std::vector<SkeletonNode>& nodes, std::size_t from);

/// The pipe law through the root: r_i = rootRadius · (L_i / L_root)^0.5, where L is the length a
/// node carries (nodes parent-first; the first root is the root).
std::vector<double> pipeRadii(const std::vector<SkeletonNode>& nodes, double rootRadius);

/// A branch's taper (util/non_increasing_fit.h), shared with a fitted sketch's inferred radii.
using util::nonIncreasingFit;

}  // namespace treesketch::skeleton::detail
