// Every key and mouse gesture of the desktop tool in one table: the README's key table and the
// window's help overlay (F1) are both written from it, and a test checks that each keyboard entry
// is bound in ViewerState::keyPress and named in the README, so the three cannot drift apart.
#pragma once

#include <string>
#include <vector>

namespace treesketch::viewer {

struct KeyBinding {
  /// The help overlay's heading: "Mouse", "Sketch", "Tools", "View", "File", "Help".
  std::string group;
  /// What the person presses, as shown to them ("Ctrl+Z", "Right drag").
  std::string keys;
  /// What it does, one line.
  std::string action;
  /// The name ViewerState::keyPress takes for it ("ctrl+z"); empty for mouse gestures and for
  /// keys the window handles itself (F1, M, the File menu's shortcuts: apps/viewer's
  /// WindowActions::onKey).
  std::string keyName;
};

/// The table, in the order a help screen lists it (mouse first, then keys, grouped).
const std::vector<KeyBinding>& keyBindings();

}  // namespace treesketch::viewer
