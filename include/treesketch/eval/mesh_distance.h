// The evaluation's one-direction surface distance: a thin layer over compare/ that fixes the
// sampling the evaluation uses (MeshLab's vertex + edge + face sampling, seeded) and handles an
// empty reconstruction (no samples: every statistic is NaN).
#pragma once

#include <cstdint>

#include "treesketch/geom/tri_mesh.h"

namespace treesketch::eval {

struct DistanceOptions {
  /// Samples on the sampled mesh; 0 = as many as it has vertices (MeshLab's default), then at
  /// least minSamples.
  std::uint64_t samples = 0;
  std::uint64_t minSamples = 20000;
  std::uint64_t seed = 1;
};

struct DirectionStats {
  std::size_t samples = 0;
  double max = 0, mean = 0, rms = 0;  ///< scene units; NaN when either mesh is empty
};

/// Samples `from` and measures each sample's distance to the surface `to` (no maximum distance:
/// every sample counts, so a reconstruction cannot hide a missing branch behind the cut-off).
DirectionStats oneWayDistance(const geom::TriMesh& from, const geom::TriMesh& to, const DistanceOptions& options);

}  // namespace treesketch::eval
