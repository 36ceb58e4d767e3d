// The 3D view's aids, in plain C++ (no GL): the scale bar (a round length in metres that adapts to
// the zoom, as in CloudCompare and map tools) and the axis gizmo (the world X/Y/Z axes as seen by
// the camera, drawn as a small triad in a corner). apps/viewer/overlays.cpp draws them.
#pragma once

#include <array>
#include <string>

#include "treesketch/geom/camera.h"
#include "treesketch/geom/types.h"

namespace treesketch::viewer {

/// The largest "round" length — 1, 2 or 5 times a power of ten — not above `maxLength`; 0 for a
/// non-positive or non-finite input.
double roundLengthAtMost(double maxLength);

/// A length in metres as a person writes it: "5 mm", "2 cm", "50 cm", "1 m", "20 m", "2 km"
/// (the unit chosen so the number is at least 1; up to 3 significant digits).
std::string formatLength(double metres);

struct ScaleBar {
  double length = 0.0;  ///< world units
  double pixels = 0.0;  ///< on screen
  std::string label;    ///< "50 cm"
  bool valid() const { return length > 0.0 && pixels > 0.0; }
};

/// The scale bar for a view where one pixel spans `worldPerPixel` world units (at the orbit
/// target's depth): the longest round length that fits in `maxPixels`. `unitsMetres` is the size of
/// one world unit in metres (1 for clouds in metres) and only changes the label. Invalid (length 0)
/// for a non-positive or non-finite scale.
ScaleBar scaleBarFor(double worldPerPixel, double maxPixels, double unitsMetres = 1.0);

/// One axis of the gizmo: world axis `axis` (0 = X, 1 = Y, 2 = Z) as seen by the camera.
struct GizmoAxis {
  int axis = 0;
  /// Screen direction of the axis (x right, y down), length = how much of it faces the screen
  /// (1 when it lies in the screen plane, 0 when it points at the viewer).
  geom::Vec2 direction = geom::Vec2::Zero();
  /// Towards the viewer (> 0) or away (< 0): the component along the camera's backward axis.
  double towardsViewer = 0.0;
};

/// The three axes under `camera`, sorted back to front (draw them in this order so the nearer
/// ones cover the farther).
std::array<GizmoAxis, 3> axisGizmo(const geom::Camera& camera);

}  // namespace treesketch::viewer
