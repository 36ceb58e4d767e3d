// Whether quitting or opening another cloud would lose work: the question behind the desktop
// tool's "Save / Discard / Cancel" prompt. Plain C++, no GL.
#pragma once

#include "treesketch/viewer/viewer_state.h"

namespace treesketch::viewer {

/// True when the sketch in `state` is not what its sketch file (state.sketchPath()) holds: it has
/// nodes and the file is missing, unreadable or holds a different sketch (compared as the sketch
/// file format writes them, so a sketch loaded and not edited is not "unsaved"). An empty sketch is
/// never unsaved work (there is nothing to lose). Decision: this asks the file rather than counting
/// edits, so every way of saving (menu, Ctrl+S, a script) and undoing back to the saved state are
/// seen alike. Reads the sketch file: call it when the question is asked, not every frame.
bool hasUnsavedWork(const ViewerState& state);

}  // namespace treesketch::viewer
