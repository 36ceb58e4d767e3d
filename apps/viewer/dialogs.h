// The window's modal questions and overlays that sit over the 3D view: the offer of an earlier
// session's autosave (restore / discard / keep for later), the question before an automatic sketch
// replaces hand edits. Each reads and answers one ViewerState
// question; nothing here keeps sketch state.
#pragma once

#include "treesketch/viewer/viewer_state.h"

namespace treesketch::gui {

/// While state.document().recoveryPending(): a modal "Restore earlier work?" with Restore / Discard / Keep for
/// later. Call between ImGui::NewFrame and Render, after the panels.
void drawRecoveryDialog(viewer::ViewerState& state);

/// While state.upWarningShown(): a banner at the top of the 3D view with the warning, the up-axis
/// choice and Dismiss.
void drawUpWarning(viewer::ViewerState& state);

/// While state.jobs().busy(): a small window over the view with the job's progress bar and Cancel.
void drawJobProgress(viewer::ViewerState& state);

/// While state.confirmationPending(): a modal with the question, Replace and Keep my sketch.
void drawConfirmDialog(viewer::ViewerState& state);

}  // namespace treesketch::gui
