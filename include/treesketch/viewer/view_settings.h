// The desktop tool's view: the orbit camera and the viewport it draws into, the view's up
// direction, how the cloud, nodes and mesh are drawn (colouring, point size, labels), and when
// the view last moved (the window draws a subsample while it moves). It owns no data: the cloud
// and the sketch are ViewerState's; what needs them (the up direction's effect on the sketch, the
// lying-down warning, the colours) is done by ViewerState. Plain C++, no GL.
#pragma once

#include <chrono>
#include <cstdint>
#include <string>

#include "treesketch/geom/camera.h"
#include "treesketch/viewer/orbit_camera.h"
#include "treesketch/viewer/point_colors.h"
#include "treesketch/viewer/view_up.h"

namespace treesketch::viewer {

/// Point colourings. The last three colour by the file's attributes (viewer/color_legend.h says
/// which a cloud has); a cloud without the attribute is drawn plain.
/// WoodProbability and WoodClass show the viewer's own wood/leaf classification
/// (ViewerState::woodClasses; the class after the lassos), the others the file's attributes.
enum class ColorMode {
  Height,
  CircleDistance,
  Plain,
  Intensity,
  FileColor,
  Classification,
  WoodProbability,
  WoodClass
};
enum class MeshStyle { Solid, Wireframe, Hidden };
/// Node numbers beside the markers: Auto (up to ViewerOptions::autoLabelMaxNodes nodes), On, Off.
enum class LabelMode { Auto, On, Off };

/// Parses "height" / "distance" / "plain" / "intensity" / "rgb" / "classification" /
/// "wood-probability" / "wood-class"; throws
/// OptionsError otherwise.
ColorMode parseColorMode(const std::string& s);
/// Parses "solid" / "wireframe" / "hidden"; throws OptionsError otherwise.
MeshStyle parseMeshStyle(const std::string& s);
/// Parses "auto" / "on" / "off"; throws OptionsError otherwise.
LabelMode parseLabelMode(const std::string& s);
const char* toString(ColorMode mode);
const char* toString(MeshStyle style);
const char* toString(LabelMode mode);

struct DisplayOptions {
  ColorMode colorMode = ColorMode::Height;
  float pointSize = 2.0f;  ///< window pixels
  MeshStyle meshStyle = MeshStyle::Solid;
  bool showCloud = true;
  bool showNodes = true;
  bool showCircles = true;
  bool showSamplingRegion = true;  ///< the selected node's slab, cylinder and slice points
  LabelMode labels = LabelMode::Auto;
};

class ViewSettings {
 public:
  OrbitCamera& orbit() { return orbit_; }
  const OrbitCamera& orbit() const { return orbit_; }
  geom::Camera camera() const { return orbit_.camera(); }
  /// The 3D view's rectangle in window pixels (top-left origin).
  void setViewport(const geom::Viewport& viewport) { orbit_.setViewport(viewport); }
  /// Frames the cloud (its bounds, given by ViewerState when a cloud opens).
  void fitView() { orbit_.fit(); }
  /// A preset view (front, side, top) about the view's up direction.
  void presetView(geom::PresetView view) { orbit_.preset(view, upDirectionVector(up_)); }
  void setOrthographic(bool ortho) { orbit_.setOrthographic(ortho); }

  DisplayOptions& display() { return display_; }
  const DisplayOptions& display() const { return display_; }
  void setColorMode(ColorMode mode) { display_.colorMode = mode; }

  /// The view's up direction (initially the cloud's up axis; ViewerState::setUpDirection sets it).
  UpDirection upDirection() const { return up_; }
  /// The person has hidden the lying-down banner (until the up direction or the cloud changes).
  bool upWarningDismissed() const { return upWarningDismissed_; }
  void dismissUpWarning() { upWarningDismissed_ = true; }

  /// The view is moving (an orbit, pan or zoom within the last kViewSettleSeconds): the window
  /// draws a subsample of the cloud (PointLod) and the whole cloud once it is still.
  bool viewMoving(std::chrono::steady_clock::time_point now) const { return now < viewSettles(); }
  /// When the view counts as still (for the window's next wake-up).
  std::chrono::steady_clock::time_point viewSettles() const {
    return lastViewChange_ + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                                 std::chrono::duration<double>(kViewSettleSeconds));
  }
  /// Design choice: a pause of 0.15 s between mouse moves ends a gesture (longer than a frame at
  /// 10 Hz, shorter than a person notices the full cloud coming back late).
  static constexpr double kViewSettleSeconds = 0.15;

 private:
  friend class ViewerState;
  OrbitCamera orbit_;
  DisplayOptions display_;
  UpDirection up_ = UpDirection::PosY;
  bool upWarningDismissed_ = false;
  std::chrono::steady_clock::time_point lastViewChange_{};
};

}  // namespace treesketch::viewer
