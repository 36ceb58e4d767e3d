#include "treesketch/viewer/key_bindings.h"

namespace treesketch::viewer {

const std::vector<KeyBinding>& keyBindings() {
  static const std::vector<KeyBinding> table = {
      {"Mouse", "Left click", "select the node under the mouse (on empty space: nothing is added)", ""},
      {"Mouse", "Shift+left click", "add a node there (child of the active node, else of the nearest node)", ""},
      {"Mouse", "Ctrl+left click", "select a node without making it active (new nodes keep their parent)", ""},
      {"Mouse", "Left drag on a node", "move the node", ""},
      {"Mouse", "Right drag, Alt+left drag", "orbit (trackball)", ""},
      {"Mouse", "Middle drag, Shift+right drag", "pan", ""},
      {"Mouse", "Wheel", "zoom", ""},
      {"Sketch", "Delete, Backspace", "delete the selected node (its children are re-attached to its parent)",
       "delete"},
      {"Sketch", "Shift+Delete", "delete the selected node with its subtree", "shift+delete"},
      {"Sketch", "Ctrl+Z", "undo", "ctrl+z"},
      {"Sketch", "Ctrl+Y, Ctrl+Shift+Z", "redo", "ctrl+y"},
      {"Sketch", "Esc", "deselect, and dismiss the error in the status bar (in pick mode: clear the picks, then leave)",
       "escape"},
      {"Sketch", "A", "uniform automatic sketch (asks first when it would replace hand edits; undoable)", "a"},
      {"Tools", "N", "tool: add nodes: a left click on the cloud adds a node (again: back to selecting)", "n"},
      {"Tools", "G", "tool: draw a limb as one stroke (drag along it; again: back to selecting)", "g"},
      {"Tools", "X", "tool: lasso points as not-wood (excluded from fits and the automatic skeleton)", "x"},
      {"Tools", "Shift+X", "tool: lasso points as wood (the fits use them whatever the classification says)",
       "shift+x"},
      {"Tools", "K", "classify wood and leaves (a background job; the fits then use the wood only)", "k"},
      {"Tools", "R", "tool: automatic skeleton inside a drawn region, merged into the sketch", "r"},
      {"Tools", "P", "tool: re-attach: click a node, then its new parent (Shift: turn the limb round)", "p"},
      {"Tools", "H", "automatic skeleton below the selected node, merged", "h"},
      {"Tools", "M", "pick mode: a left click picks a point (coordinates, attributes); two picks measure", ""},
      {"View", "F", "fit the view to the cloud", "f"},
      {"View", "O", "orthographic / perspective", "o"},
      {"View", "1, 2, 3", "front, side, top view", "1"},
      {"View", "W", "tubes: solid, wireframe, hidden", "w"},
      {"View", "C", "next point colouring: height, distance to the model's surface, plain, the file's attributes, "
       "the wood probability and class", "c"},
      {"View", "L", "node labels: automatic (shown up to 100 nodes), on, off", "l"},
      {"File", "Ctrl+O", "open a cloud", ""},
      {"File", "Ctrl+S", "save the sketch to the sketch path", "ctrl+s"},
      {"File", "Ctrl+Shift+S", "save the sketch as", ""},
      {"File", "Ctrl+E", "export the mesh", ""},
      {"File", "Ctrl+Q", "quit (asks about unsaved work)", ""},
      {"Help", "F1", "help: this list of keys", ""},
  };
  return table;
}

}  // namespace treesketch::viewer
