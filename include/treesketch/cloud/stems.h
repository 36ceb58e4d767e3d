// The stems a cloud holds at breast height, and a plot's points shared out among them.
//
// A cloud of one tree has one stem at 1.3 m above the terrain (a tree forked below breast height
// has two, as foresters count it); a plot, or a clip that caught a neighbour, has several, and a
// model of it as one tree joins the trees through the ground and the crowns. findStems finds the
// stems the way a forester's scan tools do: the points in a thin slice at breast height above the
// terrain, in groups of points linked within a few point spacings, a circle fitted to each group,
// kept when most of the points round it lie on it (bark, nothing inside), a slice half a metre
// below or above shows the same stem (a low limb crosses the slice sideways: it is not there half a
// metre away), and its points reach down to the ground (a limb hanging through breast height does
// not). Circles that overlap are one stem seen in arcs.
//
// Stems whose points join between stump height (0.3 m) and breast height are one tree (forked
// there). splitByTree shares out
// the points: every point goes to the tree whose stem is nearest along the cloud (shortest paths
// over a voxel graph of the points from each stem's breast-height voxels), so a crown that leans
// over a neighbour's stem still goes with its own; points in pieces no path reaches go to the tree
// of the nearest point a path reached.
#pragma once

#include <cstdint>
#include <vector>

#include "treesketch/geom/point_cloud.h"
#include "treesketch/geom/types.h"

namespace treesketch::cloud {

struct StemOptions {
  /// Metres per cloud unit (> 0): breast height and the diameters are in metres.
  double unitMetres = 1.0;
  /// Breast height above the terrain, metres.
  double breastHeight = 1.3;
  /// Half the thickness of each slice, metres: a few scan lines of a stem.
  double sliceHalfWidth = 0.05;
  /// The slices that confirm a stem lie this far below and above breast height, metres.
  double checkOffset = 0.5;
  /// Diameters counted as stems, metres: foresters' smallest callipered stem (5 cm) to a giant.
  double minDiameter = 0.05;
  double maxDiameter = 4.0;
  /// A group's points link within this many point spacings.
  double linkSpacings = 4.0;
  /// At least this share of a group's points lie on its circle.
  double minOnCircleShare = 0.5;
};

struct Stem {
  geom::Vec3 centre = geom::Vec3::Zero();  ///< the circle's centre at breast height (cloud units)
  double diameter = 0;                     ///< metres
  double rms = 0;                          ///< the circle's RMS residual, metres
  std::size_t points = 0;                  ///< on the circle
  double terrain = 0;                      ///< the terrain's height under it (cloud units, along up)
  /// The tree it belongs to (an index, 0 for the largest stem's): stems whose points join below
  /// breast height are one tree, forked below it.
  std::int32_t tree = 0;
};

struct Stems {
  std::vector<Stem> stems;  ///< by diameter, largest first
  std::size_t trees = 0;    ///< trees the stems belong to (Stem::tree)
  /// True when the terrain came from ground points; otherwise from the lowest points round each.
  bool terrainFromGround = false;
  double spacing = 0;  ///< the point spacing used (cloud units)
};

/// The stems of `cloud` at breast height. `ground`: indices (increasing) of the points that are
/// ground (cloud/ground.h), left out of the slices and used for the terrain's height; empty: the
/// terrain under a point is the lowest point within a metre or two (a stem's foot). `spacing`: the cloud's point spacing (not positive: measured).
/// Throws OptionsError for bad options.
Stems findStems(const geom::PointCloud& cloud, geom::UpAxis up, const std::vector<std::uint32_t>& ground,
                double spacing, const StemOptions& options = {});

/// For each point of `cloud`, its tree (Stem::tree, below `stems.trees`), or -1 for the points in
/// `ground` (and every point when there is no stem).
std::vector<std::int32_t> splitByTree(const geom::PointCloud& cloud, geom::UpAxis up, const Stems& stems,
                                      const std::vector<std::uint32_t>& ground, const StemOptions& options = {});

}  // namespace treesketch::cloud
