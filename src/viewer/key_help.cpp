#include "treesketch/viewer/key_help.h"

namespace treesketch::viewer {

std::vector<KeyHelp> helpKeyBindings() {
  return {
      {"Mouse", "Left click", "add a node (child of the active node) / select a node and make it active", ""},
      {"Mouse", "Ctrl+left click", "select a node only", ""},
      {"Mouse", "Left drag on a node", "move the node", ""},
      {"Mouse", "Right drag (Alt+left drag)", "orbit", ""},
      {"Mouse", "Middle drag (Shift+right drag)", "pan", ""},
      {"Mouse", "Wheel", "zoom", ""},
      {"Sketch", "Delete / Backspace", "delete the selected node (children re-attached)", "delete"},
      {"Sketch", "Shift+Delete", "delete the selected node with its subtree", "shift+delete"},
      {"Sketch", "Ctrl+Z", "undo", "ctrl+z"},
      {"Sketch", "Ctrl+Y / Ctrl+Shift+Z", "redo", "ctrl+y"},
      {"Sketch", "A", "replace the sketch by the uniform automatic sketch", "a"},
      {"Sketch", "Esc", "deselect (in pick mode: clear the picks)", "escape"},
      {"View", "1 / 2 / 3", "front / side / top view", "1"},
      {"View", "F", "fit the view to the cloud", "f"},
      {"View", "O", "orthographic / perspective", "o"},
      {"View", "W", "tubes: solid / wireframe / hidden", "w"},
      {"View", "C", "next point colouring (height, distance, plain, the file's attributes)", "c"},
      {"File", "Ctrl+O", "open a cloud", ""},
      {"File", "Ctrl+S", "save the sketch", "ctrl+s"},
      {"File", "Ctrl+Shift+S", "save the sketch as", ""},
      {"File", "Ctrl+E", "export the mesh", ""},
      {"File", "Ctrl+Q", "quit (asks about unsaved work)", ""},
      {"Tools", "P", "pick mode: left click picks points (coordinates, attributes); two picks measure", ""},
      {"Help", "F1", "this list", ""},
  };
}

}  // namespace treesketch::viewer
