// ViewerState's input handling: mouse gestures (pick, drag a node, add a node, orbit, pan), the
// wheel and key bindings, steering the view part and the tool part. See viewer_state.h for the
// map of the files that implement ViewerState.
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

bool ViewerState::sameAsCurrent(const geom::Camera& cam) const {
  geom::Camera cur = view_.orbit_.camera();
  return sameMatrix(cam.view, cur.view) && sameMatrix(cam.projection, cur.projection) &&
         cam.viewport.x == cur.viewport.x && cam.viewport.y == cur.viewport.y &&
         cam.viewport.width == cur.viewport.width && cam.viewport.height == cur.viewport.height;
}

// ---- input ---------------------------------------------------------------------------------------

void ViewerState::mouseDown(const Vec2& pos, MouseButton button, int mods) {
  tools_.gesture_ = Gesture::None;
  if (!view_.orbit_.viewport().contains(pos)) return;
  tools_.pressPos_ = tools_.lastPos_ = pos;
  tools_.gestureButton_ = button;
  tools_.gestureMods_ = mods;
  if (toolMouseDown(pos, button, mods)) return;
  if (button == MouseButton::Left && !(mods & kModAlt)) {
    tools_.gestureNode_ = scene_.nodeAt(pos);
    // Clicks select by default: adding is the AddNodes tool's, or Shift's, so that a click that
    // misses a marker by a few pixels never makes a stray node.
    const bool adds = tools_.tool_ == Tool::AddNodes || (mods & kModShift);
    tools_.gesture_ = tools_.gestureNode_ != kNoNode ? Gesture::PendingNode
                      : adds                         ? Gesture::PendingAdd
                                                     : Gesture::PendingEmpty;
  } else if ((button == MouseButton::Right && !(mods & kModShift)) || button == MouseButton::Left) {
    tools_.gesture_ = Gesture::Orbit;
  } else {
    tools_.gesture_ = Gesture::Pan;
  }
}

void ViewerState::mouseMove(const Vec2& pos) {
  switch (tools_.gesture_) {
    case Gesture::PendingNode:
      if ((pos - tools_.pressPos_).norm() < options_.dragThresholdPx) break;
      tools_.gesture_ = Gesture::DragNode;
      ++tools_.dragSerial_;
      tools_.selected_ = tools_.active_ = tools_.gestureNode_;
      tools_.activeChosen_ = true;
      [[fallthrough]];
    case Gesture::DragNode:
      moveNodeImpl(tools_.gestureNode_, pos, "drag:" + std::to_string(tools_.dragSerial_));
      break;
    case Gesture::Orbit:
      view_.orbit_.rotate(tools_.lastPos_, pos);
      viewMoved();
      break;
    case Gesture::Pan:
      view_.orbit_.pan(pos - tools_.lastPos_);
      viewMoved();
      break;
    case Gesture::ToolPath:
      tools_.toolPath_.push_back(pos);
      ++sceneVersion_;
      break;
    default:
      break;
  }
  tools_.lastPos_ = pos;
}

void ViewerState::mouseUp(const Vec2& pos, MouseButton button, int mods) {
  (void)mods;
  if (tools_.gesture_ == Gesture::None || button != tools_.gestureButton_) return;
  if (pos != tools_.lastPos_) mouseMove(pos);
  Gesture g = tools_.gesture_;
  tools_.gesture_ = Gesture::None;
  if (g == Gesture::ToolPath) {
    toolMouseUp(pos);
  } else if (g == Gesture::PendingNode) {
    if (tools_.gestureMods_ & kModCtrl) {
      // Ctrl+click: inspect a node without changing where new nodes attach.
      tools_.selected_ = tools_.gestureNode_;
      ++sceneVersion_;
    } else {
      selectNode(tools_.gestureNode_);
    }
    if (const std::size_t under = scene_.markersAt(pos); under > 1)
      info("selected node " + std::to_string(tools_.gestureNode_) + ", the nearest to the eye of " +
           std::to_string(under) + " markers under the click");
  } else if (g == Gesture::PendingAdd) {
    if ((pos - tools_.pressPos_).norm() < options_.dragThresholdPx) addNodeAt(pos);
  } else if (g == Gesture::PendingEmpty) {
    if ((pos - tools_.pressPos_).norm() < options_.dragThresholdPx) {
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
  view_.orbit_.zoom(steps);
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
    if (doc_.sketchPath().empty())
      error("save: no sketch path (type one in the panel and use Save)");
    else
      saveSketch(doc_.sketchPath());
  } else if (key == "escape") {
    selectNode(kNoNode);
    status_.dismiss();
  } else if (key == "f") {
    view_.fitView();
  } else if (key == "o") {
    view_.setOrthographic(!view_.orbit_.orthographic());
  } else if (key == "1") {
    view_.presetView(geom::PresetView::Front);
  } else if (key == "2") {
    view_.presetView(geom::PresetView::Side);
  } else if (key == "3") {
    view_.presetView(geom::PresetView::Top);
  } else if (key == "a") {
    requestAutoSketchUniform();
  } else if (key == "w") {
    view_.display_.meshStyle = static_cast<MeshStyle>((static_cast<int>(view_.display_.meshStyle) + 1) % 3);
  } else if (key == "c") {
    // The file's attributes too, and the wood/leaf classification once there is one.
    view_.display_.colorMode = nextColorMode(view_.display_.colorMode, cloud_, classes_ != nullptr);
  } else if (key == "l") {
    view_.display_.labels = static_cast<LabelMode>((static_cast<int>(view_.display_.labels) + 1) % 3);
    info(std::string("node labels: ") + toString(view_.display_.labels));
  } else {
    return false;
  }
  return true;
}

}  // namespace treesketch::viewer
