// The viewer's orbit camera: a target point, a distance and an orientation, moved by a trackball
// (arcball) rotation, panning and zooming, framed on a box or set to a preset view; it yields the
// geom::Camera (view, projection, viewport) that sketch nodes are drawn under. Plain C++, no GL.
#pragma once

#include <Eigen/Geometry>

#include "treesketch/geom/camera.h"
#include "treesketch/geom/types.h"

namespace treesketch::viewer {

struct OrbitCameraOptions {
  /// Vertical field of view of the perspective projection, degrees (the preset cameras of
  /// geom::presetCamera use 30°; the same here so both frame alike).
  double fovYDeg = 30.0;
  /// Zoom factor per wheel step (distance multiplied by this for one step towards the target).
  double zoomStep = 0.88;
  /// Margin around a framed box, as a fraction of its bounding sphere radius.
  double fitMargin = 0.05;
  /// Multiplier on the arcball's rotation angle (1: the point under the mouse follows it on a sphere
  /// of radius half the smaller viewport side; 2 turns twice as fast).
  double trackballSpeed = 1.5;
};

class OrbitCamera {
 public:
  explicit OrbitCamera(const OrbitCameraOptions& options = {});

  /// Viewport in window pixels (top-left origin, y down). Ignores non-positive sizes.
  void setViewport(const geom::Viewport& viewport);
  const geom::Viewport& viewport() const { return viewport_; }

  /// The scene's bounds, used for near/far planes and by fit()/preset(). An empty box is ignored.
  void setSceneBounds(const geom::BBox& box);
  const geom::BBox& sceneBounds() const { return scene_; }

  /// Orthographic (true) or perspective (false) projection. The view keeps the same size at the
  /// target when switching.
  void setOrthographic(bool ortho) { ortho_ = ortho; }
  bool orthographic() const { return ortho_; }

  /// Frames the scene bounds (its bounding sphere fills the smaller viewport side, plus the margin)
  /// keeping the current orientation.
  void fit();
  /// Looks from a preset direction (as geom::presetCamera: front, side, top, for the up axis) and
  /// frames the scene bounds.
  void preset(geom::PresetView view, geom::UpAxis up);
  /// The same for any unit `up` vector (world frame; ±X, ±Y, ±Z in the viewer): front looks along
  /// -Z for an up along Y or X, along +Y for an up along Z; side is up x front; top looks down
  /// `up`. For +Y and +Z this is exactly the preset above.
  void preset(geom::PresetView view, const geom::Vec3& up);

  /// Trackball rotation for a mouse drag from `from` to `to` (window pixels): the scene turns as if
  /// the mouse dragged a sphere around the target. A zero drag does nothing.
  void rotate(const geom::Vec2& from, const geom::Vec2& to);
  /// Moves the target so the scene follows a drag by `delta` window pixels (at the target's depth).
  void pan(const geom::Vec2& delta);
  /// Zooms by `steps` wheel steps (positive: closer). Distance stays within [1e-4, 1e4] x scene size.
  void zoom(double steps);

  /// World length of one pixel at the target's depth.
  double worldPerPixel() const;

  /// The camera (view, projection, viewport) for the current state. Near/far planes enclose the
  /// scene bounds (or a unit box around the target when there are none).
  geom::Camera camera() const;

  const geom::Vec3& target() const { return target_; }
  double distance() const { return distance_; }
  /// Rotation from eye axes to world axes (columns: screen right, screen up, backwards).
  const Eigen::Quaterniond& orientation() const { return orientation_; }
  void setTarget(const geom::Vec3& target) { target_ = target; }
  void setDistance(double d);
  void setOrientation(const Eigen::Quaterniond& q) { orientation_ = q.normalized(); }
  const OrbitCameraOptions& options() const { return options_; }

 private:
  geom::Vec3 trackballPoint(const geom::Vec2& screen) const;
  double sceneRadius() const;

  OrbitCameraOptions options_;
  geom::Viewport viewport_;
  geom::BBox scene_;
  geom::Vec3 target_ = geom::Vec3::Zero();
  double distance_ = 5.0;
  Eigen::Quaterniond orientation_ = Eigen::Quaterniond::Identity();
  bool ortho_ = false;
};

}  // namespace treesketch::viewer
