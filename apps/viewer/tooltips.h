// Tooltips for the side panel's controls, kept in one table keyed by each control's label rather
// than written after every widget: panels.cpp stays as it is and a new control needs one row here.
#pragma once

namespace treesketch::gui {

/// Shows the tooltip of the panel control under the mouse, if it has one. Call inside the panel's
/// window, after its last control and before ImGui::End() (it compares the hovered item's id with
/// the ids of the labels in the table, so the controls must not be inside a PushID scope).
void panelTooltips();

/// How many labels the table has a tooltip for (tests, docs).
int panelTooltipCount();

}  // namespace treesketch::gui
