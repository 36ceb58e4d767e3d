// Ray casting against triangle meshes with Embree: the nearest hit of a ray, one at a time
// (thread-safe) or for a batch of rays in parallel. Used by the virtual LIDAR scanner (scan/).
//
// Precision: Embree works in single precision. RayScene therefore stores the meshes translated so
// that their common bounding-box centre is at the origin, converts each ray into that frame, and
// converts the hit back. The hit point is then recomputed in double precision as
// origin + t * dir, with t taken from the ray's intersection with the hit triangle's plane
// (kept in double precision). Real-world coordinates (UTM eastings ~ 5e5 m) thus keep their
// precision; what float still limits is *which* triangle is reported for a ray that grazes an
// edge or a silhouette within ~1e-7 x (scene size + ray length) of it.
#pragma once

#include <cstdint>
#include <limits>
#include <memory>
#include <vector>

#include "treesketch/geom/tri_mesh.h"
#include "treesketch/geom/types.h"
#include "treesketch/util/progress.h"

namespace treesketch::accel {

/// Embree's BVH build quality (RTC_BUILD_QUALITY_*): higher builds slower and traces faster;
/// bench/bench_scan.cpp measures both (bench/README.md, "Scanner").
enum class BuildQuality { Low, Medium, High };

struct RaySceneOptions {
  /// BVH quality (Embree RTC_BUILD_QUALITY_*). Medium, as measured by bench_scan on a 171k-
  /// triangle tree (bench/README.md, "Scanner"): High took 5x longer to build (263 vs 49 ms)
  /// and traced the scanner's rays no faster.
  BuildQuality quality = BuildQuality::Medium;
};

/// One ray in world coordinates. `dir` need not be unit length; t is measured in units of |dir|.
struct Ray {
  geom::Vec3 origin = geom::Vec3::Zero();
  geom::Vec3 dir = geom::Vec3::UnitX();
  double tnear = 0.0;
  double tfar = std::numeric_limits<double>::infinity();
};

/// The nearest intersection of a ray with the scene.
struct RayHit {
  double t = 0.0;                         ///< ray parameter: point = origin + t * dir
  geom::Vec3 point = geom::Vec3::Zero();  ///< world coordinates, double precision
  std::int32_t meshIndex = -1;            ///< index of the input mesh hit; -1 = miss
  std::uint32_t primId = 0;               ///< triangle index within that mesh
  bool hit() const { return meshIndex >= 0; }
};

/// A committed Embree scene over one or more triangle meshes. Immutable after construction;
/// all queries are const and thread-safe. Move-only (a moved-from scene must not be queried).
class RayScene {
 public:
  /// Builds the BVH over `meshes` (the scene keeps what it needs: float vertices in Embree and
  /// each triangle's plane in double; the caller may drop the meshes). Mesh i reports
  /// meshIndex i. Empty meshes are allowed (they are never hit); a scene of only empty
  /// meshes, or no meshes, misses every ray. Throws OptionsError when a mesh is inconsistent
  /// (index out of range) or has a non-finite vertex; throws std::runtime_error with Embree's
  /// message if Embree fails (e.g. out of memory).
  explicit RayScene(const std::vector<geom::TriMesh>& meshes, const RaySceneOptions& options = {});
  /// Convenience: a scene of one mesh (meshIndex 0).
  explicit RayScene(const geom::TriMesh& mesh, const RaySceneOptions& options = {});
  ~RayScene();
  RayScene(RayScene&&) noexcept;
  RayScene& operator=(RayScene&&) noexcept;
  RayScene(const RayScene&) = delete;
  RayScene& operator=(const RayScene&) = delete;

  /// Nearest hit of the ray origin + t * dir with t in [tnear, tfar] (world coordinates, t in
  /// units of |dir|). Returns a RayHit with meshIndex -1 on a miss, or when dir is zero or
  /// any input is not finite (tfar may be +infinity). Thread-safe.
  RayHit intersect(const geom::Vec3& origin, const geom::Vec3& dir, double tnear = 0.0,
                   double tfar = std::numeric_limits<double>::infinity()) const;
  RayHit intersect(const Ray& ray) const { return intersect(ray.origin, ray.dir, ray.tnear, ray.tfar); }

  /// Casts all `rays` in parallel (TBB, Embree rtcIntersect1 per ray: the fast path for
  /// incoherent rays) and returns one RayHit per ray, in ray order (misses have meshIndex -1).
  /// `progress` (may be empty) is called from worker threads with (rays done, rays total).
  std::vector<RayHit> intersectAll(const std::vector<Ray>& rays, const ProgressFn& progress = {}) const;

  /// Number of input meshes (including empty ones).
  std::size_t meshCount() const;
  /// Total number of triangles over all meshes.
  std::size_t triangleCount() const;
  /// Bounding box of the vertices of the meshes that have triangles (world coordinates); empty
  /// when no mesh has any.
  const geom::BBox& bounds() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace treesketch::accel
