// Per-point geometric features for telling wood from leaves: the eigenvalues of the local
// covariance at several neighbourhood sizes (linearity, planarity, scattering, the verticality
// of the principal axis and of the normal), the neighbourhood's size against the cloud's own
// spacing (density), how far the neighbourhood's centroid sits off the point, and the point's
// height above the base and distance from the base's vertical line as fractions of the height.
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
  /// Neighbours kept per point for the graph step (classify/wood_graph.h), the nearest first.
  int graphNeighbours = 10;
};

/// Features of every point, row-major: point i's features are values[i * count .. i * count +
/// count - 1], in the order of `names`.
struct FeatureTable {
  std::vector<std::string> names;
  int count = 0;
  std::vector<float> values;
  /// The cloud's spacing: the median distance from a point to its nearest neighbour (cloud units).
  double spacing = 0;
  /// Each point's `graphNeighbours` nearest neighbours (itself excluded; fewer in a tiny cloud:
  /// padded with the point's own index), row-major, and their distances.
  int neighbourCount = 0;
  std::vector<std::uint32_t> neighbours;
  std::vector<float> neighbourDistances;
  /// Height of every point above the cloud's lowest point along `up` (cloud units), and the range.
  std::vector<float> heights;
  double treeHeight = 0;

  std::size_t points() const { return count == 0 ? 0 : values.size() / static_cast<std::size_t>(count); }
  const float* row(std::size_t i) const { return values.data() + i * static_cast<std::size_t>(count); }
};

/// The feature names for `options` (the order of FeatureTable::values).
std::vector<std::string> featureNames(const FeatureOptions& options);

/// Computes the features of every point of `cloud` (TBB parallel; deterministic). `up` is the
/// cloud's up axis (io/up_axis.h's rule). Throws OptionsError for scales that are not increasing
/// and >= 3, or a cloud with fewer points than the largest scale + 1 (DegenerateInputError).
FeatureTable computeFeatures(const geom::PointCloud& cloud, geom::UpAxis up, const FeatureOptions& options = {});

}  // namespace treesketch::classify
