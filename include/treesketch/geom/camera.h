// Cameras: the view, projection and viewport a sketch node was drawn under, and the mapping
// between screen pixels and world space (as gluUnProject / glm::unProject, but with the screen
// origin at the viewport's top-left and y pointing down, as mouse events arrive).
#pragma once

#include <string>

#include "treesketch/geom/types.h"

namespace treesketch::geom {

struct Viewport {
  double x = 0, y = 0, width = 1280, height = 800;  ///< pixels

  /// Whether the window point `p` (pixels) is in the rectangle, edges included (written as "not
  /// outside", so a NaN coordinate is not rejected here, as the viewer's checks always did).
  bool contains(const Vec2& p) const { return !(p.x() < x || p.y() < y || p.x() > x + width || p.y() > y + height); }
};

struct Camera {
  Mat4 view = Mat4::Identity();        ///< world -> eye (OpenGL convention: eye looks down -Z)
  Mat4 projection = Mat4::Identity();  ///< eye -> clip (OpenGL convention, depth in [-1, 1])
  Viewport viewport;

  /// True when the projection is orthographic (all view rays parallel).
  bool isOrthographic() const { return projection(3, 3) == 1.0 && projection(3, 2) == 0.0; }
  /// World position of the screen point (pixels, top-left origin, y down) at window depth
  /// `depth01` (0 = near plane, 1 = far plane). Throws OptionsError if the matrices are singular.
  Vec3 unproject(const Vec2& screen, double depth01) const;
  /// Screen position (pixels, top-left origin) and window depth in [0, 1] of a world point.
  /// The depth is outside [0, 1] for points outside the near/far range.
  Vec3 project(const Vec3& world) const;
  /// Eye position in world (for perspective cameras; for orthographic, a point on the view axis).
  Vec3 eye() const;
  /// Unit viewing direction in world (the eye's -Z).
  Vec3 forward() const;
  /// Unit screen-up direction in world (the eye's +Y).
  Vec3 up() const;
  /// Unit screen-right direction in world (the eye's +X).
  Vec3 right() const;
  /// Throws OptionsError naming `what` if the camera is degenerate (singular matrices, zero-size
  /// viewport, NaN).
  void validate(const std::string& what) const;
};

Mat4 lookAt(const Vec3& eye, const Vec3& target, const Vec3& up);
/// OpenGL-style perspective projection; fovY in degrees.
Mat4 perspective(double fovYDeg, double aspect, double zNear, double zFar);
/// OpenGL-style orthographic projection.
Mat4 orthographic(double left, double right, double bottom, double top, double zNear, double zFar);

enum class PresetView { Front, Side, Top };
/// Parses "front", "side" or "top"; throws OptionsError otherwise.
PresetView parsePresetView(const std::string& s);

/// A camera framing `box` from a preset direction: front looks along the horizontal axis that is
/// not X (-Z for Y-up, +Y for Z-up), side looks along -X, top looks down. The box fills the
/// viewport with a 5 % margin. Orthographic or perspective (30° vertical field of view).
Camera presetCamera(PresetView view, const BBox& box, UpAxis up, const Viewport& viewport, bool orthographic);

}  // namespace treesketch::geom
