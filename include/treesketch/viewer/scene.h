// What the desktop window draws of a ViewerState, computed on demand from it: point colours (kept
// until the colouring, the cloud or the lassos change), node markers and picking them, the 3D lines
// (circles, the selected node's sampling region), the highlighted points, the tube mesh and the
// model it measures against. It reads the state and never edits it. Plain C++, no GL.
#pragma once

#include <cstdint>
#include <vector>

#include "treesketch/geom/tri_mesh.h"
#include "treesketch/model/tree_model.h"
#include "treesketch/sketch/sketch.h"
#include "treesketch/viewer/point_colors.h"
#include "treesketch/viewer/scene_items.h"
#include "treesketch/viewer/view_settings.h"

namespace treesketch::viewer {

class ViewerState;

class Scene {
 public:
  explicit Scene(const ViewerState& state) : s_(state) {}
  Scene(const Scene&) = delete;
  Scene& operator=(const Scene&) = delete;

  /// Per-point colours for the current colour mode (recomputed only when stale).
  const std::vector<Rgb>& pointColors();
  /// Increases whenever pointColors() would change.
  std::uint64_t colorsVersion() const { return colorsVersion_; }
  /// The model the fitted sketch makes (model::fromReconstruction): what the exports write and
  /// the distance colouring measures against. Empty with no cloud or no two linked fitted nodes.
  model::TreeModel treeModel() const;
  /// The distance colouring's grid (its last call's counts; for tests and benchmarks).
  const DistanceColorGrid& distanceColorGrid() const { return distanceGrid_; }
  /// Markers of all nodes under the current camera.
  std::vector<NodeMarker> nodeMarkers() const;
  /// The node a click at `screen` picks: of the markers within the pick radius, the nearest to
  /// the eye (NodeMarker::depth), then the nearest on screen (kNoNode if none).
  sketch::NodeId nodeAt(const geom::Vec2& screen) const;
  /// How many visible markers lie within the pick radius of `screen` (a pick among several says
  /// which it took).
  std::size_t markersAt(const geom::Vec2& screen) const;
  /// 3D lines: fitted circles (selected one highlighted) and the selected node's sampling region.
  std::vector<Line3> sceneLines() const;
  SamplingRegion samplingRegion() const;
  /// Cloud indices of the selected node's slice points and circle inliers (empty when none).
  std::vector<std::uint32_t> highlightedSlicePoints() const;
  std::vector<std::uint32_t> highlightedInliers() const;
  NodeFitView nodeFit(sketch::NodeId id) const;
  const geom::TriMesh& mesh() const;
  /// Node numbers are drawn (display().labels and the node count).
  bool labelsShown() const;
  /// Counts of fitted and skipped nodes.
  std::size_t fittedCount() const;
  std::size_t skippedCount() const;

 private:
  friend class ViewerState;
  /// The visible node whose marker is nearest to `screen`, at any distance (kNoNode if none).
  sketch::NodeId nearestMarker(const geom::Vec2& screen) const;

  const ViewerState& s_;
  std::vector<Rgb> colors_;
  DistanceColorGrid distanceGrid_;  ///< binned once per cloud for the distance colouring
  std::uint64_t distanceGridVersion_ = 0;
  ColorMode colorsMode_ = ColorMode::Height;
  bool colorsStale_ = true;
  std::uint64_t colorsVersion_ = 1;
  std::vector<sketch::NotWoodLasso> colorsNotWood_;  ///< the lassos pointColors() last drew
  std::uint64_t colorsClasses_ = 0;                  ///< the classification pointColors() last drew
  geom::TriMesh emptyMesh_;
};

}  // namespace treesketch::viewer
