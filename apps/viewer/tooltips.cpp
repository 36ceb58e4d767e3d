#include "tooltips.h"

#include <imgui.h>
#include <imgui_internal.h>  // GImGui->HoveredId: the item under the mouse this frame

namespace treesketch::gui {

namespace {

struct Tip {
  const char* label;
  const char* text;
};

// One row per panel control (panels.cpp, tools_panel.cpp), by its full label (with any "##id": the
// ImGui ID is what is matched; gui.panels_unique_ids checks that no two controls share one).
const Tip kTips[] = {
    {"Files", "Sketch, mesh and screenshot files (also in the File menu)"},
    {"Open sketch...", "Choose a sketch file to load (undoable; asks when it was made for another cloud)"},
    {"Save sketch", "Write the sketch to its file (Ctrl+S; asks for a name when it has none)"},
    {"Save as...", "Save the sketch to another file, which becomes its file (Ctrl+Shift+S)"},
    {"Export mesh...", "Write the tube mesh as OBJ or PLY (Ctrl+E)"},
    {"png", "Where Screenshot writes"},
    {"Screenshot", "Save the window as a PNG"},
    {"Sketch", "Automatic sketches, clearing, undo and redo"},
    {"nodes##autoNodes", "How many nodes the uniform automatic sketch (Auto) places"},
    {"nodes##showNodes", "Draw the node markers and their parent links over the view"},
    {"node labels##labels", "Node numbers: automatic (shown up to 100 nodes), always or never (key L)"},
    {"up axis##upAxis", "Which direction is up in the view; the data and the sketch do not move"},
    {"Correction tools", "Edit the sketch in whole gestures: strokes, lassos, regions, re-attach"},
    {"Add nodes (N)", "A left click on the cloud adds a node under the active node (else clicks only select)"},
    {"Stroke (G)", "Drag along a missing limb, starting on the node it grows from"},
    {"Lasso (X)", "Drag around points that are not wood: fits and the skeleton leave them out"},
    {"Wood lasso (Shift+X)", "Drag around points that are wood: the fits use them whatever the classification says"},
    {"Classify wood/leaf (K)", "Tell wood from leaves (a background job): the fits and strokes then use the wood only"},
    {"Region (R)", "Drag around a region: the automatic skeleton runs there and is merged"},
    {"Re-attach (P)", "Click a node, then its new parent"},
    {"Automatic below selected (H)", "Re-run the automatic skeleton below the selected node and merge it"},
    {"Clear##notWood", "Remove every lasso, not-wood and wood (undoable)"},
    {"Auto", "Replace the sketch by the thesis's uniform automatic sketch (undoable)"},
    {"Auto skeleton", "Replace the sketch by the automatic branching skeleton (undoable)"},
    {"##leaves", "Leaf-off; in leaf: every point, the settings for leafy scans; wood only: the points classified "
                 "as wood (classifies first), the leaf-off settings"},
    {"Clear", "Remove every node (undoable)"},
    {"Refit all", "Fit every node from the cloud instead of keeping the automatic model's circles"},
    {"Undo", "Undo the last edit (Ctrl+Z)"},
    {"Redo", "Redo (Ctrl+Y)"},
    {"Node", "The selected node's fit and sampling sizes"},
    {"slice half-thickness", "Half the thickness of the slab around the node's plane that cuts its slice of points"},
    {"lineEpsilon",
     "Radius of the cylinder around the node's 3D line that keeps test points (grown until a circle fits)"},
    {"enabled", "A disabled node is kept in the sketch but not fitted"},
    {"Refit from the cloud", "Fit this node from the points instead of keeping the automatic model's circle"},
    {"Delete node", "Remove the node; its children join its parent (Delete)"},
    {"Delete subtree", "Remove the node and everything below it (Shift+Delete)"},
    {"Deselect", "Clear the selection (Esc)"},
    {"View", "How the cloud and the model are drawn"},
    {"colour", "Colour points by height, distance to the fitted circles, plain, or the file's attributes (C)"},
    {"point size", "Point size in pixels"},
    {"solid", "Draw the tubes shaded (W cycles)"},
    {"wireframe", "Draw the tubes' triangles as lines (W cycles)"},
    {"hidden", "Do not draw the tubes (W cycles)"},
    {"cloud", "Show the point cloud"},
    {"circles", "Show the fitted circles"},
    {"sampling region of the selected node", "Show the selected node's slab, line cylinder and slice points"},
    {"orthographic", "Orthographic or perspective projection (O)"},
    {"Front", "Look from the front (1)"},
    {"Side", "Look from the side (2)"},
    {"Top", "Look from above (3)"},
    {"Fit", "Frame the whole cloud (F)"},
    {"Help", "Mouse and keys (F1 lists them all)"},
};

}  // namespace

void panelTooltips() {
  ImGuiID hovered = GImGui->HoveredId;
  if (hovered == 0) return;
  for (const Tip& t : kTips) {
    if (ImGui::GetID(t.label) == hovered) {
      ImGui::SetTooltip("%s", t.text);
      return;
    }
  }
}

int panelTooltipCount() { return static_cast<int>(sizeof kTips / sizeof kTips[0]); }

}  // namespace treesketch::gui
