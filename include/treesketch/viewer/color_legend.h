// Which colourings a cloud offers and the legend of the current one: the viewer's height and
// distance colourings and the file's attributes (viewer/attribute_colors.h). Plain C++, no GL.
#pragma once

#include <vector>

#include "treesketch/geom/point_cloud.h"
#include "treesketch/viewer/attribute_colors.h"
#include "treesketch/viewer/viewer_state.h"

namespace treesketch::viewer {

/// True when `cloud` has what `mode` colours by (intensity, RGB, classification: the attribute,
/// one per point; the wood probability and class: `classified`, the viewer's own classification
/// is there); height, distance and plain are always available.
bool colorModeAvailable(ColorMode mode, const geom::PointCloud& cloud, bool classified = false);
/// The available modes in menu order (height, distance, plain, the file's attributes, then the
/// wood probability and class when `classified`).
std::vector<ColorMode> availableColorModes(const geom::PointCloud& cloud, bool classified = false);
/// The available mode after `mode` (wrapping), for the `C` key.
ColorMode nextColorMode(ColorMode mode, const geom::PointCloud& cloud, bool classified = false);
/// A readable name for menus ("distance to circles", "RGB (file)").
const char* colorModeLabel(ColorMode mode);

/// Point colours by one of the attribute modes (intensity over its 1–99 % range in grey, the file's
/// RGB, the ASPRS class colours); {} when the cloud lacks the attribute or for another mode.
std::vector<Rgb> attributeColors(const geom::PointCloud& cloud, ColorMode mode);

/// The legend of the state's current colouring: height along the view's up direction above the
/// lowest point;
/// distance to the nearest circle from 0 to the colouring's scale (ViewerOptions::
/// distanceColorScale of the diagonal); intensity over its 1–99 % range; classification as the
/// classes present with their ASPRS names and counts; none for plain and RGB (which say so in
/// `note`). O(points) for intensity and classification: cache it per cloudVersion() and mode.
Legend colorLegend(const ViewerState& state);

}  // namespace treesketch::viewer
