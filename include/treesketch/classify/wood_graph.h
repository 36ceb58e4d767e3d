// The graph step of the wood/leaf classification: a core's wood probability is averaged with its
// neighbours' (wood is continuous, one core's answer noisy), and wood must hang together with the
// stem. Wood
// grows from confident wood at the base of the tree along the neighbour graph, passing through
// points the classifier is unsure of (a twig's points behind a leaf), and takes every wood point
// it reaches; wood it does not reach stays wood only when it forms a piece large enough to stand
// on its own (a limb cut off by occlusion). Isolated "wood" in the crown — a leaf's edge seen
// edge-on, a cluster of stalks — is demoted to leaf.
// Method: after the graph-based separation of Tian et al. (2022, "Graph-based leaf-wood
// separation", GBS), which grows wood from the base along shortest paths.
#pragma once

#include <cstdint>
#include <vector>

#include "treesketch/classify/features.h"

namespace treesketch::classify {

struct WoodGraphOptions {
  /// Seeds: wood points within this fraction of the tree's height above its lowest point (5 %:
  /// the root collar and lower stem, which every scan of a standing tree sees).
  double baseFraction = 0.05;
  /// Growth passes through points whose wood probability is at least this (below the wood
  /// threshold: a twig half hidden by leaves scores 0.2-0.5), never through confident leaves.
  double bridgeProbability = 0.25;
  /// Graph edges longer than this many cloud spacings join nothing (a gap in the scan is not a
  /// connection).
  double maxEdgeSpacings = 6.0;
  /// A piece of wood not reached from the base stays wood when it has at least this many core
  /// points (a limb whose link to the stem is occluded), else it is demoted.
  int minPiecePoints = 30;
  /// Points below the wood threshold but at least this probable become wood where growth from the
  /// base reaches them (1: never).
  double promoteProbability = 1.0;
};

/// Counts are of core points (features.h).
struct WoodGraphResult {
  std::vector<std::uint8_t> wood;  ///< 1 = wood, one per core point
  std::size_t seeds = 0;           ///< wood points at the base growth started from
  std::size_t reached = 0;         ///< wood points reached from the base
  std::size_t kept = 0;            ///< wood points in large enough pieces not reached
  std::size_t demoted = 0;         ///< wood points demoted to leaf
  std::size_t promoted = 0;        ///< points below the threshold made wood (promoteProbability)
};

/// Each core's probability averaged with its graph neighbours' (the `neighbourCount` nearest
/// within `maxEdgeSpacings` spacings, the graph step's edges): p <- (1 - weight) p + weight *
/// mean(p of the neighbours), `passes` times (each pass reads the previous one's answers, so
/// two passes reach the neighbours' neighbours). Wood is continuous: a limb's cores agree with
/// the cores along it, and one core's answer, from a neighbourhood of a few dozen cores, is noisy
/// (a patch of bark as flat as a leaf, a leaf's edge seen edge-on); the neighbours' mean carries
/// what the limb around it says. A core with no neighbour within reach keeps its probability.
std::vector<float> smoothOverGraph(const FeatureTable& features, const std::vector<float>& probability, double weight,
                                   int passes, double maxEdgeSpacings = WoodGraphOptions{}.maxEdgeSpacings);

/// Applies the graph step to `probability` (one per core point of `features`, wood at >= `threshold`).
/// With no wood at the base (a cloud cut above the ground, a branch alone) every piece is judged
/// by its size alone.
WoodGraphResult connectWood(const FeatureTable& features, const std::vector<float>& probability, double threshold,
                            const WoodGraphOptions& options = {});

}  // namespace treesketch::classify
