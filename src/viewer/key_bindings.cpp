#include "treesketch/viewer/key_bindings.h"

namespace treesketch::viewer {

const std::vector<KeyBinding>& keyBindings() {
  static const std::vector<KeyBinding> table = {
      {"Left click", "add a node (child of the active node, else of the nearest node) or select a node", ""},
      {"Ctrl+left click", "select a node without making it active (new nodes keep their parent)", ""},
      {"Left drag on a node", "move the node", ""},
      {"Right drag, Alt+left drag", "orbit (trackball)", ""},
      {"Middle drag, Shift+right drag", "pan", ""},
      {"Wheel", "zoom", ""},
      {"Delete, Backspace", "delete the selected node (its children are re-attached to its parent)", "delete"},
      {"Shift+Delete", "delete the selected node with its subtree", "shift+delete"},
      {"Ctrl+Z", "undo", "ctrl+z"},
      {"Ctrl+Y, Ctrl+Shift+Z", "redo", "ctrl+y"},
      {"Ctrl+S", "save the sketch to the sketch path", "ctrl+s"},
      {"Esc", "deselect, and dismiss the error in the status bar", "escape"},
      {"F", "fit the view to the cloud", "f"},
      {"O", "orthographic / perspective", "o"},
      {"1, 2, 3", "front, side, top view", "1"},
      {"A", "uniform automatic sketch (asks first when it would replace hand edits; undoable)", "a"},
      {"W", "tubes: solid, wireframe, hidden", "w"},
      {"C", "colour: height, distance to the circles, plain", "c"},
      {"L", "node labels: automatic (shown up to 100 nodes), on, off", "l"},
      {"G", "tool: draw a limb as one stroke (drag along it; again: back to sketching)", "g"},
      {"X", "tool: lasso points as not-wood (excluded from fits and the automatic skeleton)", "x"},
      {"R", "tool: automatic skeleton inside a drawn region, merged into the sketch", "r"},
      {"P", "tool: re-attach: click a node, then its new parent", "p"},
      {"H", "automatic skeleton below the selected node, merged", "h"},
      {"F1", "help: this list of keys", ""},
  };
  return table;
}

}  // namespace treesketch::viewer
