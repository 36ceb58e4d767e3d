// Features from shortest paths over the core points' neighbour graph (see features.h): every core
// point's shortest path to the base of the tree, with hops weighted by their squared length so
// that paths keep to continuous surfaces, and how many points' paths pass through it. Paths from
// the whole crown funnel through the wood and end in the leaves, so the count separates a twig
// from the leaves around it where the local shape cannot (the passage count of arbor and of the
// graph-based separations, e.g. Wang 2020, "LeWoS", and Tian 2022, "GBS").
#pragma once

#include <vector>

#include "treesketch/classify/features.h"

namespace treesketch::classify::detail {

/// Names of the graph features, in order.
std::vector<std::string> graphFeatureNames();

/// Fills the graph features of every core of `t` (its neighbours, heights and core sizes must be
/// set) into columns `column` onwards. `baseFraction`: seeds are the cores this fraction of the
/// height above the lowest one. Cores the paths do not reach get a passage of 0 and a path length
/// of -1.
void graphFeatures(const std::vector<geom::Vec3>& cores, double baseFraction, int column, FeatureTable& t);

}  // namespace treesketch::classify::detail
