// Simulated users: sketches made from known branch axes (3D polylines, e.g. a generated tree's
// skeleton). sketchFromPolylines is a careful user drawing on screen with a little hand jitter;
// pointNodesFromPolylines is the ideal user who places 3D nodes with exact branch tangents.
// Both serve the demo and the evaluation (a best case to compare automatic sketches against).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "treesketch/geom/camera.h"
#include "treesketch/sketch/sketch.h"

namespace treesketch::sketch {

/// One branch axis, world frame, ordered from the branch's base to its tip.
struct BranchPolyline {
  std::vector<geom::Vec3> points;
  /// Index of the parent branch in the list; -1 for the trunk (exactly one branch has -1).
  int parent = -1;
  /// Index of the parent's polyline vertex where this branch starts (ignored for the trunk).
  std::size_t parentVertex = 0;
};

struct PolylineSketchOptions {
  /// Distance between consecutive nodes along a branch, world units. When <= 0, nodeCount is
  /// used instead.
  double nodeSpacing = 0.0;
  /// Approximate total number of nodes: the spacing becomes (total polyline length) / nodeCount.
  int nodeCount = 20;
  /// Standard deviation of the Gaussian hand jitter added to each screen position, pixels
  /// (screen sketches only). 0 = exact projections.
  double pixelNoise = 0.0;
  /// Seed of the jitter (a fixed seed gives the same sketch).
  std::uint64_t seed = 1;
  /// Sampling sizes of every node (use defaultSamplingFor(cloud bounds) for a real cloud).
  SamplingParams params;
  /// The world's up axis (Sketch::up).
  geom::UpAxis up = geom::UpAxis::Y;
};

/// A screen sketch under `camera` following the branches. Each branch of length L gets
/// n = max(1, round(L / spacing)) nodes at the midpoints of n equal arc-length pieces
/// ((k + 0.5) L / n); the trunk also gets the root at its base (arc length 0). Nodes of a branch
/// form a chain; a branch's first node is a child of the node of its parent branch nearest (3D)
/// to the branch's start vertex (parent.points[parentVertex]). Screen position = projection of
/// the resampled point + N(0, pixelNoise²) per axis. Branches of zero length are skipped, with
/// their sub-branches attached to the nearest node of the closest ancestor that has nodes.
/// Throws OptionsError for: no branches, not exactly one trunk, a parent index out of range or a
/// cycle of parents, parentVertex out of range, an empty/NaN polyline, a trunk of zero length,
/// a point behind the camera, a degenerate camera, non-positive spacing and count, bad params.
Sketch sketchFromPolylines(const std::vector<BranchPolyline>& branches, const geom::Camera& camera,
                           const PolylineSketchOptions& options);

/// The same resampling and hierarchy, as point nodes: point = the resampled point (no noise),
/// normal = the unit polyline tangent there (direction of the segment holding the point; the
/// mean of the two segments at an interior vertex). No camera. Same errors (camera aside).
Sketch pointNodesFromPolylines(const std::vector<BranchPolyline>& branches, const PolylineSketchOptions& options);

}  // namespace treesketch::sketch
