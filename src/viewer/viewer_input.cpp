// ViewerState, part 2 of 3: input handling — mouse gestures (pick, drag a node, add a node,
// orbit, pan), the wheel, key bindings, and the view they steer. See viewer_state.cpp for the
// map of the three parts.
#include <algorithm>

#include "treesketch/util/text.h"
#include "treesketch/viewer/color_legend.h"
#include "treesketch/viewer/viewer_state.h"

namespace treesketch::viewer {

using geom::Vec2;

namespace {

/// Equal up to rounding (1e-12 of the larger entry): a camera rebuilt from the orbit's state may
/// differ from a stored copy in the last bits.
bool sameMatrix(const geom::Mat4& a, const geom::Mat4& b) {
  double scale = std::max(a.cwiseAbs().maxCoeff(), b.cwiseAbs().maxCoeff());
  return (a - b).cwiseAbs().maxCoeff() <= 1e-12 * std::max(scale, 1.0);
}

}  // namespace

// ---- view ----------------------------------------------------------------------------------------

void ViewerState::setViewport(const geom::Viewport& viewport) { orbit_.setViewport(viewport); }

void ViewerState::fitView() { orbit_.fit(); }

void ViewerState::presetView(geom::PresetView view) { orbit_.preset(view, upDirectionVector(viewUp_)); }

void ViewerState::setOrthographic(bool ortho) { orbit_.setOrthographic(ortho); }

bool ViewerState::sameAsCurrent(const geom::Camera& cam) const {
  geom::Camera cur = orbit_.camera();
  return sameMatrix(cam.view, cur.view) && sameMatrix(cam.projection, cur.projection) &&
         cam.viewport.x == cur.viewport.x && cam.viewport.y == cur.viewport.y &&
         cam.viewport.width == cur.viewport.width && cam.viewport.height == cur.viewport.height;
}

// ---- input ---------------------------------------------------------------------------------------

void ViewerState::mouseDown(const Vec2& pos, MouseButton button, int mods) {
  gesture_ = Gesture::None;
  if (!orbit_.viewport().contains(pos)) return;
  pressPos_ = lastPos_ = pos;
  gestureButton_ = button;
  gestureMods_ = mods;
  if (toolMouseDown(pos, button, mods)) return;
  if (button == MouseButton::Left && !(mods & kModAlt)) {
    gestureNode_ = nodeAt(pos);
    // Clicks select by default: adding is the AddNodes tool's, or Shift's, so that a click that
    // misses a marker by a few pixels never makes a stray node.
    const bool adds = tool_ == Tool::AddNodes || (mods & kModShift);
    gesture_ = gestureNode_ != kNoNode ? Gesture::PendingNode : adds ? Gesture::PendingAdd : Gesture::PendingEmpty;
  } else if ((button == MouseButton::Right && !(mods & kModShift)) || button == MouseButton::Left) {
    gesture_ = Gesture::Orbit;
  } else {
    gesture_ = Gesture::Pan;
  }
}

void ViewerState::mouseMove(const Vec2& pos) {
  switch (gesture_) {
    case Gesture::PendingNode:
      if ((pos - pressPos_).norm() < options_.dragThresholdPx) break;
      gesture_ = Gesture::DragNode;
      ++dragSerial_;
      selected_ = active_ = gestureNode_;
      activeChosen_ = true;
      [[fallthrough]];
    case Gesture::DragNode:
      moveNodeImpl(gestureNode_, pos, "drag:" + std::to_string(dragSerial_));
      break;
    case Gesture::Orbit:
      orbit_.rotate(lastPos_, pos);
      viewMoved();
      break;
    case Gesture::Pan:
      orbit_.pan(pos - lastPos_);
      viewMoved();
      break;
    case Gesture::ToolPath:
      toolPath_.push_back(pos);
      ++sceneVersion_;
      break;
    default:
      break;
  }
  lastPos_ = pos;
}

void ViewerState::mouseUp(const Vec2& pos, MouseButton button, int mods) {
  (void)mods;
  if (gesture_ == Gesture::None || button != gestureButton_) return;
  if (pos != lastPos_) mouseMove(pos);
  Gesture g = gesture_;
  gesture_ = Gesture::None;
  if (g == Gesture::ToolPath) {
    toolMouseUp(pos);
  } else if (g == Gesture::PendingNode) {
    if (gestureMods_ & kModCtrl) {
      // Ctrl+click: inspect a node without changing where new nodes attach.
      selected_ = gestureNode_;
      ++sceneVersion_;
    } else {
      selectNode(gestureNode_);
    }
    if (const std::size_t under = markersAt(pos); under > 1)
      info("selected node " + std::to_string(gestureNode_) + ", the nearest to the eye of " + std::to_string(under) +
           " markers under the click");
  } else if (g == Gesture::PendingAdd) {
    if ((pos - pressPos_).norm() < options_.dragThresholdPx) addNodeAt(pos);
  } else if (g == Gesture::PendingEmpty) {
    if ((pos - pressPos_).norm() < options_.dragThresholdPx) {
      selectNode(kNoNode);
      info("no node here (nothing added): N or Tools > Add nodes adds nodes with a click, Shift+click adds one");
    }
  } else if (g == Gesture::DragNode) {
    lastEditKey_.clear();
    if (autosavePending_) {
      autosavePending_ = false;
      autosave();
    }
  }
}

void ViewerState::scroll(double steps) {
  orbit_.zoom(steps);
  viewMoved();
}

void ViewerState::clickAt(const Vec2& pos, MouseButton button, int mods) {
  mouseDown(pos, button, mods);
  mouseUp(pos, button, mods);
}

void ViewerState::dragTo(const Vec2& from, const Vec2& to, MouseButton button, int mods, int steps,
                         const std::function<void()>& afterEachMove) {
  steps = std::max(steps, 1);
  mouseDown(from, button, mods);
  for (int i = 1; i <= steps; ++i) {
    mouseMove(from + (to - from) * (double(i) / steps));
    if (afterEachMove) afterEachMove();
  }
  mouseUp(to, button, mods);
}

bool ViewerState::keyPress(const std::string& keyName, int mods) {
  std::string key = lowercase(keyName);
  for (;;) {
    if (key.rfind("ctrl+", 0) == 0)
      mods |= kModCtrl, key = key.substr(5);
    else if (key.rfind("shift+", 0) == 0)
      mods |= kModShift, key = key.substr(6);
    else if (key.rfind("alt+", 0) == 0)
      mods |= kModAlt, key = key.substr(4);
    else
      break;
  }
  bool ctrl = mods & kModCtrl, shift = mods & kModShift;
  if (toolKey(key, mods)) return true;
  if (key == "delete" || key == "backspace") {
    deleteSelected(shift);
  } else if (key == "z" && ctrl) {
    if (shift)
      redo();
    else
      undo();
  } else if (key == "y" && ctrl) {
    redo();
  } else if (key == "s" && ctrl) {
    if (sketchPath().empty())
      error("save: no sketch path (type one in the panel and use Save)");
    else
      saveSketch(sketchPath());
  } else if (key == "escape") {
    selectNode(kNoNode);
    dismissStatus();
  } else if (key == "f") {
    fitView();
  } else if (key == "o") {
    setOrthographic(!orbit_.orthographic());
  } else if (key == "1") {
    presetView(geom::PresetView::Front);
  } else if (key == "2") {
    presetView(geom::PresetView::Side);
  } else if (key == "3") {
    presetView(geom::PresetView::Top);
  } else if (key == "a") {
    requestAutoSketchUniform();
  } else if (key == "w") {
    display_.meshStyle = static_cast<MeshStyle>((static_cast<int>(display_.meshStyle) + 1) % 3);
  } else if (key == "c") {
    display_.colorMode = nextColorMode(display_.colorMode, cloud_);  // the file's attributes too
  } else if (key == "l") {
    display_.labels = static_cast<LabelMode>((static_cast<int>(display_.labels) + 1) % 3);
    info(std::string("node labels: ") + toString(display_.labels));
  } else {
    return false;
  }
  return true;
}

}  // namespace treesketch::viewer
