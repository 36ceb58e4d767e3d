// Per-point geometric features for telling wood from leaves: the eigenvalues of the local
// covariance at several neighbourhood sizes (linearity, planarity, scattering, the verticality
// of the principal axis and of the normal), the neighbourhood's size against the cloud's own
// spacing (density), how far the neighbourhood's centroid sits off the point, the same over a
// coarse level (cubes of a fraction of the tree's height), how the surface normals turn over each
// neighbourhood (bark fans about one axis, leaves scatter), and the point's height above the base
// and distance from the base's vertical line as fractions of the height.
// Neighbourhoods are k nearest points, so every scale follows the cloud's local spacing; features
// are ratios, so they do not depend on the cloud's unit.
// Method: the multi-scale covariance features of Weinmann et al. (2015, "Semantic point cloud
// interpretation based on optimal neighborhoods"), as wood/leaf studies use them.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "treesketch/geom/point_cloud.h"
#include "treesketch/geom/types.h"

namespace treesketch::classify {

struct FeatureOptions {
  /// Neighbourhood sizes, points, increasing. 8 sees a leaf's surface or a twig's few points, 32
  /// a branch's length beyond its width (a flat leaf and a thin branch both look planar or linear
  /// at one scale only). The largest also bounds the one k-nearest query per point.
  std::vector<int> scales = {8, 16, 32};
  /// Neighbours kept per core point for the graph step (classify/wood_graph.h), the nearest first.
  int graphNeighbours = 10;
  /// Core points: the cloud is cut into cubes of this many spacings and the centroid of each
  /// cube's points stands for them (features, classifier and graph run on the cores; every point
  /// takes its core's answer). 2 spacings: about a quarter of a scan's points, which is what keeps
  /// a million points within seconds, and finer than a twig's width at the scans' spacings
  /// (docs/classify.md). 0: every point is a core.
  double coreSpacings = 2.0;
  /// The spacing the features work at is the cloud's measured spacing, but never finer than this
  /// fraction of the tree's height (0.15 %: 7 mm on a 4.6 m tree; cores then at least 0.3 % of the
  /// height). A scan denser than a terrestrial one, such as the thesis's sphere pattern whose rays
  /// all cross near the crown's centre (spacing 0.03-0.09 % of the height there), adds no shape the
  /// features can use, and at its own spacing the largest fine scale (32 cores) covers a 2 cm patch
  /// of a thick limb, as flat as a leaf: such scans lost 60-80 % of their wood (docs/classify.md).
  /// At this floor the 32 nearest cores span a limb's curvature. 0: the measured spacing alone.
  double minSpacingHeightFraction = 0.0015;
  /// The coarse level: the same features over cubes of `coarseHeightFraction` of the tree's
  /// height, at these neighbourhood sizes (in cubes). On a dense scan the fine scales see only a
  /// patch of a thick stem, as flat as a leaf; at 1 % of the height (5 cm on a 5 m tree) a stem is
  /// a smooth cylinder and a cluster of leaves a scattered cloud. Empty: no coarse level.
  std::vector<int> coarseScales = {8, 24};
  double coarseHeightFraction = 0.01;
  /// Shortest-path features over the core points' neighbour graph from the base (the points whose
  /// paths pass through a point, the path's length and detour; src/classify/graph_features.h).
  bool graphFeatures = true;
  /// How the surface normals turn over each neighbourhood (at every scale after the first, fine and
  /// coarse; the normals are those of the first scale): a leaf is flat and small, so its normals
  /// agree over its own patch and scatter in every direction over a cluster of leaves; bark curves
  /// about one axis, so over a patch of a limb its normals fan out in one plane and never along the
  /// limb, however flat the limb looks to the point covariance at that scale.
  bool normalFeatures = true;
  /// The point's height above the base and distance from the base's vertical line, as fractions
  /// of the height: a prior on where wood is (the stem low and central) that the generator's trees
  /// teach and a bare crown or a conifer's needles contradict.
  bool positionFeatures = true;
};

/// Features of every core point, row-major: core i's features are values[i * count .. i * count +
/// count - 1], in the order of `names`.
struct FeatureTable {
  std::vector<std::string> names;
  int count = 0;
  std::vector<float> values;
  /// The spacing the features work at (cloud units): the cloud's measured spacing, raised to the
  /// floor of FeatureOptions::minSpacingHeightFraction. Cores are cubes of coreSpacings of it, the
  /// density features and the graph step's edges are measured in it.
  double spacing = 0;
  /// The cloud's measured spacing: the median distance from a point to its nearest neighbour.
  double measuredSpacing = 0;
  /// The core of every point of the cloud, and the number of cloud points each core stands for.
  std::vector<std::uint32_t> coreOf;
  std::vector<std::uint32_t> coreSize;
  /// Each core's `graphNeighbours` nearest cores (itself excluded; fewer in a tiny cloud: padded
  /// with its own index), row-major, and their distances.
  int neighbourCount = 0;
  std::vector<std::uint32_t> neighbours;
  std::vector<float> neighbourDistances;
  /// Height of every core above the cloud's lowest point along `up` (cloud units), and the range.
  std::vector<float> heights;
  double treeHeight = 0;

  std::size_t points() const { return count == 0 ? 0 : values.size() / static_cast<std::size_t>(count); }
  const float* row(std::size_t i) const { return values.data() + i * static_cast<std::size_t>(count); }
};

/// The feature names for `options` (the order of FeatureTable::values).
std::vector<std::string> featureNames(const FeatureOptions& options);

/// Computes the features of the core points of `cloud` (TBB parallel; deterministic). `up` is
/// the cloud's up axis (io/up_axis.h's rule). Throws OptionsError for scales that are not
/// increasing and >= 3, and DegenerateInputError for a cloud with fewer cores than the largest
/// scale + 1.
FeatureTable computeFeatures(const geom::PointCloud& cloud, geom::UpAxis up, const FeatureOptions& options = {});

}  // namespace treesketch::classify
