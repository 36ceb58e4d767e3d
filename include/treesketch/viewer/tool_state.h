// The desktop tool's hand on the sketch: which tool a left click or drag uses, the path being
// dragged (stroke, lasso, region), the selected and the active node, and the mouse gesture under
// way (a press that may become a click, a node drag, an orbit or a pan). It owns no sketch: the
// edits that selection and tools make go through ViewerState, which keeps this part consistent
// with the sketch after every edit. Plain C++, no GL.
#pragma once

#include <cstdint>
#include <vector>

#include "treesketch/geom/types.h"
#include "treesketch/sketch/sketch.h"

namespace treesketch::viewer {

enum class MouseButton { Left, Right, Middle };
/// Modifier key bits for mouse and key events.
enum Modifier : int { kModNone = 0, kModShift = 1, kModCtrl = 2, kModAlt = 4 };

/// What a left click or drag in the view does: Select (pick and drag nodes; a click on empty
/// space adds nothing, Shift+click adds a node there — the default), AddNodes (a click on
/// empty space adds a node), Stroke (draw a limb as one stroke), Lasso (mark points as
/// not-wood), Region (automatic skeleton inside the drawn region, merged), Reattach (a click on
/// a node makes it the selected node's new parent). Keys: N add nodes, G stroke, X lasso, R
/// region, P re-attach (each toggles its tool), H automatic below the selected node, Escape
/// back to Select.
enum class Tool { Select, AddNodes, Stroke, Lasso, Region, Reattach, LassoWood };
/// The tool's name as the canvas and the Tools menu show it ("select", "add nodes", ...).
const char* toolLabel(Tool tool);
/// The tool's name with a line on how to use it (the status line when it is chosen).
const char* toolHelp(Tool tool);

class ToolState {
 public:
  Tool tool() const { return tool_; }
  /// The stroke or polygon being drawn (window pixels), for the overlay; empty when none.
  const std::vector<geom::Vec2>& toolPath() const { return toolPath_; }
  sketch::NodeId selected() const { return selected_; }
  /// The node new nodes hang from (kNoNode: none).
  sketch::NodeId active() const { return active_; }
  /// The person chose the active node (selected it, added it, dragged it); false when it is a
  /// fallback (the root after a load, an automatic sketch, a deletion of the active node).
  bool activeChosen() const { return activeChosen_; }
  /// The Reattach tool's first click (the node to move; kNoNode before it).
  sketch::NodeId reattachSource() const { return reattachSource_; }

 private:
  friend class ViewerState;
  enum class Gesture { None, PendingAdd, PendingEmpty, PendingNode, DragNode, Orbit, Pan, ToolPath };

  Tool tool_ = Tool::Select;
  std::vector<geom::Vec2> toolPath_;
  sketch::NodeId selected_ = sketch::kNoNode;
  sketch::NodeId active_ = sketch::kNoNode;
  bool activeChosen_ = false;
  sketch::NodeId reattachSource_ = sketch::kNoNode;

  Gesture gesture_ = Gesture::None;
  MouseButton gestureButton_ = MouseButton::Left;
  int gestureMods_ = kModNone;
  geom::Vec2 pressPos_ = geom::Vec2::Zero();
  geom::Vec2 lastPos_ = geom::Vec2::Zero();
  sketch::NodeId gestureNode_ = sketch::kNoNode;
  std::uint64_t dragSerial_ = 0;
};

}  // namespace treesketch::viewer
