// Whether a cloud's size and coordinates make sense for one tree in metres: a cloud in millimetres
// read as metres is a 3,700 m "tree" of millions of cubic metres, and a cloud far from its origin
// (1e15, where doubles step by 0.125) has lost its point spacing before any algorithm runs. Both
// are said, with the fix, instead of giving silent figures.
#pragma once

#include <string>
#include <vector>

#include "treesketch/cloud/stray_points.h"
#include "treesketch/geom/point_cloud.h"

namespace treesketch::cloud {

struct ScaleCheckOptions {
  /// The largest extent of one tree, metres: the tallest trees are about 115 m, the widest crowns
  /// about 60 m; 200 leaves room for a small plot and none for a cloud in centimetres or millimetres.
  double maxTreeMetres = 200.0;
  /// The point spacing must be at least this many steps of a double at the cloud's coordinates:
  /// at fewer, neighbouring points merge or snap to a grid coarser than a tenth of their spacing.
  double minSpacingSteps = 10.0;
  /// The farthest from its origin (cloud units) the automatic model was measured to be the model
  /// of the same cloud at the origin: a real scan moved by 1e6 and 1e9 (tests/cli/
  /// far_coordinates_test.cpp) and 1e10 gave the same volume. Farther it drifts before the
  /// spacing check above fires: 1.6 % at 1e11, 16 % at 1e12 (where doubles step by 0.12 mm).
  /// Projected coordinates (UTM, national grids, geocentric) stay below 1e7.
  double maxTestedOffset = 1e10;
};

struct ScaleCheck {
  double extentMetres = 0;  ///< the largest extent of the points kept (strays aside), metres
  double offset = 0;        ///< the largest absolute coordinate of the points kept, cloud units
  double doubleStep = 0;    ///< the spacing of doubles at `offset`, cloud units
  double floatStep = 0;     ///< the spacing of floats there (what a float PLY or a float export keeps)
  double spacing = 0;       ///< the measured point spacing, cloud units (0: not measured)
  bool implausibleSize = false;
  bool precisionLost = false;
  bool beyondTestedOffset = false;  ///< farther than maxTestedOffset, spacing still kept
  std::vector<std::string> warnings;  ///< each names the figure and the fix
};

/// Checks `cloud` without the points `strays` sets aside (from findStrayPoints on the same cloud);
/// `unitMetres` = metres per cloud unit (as --units-metres gives it). An empty cloud gives no
/// warning.
ScaleCheck checkScale(const geom::PointCloud& cloud, const StrayPoints& strays, double unitMetres = 1.0,
                      const ScaleCheckOptions& options = {});

}  // namespace treesketch::cloud
