#include "treesketch/eval/mesh_distance.h"

#include <algorithm>
#include <cmath>

#include "treesketch/compare/hausdorff.h"

namespace treesketch::eval {

DirectionStats oneWayDistance(const geom::TriMesh& from, const geom::TriMesh& to, const DistanceOptions& options) {
  DirectionStats s;
  if (from.empty() || to.empty()) {
    s.max = s.mean = s.rms = std::nan("");
    return s;
  }
  compare::CompareOptions co;
  std::uint64_t n = options.samples > 0 ? options.samples : from.vertices.size();
  co.sampling.count = std::max(n, options.minSamples);
  co.sampling.seed = options.seed;
  compare::DistanceReport r = compare::compareMeshes(from, to, co);
  s.samples = r.samplesUsed;
  s.max = r.max;
  s.mean = r.mean;
  s.rms = r.rms;
  return s;
}

}  // namespace treesketch::eval
