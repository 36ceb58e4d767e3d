// The ground under a tree: the points of the terrain a scan of a standing tree often holds (a
// terrestrial scan's clip keeps a disc of it around the stem; a plot keeps all of it), set aside
// before modelling as the field's tools classify it first (CloudCompare's CSF, 3DFin, TreeLS).
// Left in, the skeleton starts from the terrain and the model's volume grows by the ground's
// shell of tubes.
//
// The rule reads the ground's shape, at scales taken from the cloud's own point spacing (nothing
// assumes metres): on a grid of columns across the up axis, a column is ground when the lowest
// points of its sub-columns fill it and lie on one plane that is not steep, i.e. a continuous,
// nearly level surface under which the scanner saw nothing. A stem's foot is a ring of bark (its
// inside has no points), a limb is a curved strip, a crown's underside stands far above the cloud's
// lowest points: none of them is ground. Columns of ground joined side by side form the terrain;
// only terrain wide against the grid (a few dozen columns) and reaching the cloud's bottom is kept.
// A point is ground when it lies at most a few spacings (or three of the terrain's own roughness)
// above the plane of its column or, where its column is not terrain (sparse lines of points far
// from a scanner, the shadow under a stem's foot), of the nearest terrain columns round it. Points a LAS file classifies
// as ground (ASPRS class 2) are ground whatever their shape.
#pragma once

#include <cstdint>
#include <vector>

#include "treesketch/geom/point_cloud.h"
#include "treesketch/cloud/stray_points.h"
#include "treesketch/geom/types.h"

namespace treesketch::cloud {

struct GroundOptions {
  bool enabled = true;
  /// A column's side, in point spacings: wide enough to hold a patch of terrain with many points,
  /// narrow against a tree's crown.
  double columnSpacings = 8.0;
  /// Each column is cut into this many sub-columns per side; the terrain fills them.
  int subColumns = 4;
  /// The share of the sub-columns that must hold points for the column to be a filled surface.
  double minFilledShare = 0.75;
  /// The steepest terrain, degrees from level.
  double maxSlopeDeg = 40.0;
  /// The sub-columns' lowest points lie within this share of a column's side of their plane (RMS).
  double maxRoughnessColumns = 0.25;
  /// Terrain of fewer columns than this is not ground (a flat patch of bark or a thick limb).
  int minColumns = 24;
  /// A point at most this many spacings above its ground plane (or three roughnesses, whichever is
  /// more) is ground.
  double heightSpacings = 3.0;
};

struct Ground {
  /// Indices into the cloud, increasing.
  std::vector<std::uint32_t> points;
  std::size_t columns = 0;      ///< columns of terrain found
  double columnSize = 0;        ///< their side, in the cloud's units
  std::size_t classified = 0;   ///< of `points`, those the file classifies as ground
};

/// The ground points of `cloud` (see above). `spacing` is the cloud's point spacing (as
/// StrayPoints measures it; not positive: measured here). Nothing is ground with the rule off, in a
/// cloud of fewer than 64 points, or when the terrain would leave fewer than 64 (then the cloud is a
/// surface, not a tree on the ground).
Ground findGround(const geom::PointCloud& cloud, geom::UpAxis up, double spacing, const GroundOptions& options = {});

/// The points to set aside before modelling: those the file marks as noise (findMarkedNoise: a
/// low point under the terrain would otherwise be the cloud's bottom) and those repeating an
/// earlier point (findRepeatedPoints), then the ground of the rest (findGround), then the stray
/// points of what is left (findStrayPoints: with the terrain gone, what is left of it far from the
/// tree is far from the tree), as one StrayPoints (indices into `cloud`, each reason counted apart).
/// A cloud with no point marked as noise and none repeated gives what the rules give on it alone.
StrayPoints findStrayAndGroundPoints(const geom::PointCloud& cloud, geom::UpAxis up,
                                     const StrayPointOptions& strays = {}, const GroundOptions& ground = {},
                                     const MarkedNoiseOptions& noise = {});

}  // namespace treesketch::cloud
