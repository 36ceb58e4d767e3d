// Metro/MeshLab-style Hausdorff comparison of two surfaces (thesis §2.5, §3.6, §4.5): sample one
// surface (vertices, edges, faces), find each sample's closest point on the other, and report
// min / max / mean / RMS. Forward = the original sampled against the reconstruction, backward =
// the reconstruction sampled against the original; the symmetric Hausdorff distance is the larger
// maximum. The target may be a triangle mesh or a point cloud.
//
// Known limits (as Metro's): the maximum is a lower bound of the true one-sided Hausdorff
// distance (only samples are measured; more samples tighten it), and with a search distance
// the farthest samples are dropped, not counted in the statistics (their number is reported).
#pragma once

#include <limits>
#include <nlohmann/json.hpp>
#include <vector>

#include "treesketch/accel/closest_point.h"
#include "treesketch/compare/distance_report.h"
#include "treesketch/compare/surface_sampling.h"
#include "treesketch/geom/point_cloud.h"
#include "treesketch/geom/tri_mesh.h"
#include "treesketch/util/progress.h"

namespace treesketch::compare {

struct CompareOptions {
  SamplingOptions sampling;
  /// Search distance (metres): samples with no target point within it are dropped and counted.
  /// Default: none. (MeshLab's filter defaults to 5 % of the sampled mesh's bounding-box diagonal,
  /// thesis §4.5; see maxDistanceFraction.)
  double maxDistance = std::numeric_limits<double>::infinity();
  /// When > 0, the search distance is this fraction of the sampled surface's bounding-box
  /// diagonal (MeshLab's default is 0.05), or maxDistance if smaller. 0 = unused.
  double maxDistanceFraction = 0;
  /// Histogram bins (>= 1).
  int histogramBins = 10;
  /// Keep the per-sample distances, kinds and vertex indices in the report (for error meshes and
  /// plots). Costs 17 bytes a sample.
  bool keepSamples = false;
  /// Closest-point index options (the answers do not depend on them, only the speed).
  accel::ClosestPointOptions accel;
  /// Called from worker threads with (queries done, total); may be empty.
  ProgressFn progress;
};

/// One direction: `sampled` sampled as options.sampling says, each sample's distance to the
/// closest point of `target` (metres, exact point-triangle distance). The report's percentages
/// are relative to `sampled`'s bounding-box diagonal. Deterministic for a given seed (bit-identical
/// across runs and thread counts). Throws OptionsError when either mesh has no triangles, a
/// triangle references a missing vertex, a vertex is NaN/Inf, or an option is out of range.
DistanceReport compareMeshes(const geom::TriMesh& sampled, const geom::TriMesh& target, const CompareOptions& options);
/// As compareMeshes, against the nearest point of a point cloud (throws OptionsError when the
/// cloud is empty or has NaN/Inf points).
DistanceReport compareMeshToCloud(const geom::TriMesh& sampled, const geom::PointCloud& target,
                                  const CompareOptions& options);
/// A point cloud's points (all, or a seeded subset of options.sampling.count) against a mesh: the
/// backward direction when the reconstruction's target is only known as a cloud. Only vertex
/// sampling applies; percentages are relative to the cloud's bounding-box diagonal.
DistanceReport compareCloudToMesh(const geom::PointCloud& sampled, const geom::TriMesh& target,
                                  const CompareOptions& options);

/// Both directions and the symmetric Hausdorff distance.
struct BothReport {
  DistanceReport forward;   ///< original sampled against the reconstruction
  DistanceReport backward;  ///< reconstruction sampled against the original
  /// max(forward.max, backward.max), metres; NaN when a direction used no sample.
  double hausdorff = std::numeric_limits<double>::quiet_NaN();
  /// hausdorff as a percentage of the original's bounding-box diagonal (forward.diagonal).
  double hausdorffPercent = std::numeric_limits<double>::quiet_NaN();
};

/// Forward and backward comparison of two meshes with the same options (the sample count 0 means
/// each sampled mesh's own vertex count). Throws as compareMeshes.
BothReport compareBoth(const geom::TriMesh& original, const geom::TriMesh& reconstruction,
                       const CompareOptions& options);
/// Fills hausdorff and hausdorffPercent of a BothReport from its two directions.
void finishBoth(BothReport& report);

/// {"forward": ..., "backward": ..., "hausdorff": ..., "hausdorffPercent": ...}.
nlohmann::json toJson(const BothReport& report);

/// Distance (metres) of each vertex of `mesh` to `target`; +inf for vertices with no target point
/// within `maxDistance`. Only the entries of `distances` that are NaN are computed (so a report's
/// vertex samples can be reused); `distances` is resized to the vertex count (new entries NaN)
/// first. Throws as compareMeshes.
void fillVertexDistances(const geom::TriMesh& mesh, const geom::TriMesh& target, double maxDistance,
                         std::vector<double>& distances);
void fillVertexDistances(const geom::TriMesh& mesh, const geom::PointCloud& target, double maxDistance,
                         std::vector<double>& distances);

/// Per-vertex distances recorded in a report kept with keepSamples (vertex samples only); NaN for
/// vertices that were not sampled. `vertexCount` is the sampled mesh's vertex count.
std::vector<double> vertexDistancesFromReport(const DistanceReport& report, std::size_t vertexCount);

}  // namespace treesketch::compare
