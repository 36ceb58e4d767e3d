// Options shared by the point-cloud readers (PLY, XYZ/TXT/CSV, LAS, OBJ-as-cloud) and the
// minimum-size check every reader applies before returning a cloud.
#pragma once

#include <cstddef>
#include <string>

#include "treesketch/geom/point_cloud.h"

namespace treesketch::io {

/// Fewest points a usable tree cloud may have. A circle through 3 points always exists, so a
/// RANSAC circle fit (thesis section 4.3) needs at least one more point to test a candidate
/// against; anything smaller is rejected at load time instead of failing later.
inline constexpr std::size_t kMinCloudPoints = 4;

struct CloudReadOptions {
  /// Readers throw InputError when the file holds fewer points than this (default
  /// kMinCloudPoints). Set to 1 to accept any non-empty cloud; 0 also accepts an empty one.
  std::size_t minPoints = kMinCloudPoints;
  /// XYZ/TXT/CSV only: how many lines at the top of the file may be skipped as a header (lines
  /// whose first three fields are not numbers, e.g. "X,Y,Z" or a point count). Past this,
  /// a non-numeric line is an error. Unit: lines. Chosen generously; real headers are 1–2 lines.
  std::size_t maxHeaderLines = 100;
};

/// Throws InputError "<source>: ... holds N points, at least M are needed" when `cloud` has
/// fewer than `minPoints` points. Does nothing otherwise.
void checkCloudSize(const geom::PointCloud& cloud, const std::string& source, std::size_t minPoints = kMinCloudPoints);

}  // namespace treesketch::io
