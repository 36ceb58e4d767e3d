// The menu bar: File, View, Tools, Help. Decision: it is the side panel's own menu bar (the top of
// the window's left column, where File menus sit) rather than a bar across the whole window, so
// the 3D view keeps its size and position — every scripted session's click coordinates stay valid.
#include <imgui.h>

#include "treesketch/viewer/color_legend.h"
#include "treesketch/viewer/view_overlays.h"
#include "window_ui.h"

namespace treesketch::gui {

namespace {
void tip(const char* text) {
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", text);
}
}  // namespace

// The File menu's items (its BeginMenu is open; ends it).
void WindowActions::drawFileMenu() {
  if (ImGui::MenuItem("Open cloud...", "Ctrl+O")) openCloudDialog();
  tip("Open another point cloud (.xyz .txt .csv .pts .asc .las .laz .ply) or a mesh (.obj .ply, scanned first)");
  if (ImGui::MenuItem("Open sketch...")) openSketchDialog();
  tip("Load a sketch file (.json) over this cloud");
  if (ImGui::MenuItem("Save sketch", "Ctrl+S")) save();
  tip("Save the sketch to its file (shown in the Files section)");
  if (ImGui::MenuItem("Save sketch as...", "Ctrl+Shift+S")) saveAsDialog();
  tip("Save the sketch to another file, which becomes its file");
  if (ImGui::MenuItem("Export mesh...", "Ctrl+E")) exportMeshDialog();
  tip("Write the tube mesh as OBJ or PLY");
  using F = viewer::ViewerState::ModelFile;
  if (ImGui::MenuItem("Export cylinder table...")) exportModelDialog(F::Cylinders);
  tip("Write the model's cylinders as treesketch's CSV table (as reconstruct --cylinders)");
  if (ImGui::MenuItem("Export TreeQSM table...")) exportModelDialog(F::Qsm);
  tip("Write the cylinders in TreeQSM's text layout (as reconstruct --qsm)");
  if (ImGui::MenuItem("Export metrics...")) exportModelDialog(F::Metrics);
  tip("Write height, DBH, volumes by branch order, crown and taper as JSON (as reconstruct --metrics)");
  if (ImGui::MenuItem("Export fit report...")) exportModelDialog(F::Report);
  tip("Write how well the model explains the cloud, with its figures, as JSON (as reconstruct --report)");
  ImGui::Separator();
  if (ImGui::BeginMenu("Recent files", !recent_.entries().empty())) {
    for (std::size_t i = 0; i < recent_.entries().size(); ++i) {
      const viewer::RecentFile& e = recent_.entries()[i];
      std::string label = std::string(e.kind == viewer::RecentKind::Cloud ? "cloud   " : "sketch  ") +
                          e.path.filename().string() + "##" + std::to_string(i);
      if (ImGui::MenuItem(label.c_str())) {
        openRecent(i);
        break;
      }
      tip(e.path.string().c_str());
    }
    ImGui::EndMenu();
  }
  tip("Clouds and sketches opened or saved lately (kept in ~/.config/treesketch)");
  ImGui::Separator();
  if (ImGui::MenuItem("Quit", "Ctrl+Q")) requestQuit();
  tip("Close the window (asks first when the sketch has unsaved changes)");
  ImGui::EndMenu();
}

// The View menu's items (its BeginMenu is open; ends it).
void WindowActions::drawViewMenu() {
  viewer::DisplayOptions& d = state_.view().display();
  if (ImGui::BeginMenu("Colour points by")) {
    for (viewer::ColorMode m : viewer::availableColorModes(state_.cloud(), state_.woodClasses() != nullptr))
      if (ImGui::MenuItem(viewer::colorModeLabel(m), nullptr, d.colorMode == m)) state_.view().setColorMode(m);
    ImGui::EndMenu();
  }
  tip("Height, distance to the fitted circles, plain, or the file's intensity / RGB / classification (C cycles)");
  ImGui::MenuItem("Cloud", nullptr, &d.showCloud);
  tip("Show the point cloud");
  ImGui::MenuItem("Node markers", nullptr, &d.showNodes);
  tip("Show the sketch's nodes and links");
  ImGui::MenuItem("Circles", nullptr, &d.showCircles);
  tip("Show the fitted circles");
  ImGui::MenuItem("Sampling region", nullptr, &d.showSamplingRegion);
  tip("Show the selected node's slab, line cylinder and slice points");
  int ms = static_cast<int>(d.meshStyle);
  if (ImGui::BeginMenu("Tubes")) {
    if (ImGui::MenuItem("Solid", nullptr, ms == 0)) d.meshStyle = viewer::MeshStyle::Solid;
    if (ImGui::MenuItem("Wireframe", nullptr, ms == 1)) d.meshStyle = viewer::MeshStyle::Wireframe;
    if (ImGui::MenuItem("Hidden", nullptr, ms == 2)) d.meshStyle = viewer::MeshStyle::Hidden;
    ImGui::EndMenu();
  }
  tip("How the reconstructed tubes are drawn (W cycles)");
  ImGui::MenuItem("Legend", nullptr, &showLegend_);
  tip("The colour scale or classes of the point colouring");
  ImGui::MenuItem("Axis gizmo", nullptr, &showGizmo_);
  tip("The X/Y/Z axes as the camera sees them, bottom left");
  ImGui::MenuItem("Scale bar", nullptr, &showScaleBar_);
  tip("A round length at the centre of rotation's depth, bottom right");
  ImGui::Separator();
  bool ortho = state_.view().orbit().orthographic();
  if (ImGui::MenuItem("Orthographic", "O", ortho)) state_.view().setOrthographic(!ortho);
  tip("Orthographic or perspective projection");
  if (ImGui::MenuItem("Front", "1")) state_.view().presetView(geom::PresetView::Front);
  if (ImGui::MenuItem("Side", "2")) state_.view().presetView(geom::PresetView::Side);
  if (ImGui::MenuItem("Top", "3")) state_.view().presetView(geom::PresetView::Top);
  if (ImGui::MenuItem("Reset camera")) state_.view().presetView(geom::PresetView::Front);
  tip("Back to the start view: from the front, the whole cloud framed (F frames it keeping the direction)");
  if (ImGui::BeginMenu("Up axis")) {
    // The same six directions as the View panel's combo and the lying-down banner.
    const char* ups[] = {"+x", "-x", "+y", "-y", "+z", "-z"};
    for (int i = 0; i < 6; ++i) {
      const auto d = static_cast<viewer::UpDirection>(i);
      if (ImGui::MenuItem(ups[i], nullptr, state_.view().upDirection() == d)) state_.setUpDirection(d);
    }
    ImGui::EndMenu();
  }
  tip("Which world axis points up");
  ImGui::EndMenu();
}

void WindowActions::drawMenuBar() {
  if (!ImGui::BeginMenuBar()) return;
  if (forcedMenu_ == "File") ImGui::OpenPopup("File");  // the same id BeginMenu uses
  if (ImGui::BeginMenu("File")) drawFileMenu();
  if (forcedMenu_ == "View") ImGui::OpenPopup("View");  // the same id BeginMenu uses
  if (ImGui::BeginMenu("View")) drawViewMenu();
  if (forcedMenu_ == "Tools") ImGui::OpenPopup("Tools");  // the same id BeginMenu uses
  if (ImGui::BeginMenu("Tools")) {
    // What a left click or drag in the view does (the keys toggle them; Esc: back to Select).
    using Tool = viewer::ViewerState::Tool;
    static const std::pair<Tool, const char*> kTools[] = {{Tool::Select, "Esc"}, {Tool::AddNodes, "N"},
                                                          {Tool::Stroke, "G"},   {Tool::Lasso, "X"},
                                                          {Tool::LassoWood, "Shift+X"},
                                                          {Tool::Region, "R"},   {Tool::Reattach, "P"}};
    for (const auto& [tool, key] : kTools)
      if (ImGui::MenuItem(viewer::toolLabel(tool), key, state_.tools().tool() == tool)) state_.setTool(tool);
    if (ImGui::MenuItem("Delete subtree of the selected node", "Shift+Del", false,
                        state_.tools().selected() != sketch::kNoNode))
      state_.requestDeleteSubtree(state_.tools().selected());
    ImGui::Separator();
    if (ImGui::MenuItem("Classify wood/leaf", "K", false, !state_.jobs().busy())) state_.startClassifyJob();
    tip("Tell wood from leaves in the background; the fits and strokes then use the wood only");
    ImGui::Separator();
    bool pick = pickMode_;
    if (ImGui::MenuItem("Pick points / measure", "M", pick)) setPickMode(!pick);
    tip("Left clicks pick points (coordinates and the file's attributes); a second pick measures the distance");
    if (ImGui::MenuItem("Clear picks", "Esc", false, picks_.count() > 0)) picks_.clear();
    ImGui::EndMenu();
  }
  if (forcedMenu_ == "Help") ImGui::OpenPopup("Help");  // the same id BeginMenu uses
  if (ImGui::BeginMenu("Help")) {
    if (ImGui::MenuItem("Keys and mouse", "F1", showHelp_)) toggleHelp();
    tip("Every key and mouse gesture");
    if (ImGui::MenuItem("About treesketch")) showAbout_ = true;
    ImGui::EndMenu();
  }
  ImGui::EndMenuBar();
}

}  // namespace treesketch::gui
