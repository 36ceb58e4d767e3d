// Which axis is up when the user does not say: the rule every command that needs "up" follows.
//
// 1. An explicit --up always wins.
// 2. Else the file's own declaration (geom::PointCloud::up, set by the readers): LAS is Z-up by
//    its specification; a PLY says it in a `comment up_axis y|z` line (treesketch writes one for
//    every cloud that knows its up, such as its synthetic scans of Y-up trees).
// 3. Else Z: text clouds (.xyz .txt .csv .pts .asc), OBJ vertices and PLY files without the comment
//    follow the convention of field scans and forestry tools (TreeQSM, SimpleForest, rTwig,
//    AdTree), which is Z up.
#pragma once

#include <string>

#include "treesketch/geom/point_cloud.h"

namespace treesketch::io {

struct UpAxisChoice {
  geom::UpAxis up = geom::UpAxis::Z;
  /// Why, for the message the commands print: "--up y", "the file declares z", "z, the default
  /// for clouds that do not say (field convention)".
  std::string reason;
};

/// Applies the rule above. `option` is the --up value ("" when not given; "y"/"z", any case).
/// Throws OptionsError for another value.
UpAxisChoice chooseUpAxis(const std::string& option, const geom::PointCloud& cloud);

}  // namespace treesketch::io
