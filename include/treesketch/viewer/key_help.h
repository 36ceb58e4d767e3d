// The list of keys and mouse gestures the help overlay (F1) shows. Interim: another change
// (issue 20, the GUI fixes) adds the single table of key bindings the tool dispatches from
// (`keyBindings()` in src/viewer); when both are merged the overlay should list that table and this
// file should keep only the window's own keys and the mouse gestures. Same shape: one row per
// binding, grouped.
#pragma once

#include <string>
#include <vector>

namespace treesketch::viewer {

struct KeyHelp {
  std::string group;  ///< "View", "Sketch", "File", "Tools", "Mouse"
  std::string keys;   ///< as shown: "Ctrl+Z", "Shift+Delete", "Right drag"
  std::string action;
  /// The name ViewerState::keyPress takes for it ("ctrl+z"); empty for keys the window handles
  /// itself (menus, F1, pick mode) and for mouse gestures.
  std::string stateKey;
};

/// Every key and gesture of the tool, grouped, in the order the overlay lists them.
std::vector<KeyHelp> helpKeyBindings();

}  // namespace treesketch::viewer
