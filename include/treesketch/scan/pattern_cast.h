// The scanner's core: casts a pattern of rays (any function ray index -> ray) at a RayScene in
// parallel and turns the nearest hits into a point cloud, in ray order, misses dropped. The
// patterns themselves live in sphere_scan.h (thesis) and tls_scan.h (terrestrial stations).
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include "treesketch/accel/ray_scene.h"
#include "treesketch/geom/point_cloud.h"
#include "treesketch/scan/beam_footprint.h"
#include "treesketch/util/progress.h"

namespace treesketch::scan {

/// One ray of a pattern, with the station that fired it (-1 = none).
struct ScanRay {
  accel::Ray ray;
  std::int32_t station = -1;
};

/// Makes ray number `index` (0-based) of a pattern. Must be a pure function of the index: it is
/// called concurrently from several threads, in no particular order.
using RayGenerator = std::function<ScanRay(std::uint64_t index)>;
/// Makes rays first .. first+count-1 into out[0 .. count-1] (count <= kRayBatch): the same
/// contract as RayGenerator, for patterns that are cheaper to step from ray to ray than to
/// compute from scratch (the built-in patterns use it).
using RayBatchGenerator = std::function<void(std::uint64_t first, std::size_t count, ScanRay* out)>;
/// Rays per RayBatchGenerator call at most.
inline constexpr std::size_t kRayBatch = 256;

struct CastOptions {
  /// Size of one scene unit in metres (1 = the scene is in metres; 0.1 = decimetres, as the
  /// ez-tree test trees are taken to be). The instrument's figures below are in metres and are
  /// divided by it to act in the scene.
  double unitMetres = 1.0;
  /// Standard deviation of Gaussian range noise added along each ray, metres. 0 = exact hits
  /// (the thesis's scanner, §4.2).
  double rangeNoise = 0.0;
  /// The beam's width and mixed returns at edges (off: thin rays).
  BeamFootprint beam;
  /// Seed of the noise (each ray's noise is a function of (seed, ray index) only).
  std::uint64_t seed = 1;
  /// Fill PointCloud::meshId with the input mesh each point lies on.
  bool recordMesh = false;
  /// Fill PointCloud::station with ScanRay::station.
  bool recordStation = false;
  /// Fill PointCloud::scanner with each ray's origin.
  bool recordScanner = false;
};

/// What a scan did.
struct ScanStats {
  std::uint64_t raysCast = 0;
  std::uint64_t hits = 0;                  ///< points in the cloud
  std::vector<std::uint64_t> hitsPerMesh;  ///< one per input mesh of the scene
  /// With a beam footprint: points that blend two surfaces' ranges (edges), points from beams
  /// that only partly hit, and beams dropped as too weak (see beam_footprint.h). 0 without.
  std::uint64_t mixed = 0, partial = 0, weak = 0;
  double milliseconds = 0.0;  ///< wall time of the casting (not of building the scene)
  /// Fraction of hits on mesh `i` (0 when there are no hits).
  double fraction(std::size_t i) const {
    return hits == 0 || i >= hitsPerMesh.size() ? 0.0 : static_cast<double>(hitsPerMesh[i]) / hits;
  }
};

struct ScanResult {
  geom::PointCloud cloud;  ///< world coordinates
  ScanStats stats;
};

/// Casts rays 0 .. rayCount-1 from `generator` at `scene` (TBB parallel, deterministic: the
/// result does not depend on the thread count). Each hit becomes the point
/// hit + noise * unit(dir), noise ~ N(0, (rangeNoise / unitMetres)^2) drawn from (seed, ray
/// index); rays that miss (or whose direction is zero/non-finite) add nothing. With a beam
/// footprint, each ray is the centre of a beam (castBeam, the ring turned by an angle drawn from
/// (seed, ray index)) and "hit" is the beam's return. Points are in ray order.
/// `progress` (may be empty) is called from worker threads, possibly concurrently, with (rays
/// done, rayCount). rayCount 0 gives an empty cloud. Throws OptionsError for a negative or
/// non-finite rangeNoise, unitMetres not > 0 and finite, or an invalid footprint.
ScanResult castPattern(const accel::RayScene& scene, std::uint64_t rayCount, const RayGenerator& generator,
                       const CastOptions& options = {}, const ProgressFn& progress = {});
/// Same, with rays made in batches.
ScanResult castPattern(const accel::RayScene& scene, std::uint64_t rayCount, const RayBatchGenerator& generator,
                       const CastOptions& options = {}, const ProgressFn& progress = {});

}  // namespace treesketch::scan
