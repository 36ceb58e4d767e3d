// Sampling a triangle mesh's surface as Metro (Cignoni, Rocchini & Scopigno 1998) and MeshLab's
// Hausdorff-distance filter do (thesis §2.5, §4.5): its vertices, points evenly spaced along its
// edges, and area-weighted random points on its faces. Seeded and deterministic.
#pragma once

#include <cstdint>
#include <vector>

#include "treesketch/geom/point_cloud.h"
#include "treesketch/geom/tri_mesh.h"

namespace treesketch::compare {

enum class SampleKind : std::uint8_t { Vertex, Edge, Face };
const char* toString(SampleKind kind);

/// How many samples of each kind. As in MeshLab's filter, the count is not split between the
/// kinds: every enabled kind gets `count` samples (so all three kinds give up to 3 × count), except
/// that vertex sampling never gives more samples than there are vertices.
struct SamplingOptions {
  /// Vertex samples: every vertex used by a triangle when count >= their number, else a seeded
  /// random subset of `count` of them (MeshLab: "VertexUniform").
  bool vertices = true;
  /// Edge samples: `count` points evenly spaced (step = total length of the unique edges / count,
  /// the first half a step in) along the unique edges, so none falls on a vertex (MeshLab:
  /// "EdgeUniform").
  bool edges = true;
  /// Face samples: `count` points, each on a triangle chosen with probability proportional to its
  /// area and uniform on it (MeshLab: "Montecarlo").
  bool faces = true;
  /// Samples per enabled kind; 0 = as many as the mesh has vertices (MeshLab's default,
  /// "SampleNum" = vertex count of the sampled mesh; thesis §4.5).
  std::uint64_t count = 0;
  /// Seed of the vertex subset and the face samples (each kind draws from its own stream, so
  /// switching one kind off does not change the others).
  std::uint64_t seed = 1;
};

/// Samples in the order vertex, edge, face samples.
struct SurfaceSamples {
  std::vector<geom::Vec3> points;  ///< world, metres
  std::vector<SampleKind> kinds;   ///< one per point
  /// One per point: the mesh vertex a vertex sample is, -1 for edge and face samples.
  std::vector<std::int64_t> vertex;
  std::size_t vertexSamples = 0, edgeSamples = 0, faceSamples = 0;

  std::size_t size() const { return points.size(); }
};

/// Samples `mesh` as the options say. A mesh without triangles gives no samples (vertices not
/// used by any triangle are never sampled); zero-length edges and zero-area faces are never
/// chosen, so a fully degenerate mesh gives only vertex samples. Throws OptionsError when a
/// triangle references a missing vertex.
SurfaceSamples sampleSurface(const geom::TriMesh& mesh, const SamplingOptions& options);

/// Samples a point cloud: its points (all when count is 0 or >= its size, else a seeded random
/// subset), as vertex samples (`vertex` = point index). Edges and faces do not apply.
SurfaceSamples sampleCloud(const geom::PointCloud& cloud, const SamplingOptions& options);

}  // namespace treesketch::compare
