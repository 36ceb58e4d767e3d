#include "panels.h"

#include <imgui.h>
#include <imgui_stdlib.h>

#include <algorithm>
#include <cstdio>
#include <optional>

#include "tooltips.h"
#include "treesketch/viewer/color_legend.h"
#include "treesketch/viewer/key_bindings.h"

namespace treesketch::gui {

using viewer::NodeStatus;

geom::Viewport Layout::sceneViewport(int width, int height) {
  geom::Viewport vp;
  vp.x = kPanelWidth;
  vp.y = 0;
  vp.width = std::max(1.0, width - static_cast<double>(kPanelWidth));
  vp.height = std::max(1.0, height - static_cast<double>(kStatusHeight));
  return vp;
}

namespace {

ImU32 rgb(const unsigned char c[3], int alpha = 255) { return IM_COL32(c[0], c[1], c[2], alpha); }

/// A logarithmic slider for a world-unit size; returns true when the value changed.
bool sizeSlider(const char* label, double* value, double lo, double hi) {
  float v = static_cast<float>(*value);
  bool changed = ImGui::SliderFloat(label, &v, static_cast<float>(lo), static_cast<float>(hi), "%.4f",
                                    ImGuiSliderFlags_Logarithmic);
  if (changed) *value = v;
  return changed;
}

void samplingControls(viewer::ViewerState& state) {
  const sketch::Sketch& sk = state.sketch();
  bool haveNode = state.tools().selected() != sketch::kNoNode && sk.contains(state.tools().selected());
  sketch::SamplingParams p = haveNode ? sk.node(state.tools().selected()).params : sk.defaults;
  double diag = std::max(state.bounds().diagonal(), 1e-6);
  double slice = p.sliceHalfThickness, line = p.lineEpsilon;
  if (sizeSlider("slice half-thickness", &slice, 1e-4 * diag, 0.1 * diag)) state.setSliceHalfThickness(slice);
  if (ImGui::IsItemDeactivatedAfterEdit()) state.finishEdit();
  if (sizeSlider("lineEpsilon", &line, 1e-3 * diag, 0.5 * diag)) state.setLineEpsilon(line);
  if (ImGui::IsItemDeactivatedAfterEdit()) state.finishEdit();
  if (haveNode) {
    bool enabled = p.enabled;
    if (ImGui::Checkbox("enabled", &enabled)) state.setNodeEnabled(enabled);
  }
}

void selectedNodeSection(viewer::ViewerState& state) {
  const sketch::Sketch& sk = state.sketch();
  sketch::NodeId id = state.tools().selected();
  if (id == sketch::kNoNode || !sk.contains(id)) {
    ImGui::TextDisabled("No node selected: sizes for new nodes");
    samplingControls(state);
    return;
  }
  const sketch::Node& node = sk.node(id);
  viewer::NodeFitView fit = state.scene().nodeFit(id);
  ImGui::Text("Node %d  (parent %d, %zu children)", id, node.parent, node.children.size());
  ImVec4 statusColor = fit.status == NodeStatus::Fitted    ? ImVec4(0.3f, 0.9f, 0.4f, 1)
                       : fit.status == NodeStatus::Skipped ? ImVec4(1.0f, 0.4f, 0.2f, 1)
                                                           : ImVec4(0.8f, 0.8f, 0.8f, 1);
  ImGui::TextColored(statusColor, "%s", viewer::toString(fit.status));
  if (fit.status == NodeStatus::Fitted) {
    ImGui::Text("circle radius %.4f", fit.circle.radius);
    ImGui::Text("centre (%.3f, %.3f, %.3f)", fit.circle.centre.x(), fit.circle.centre.y(), fit.circle.centre.z());
    if (fit.kept) {
      ImGui::TextDisabled("kept from the automatic model (not fitted)");
      if (ImGui::Button("Refit from the cloud")) state.refitSelected();
    } else {
      ImGui::Text("inliers %zu of %zu test points", fit.inliers, fit.testPoints);
      ImGui::Text("lineEpsilon used: %.4f", fit.finalLineEpsilon);
    }
  } else if (fit.status == NodeStatus::Skipped) {
    ImGui::PushTextWrapPos(0.0f);
    ImGui::TextColored(statusColor, "why: %s", fit.reason.c_str());
    ImGui::PopTextWrapPos();
  }
  samplingControls(state);
  if (ImGui::Button("Delete node")) state.deleteSelected(false);
  ImGui::SameLine();
  if (ImGui::Button("Delete subtree")) state.deleteSelected(true);
  ImGui::SameLine();
  if (ImGui::Button("Deselect")) state.selectNode(sketch::kNoNode);
}

void displaySection(viewer::ViewerState& state) {
  viewer::DisplayOptions& d = state.view().display();
  if (ImGui::BeginCombo("colour", viewer::colorModeLabel(d.colorMode))) {
    for (viewer::ColorMode m :
         viewer::availableColorModes(state.cloud(), state.woodClasses() != nullptr))  // the file's attributes too
      if (ImGui::Selectable(viewer::colorModeLabel(m), m == d.colorMode)) d.colorMode = m;
    ImGui::EndCombo();
  }
  ImGui::SliderFloat("point size", &d.pointSize, 1.0f, 8.0f, "%.1f px");
  int ms = static_cast<int>(d.meshStyle);
  ImGui::Text("tubes:");
  ImGui::SameLine();
  ImGui::RadioButton("solid", &ms, 0);
  ImGui::SameLine();
  ImGui::RadioButton("wireframe", &ms, 1);
  ImGui::SameLine();
  ImGui::RadioButton("hidden", &ms, 2);
  d.meshStyle = static_cast<viewer::MeshStyle>(ms);
  ImGui::Checkbox("cloud", &d.showCloud);
  ImGui::SameLine();
  ImGui::Checkbox("nodes##showNodes", &d.showNodes);
  ImGui::SameLine();
  ImGui::Checkbox("circles", &d.showCircles);
  ImGui::Checkbox("sampling region of the selected node", &d.showSamplingRegion);
  const char* labelModes[] = {"auto (up to 100 nodes)", "on", "off"};
  int lm = static_cast<int>(d.labels);
  if (ImGui::Combo("node labels##labels", &lm, labelModes, 3)) d.labels = static_cast<viewer::LabelMode>(lm);
  const char* ups[] = {"+x", "-x", "+y", "-y", "+z", "-z"};
  int up = static_cast<int>(state.view().upDirection());
  if (ImGui::Combo("up axis##upAxis", &up, ups, 6)) state.setUpDirection(static_cast<viewer::UpDirection>(up));
  bool ortho = state.view().orbit().orthographic();
  if (ImGui::Checkbox("orthographic", &ortho)) state.view().setOrthographic(ortho);
  if (ImGui::Button("Front")) state.view().presetView(geom::PresetView::Front);
  ImGui::SameLine();
  if (ImGui::Button("Side")) state.view().presetView(geom::PresetView::Side);
  ImGui::SameLine();
  if (ImGui::Button("Top")) state.view().presetView(geom::PresetView::Top);
  ImGui::SameLine();
  if (ImGui::Button("Fit")) state.view().fitView();
}

void messagesSection(const viewer::ViewerState& state) {
  const auto& msgs = state.status().messages();
  std::size_t first = msgs.size() > 6 ? msgs.size() - 6 : 0;
  ImGui::PushTextWrapPos(0.0f);
  for (std::size_t i = first; i < msgs.size(); ++i) {
    if (msgs[i].error)
      ImGui::TextColored(ImVec4(1.0f, 0.35f, 0.3f, 1), "%s", msgs[i].text.c_str());
    else
      ImGui::TextDisabled("%s", msgs[i].text.c_str());
  }
  ImGui::PopTextWrapPos();
}

// The status bar under the panel and the view: counts, timing, projection, the last message.
void statusBar(viewer::ViewerState& state, int width, int height) {
  ImGui::SetNextWindowPos(ImVec2(0, height - Layout::kStatusHeight));
  ImGui::SetNextWindowSize(ImVec2(static_cast<float>(width), Layout::kStatusHeight));
  ImGui::Begin("status", nullptr,
               ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoTitleBar |
                   ImGuiWindowFlags_NoScrollbar | ImGuiWindowFlags_NoSavedSettings);
  std::optional<viewer::StatusMessage> last = state.status().statusLine();
  ImGui::Text("%zu points | %zu nodes: %zu fitted (%zu kept circles), %zu skipped | last rebuild %.2f ms | %s |",
              state.cloud().size(), state.sketch().size(), state.scene().fittedCount(),
              state.sketch().keptCircleCount(), state.scene().skippedCount(), state.lastRebuildMs(),
              state.view().orbit().orthographic() ? "orthographic" : "perspective");
  // Infos expire (ViewerOptions::statusInfoSeconds); an error stays until dismissed or replaced.
  if (last) {
    ImGui::SameLine();
    if (last->error) {
      if (ImGui::SmallButton("x##dismissStatus")) state.status().dismiss();
      ImGui::SameLine();
      ImGui::TextColored(ImVec4(1.0f, 0.35f, 0.3f, 1), "%s", last->text.c_str());
    } else {
      ImGui::TextUnformatted(last->text.c_str());
    }
  }
  ImGui::End();
}

/// The automatic sketches: the uniform one with its node count, the skeleton with its choice for
/// the leaves (leaf-off; "in leaf": every point, the leafy-scan settings; "wood only": the
/// classified wood with the leaf-off settings).
void automaticSketchRows(viewer::ViewerState& state, PanelState& panel) {
  // "##": the label shows "nodes", the ID is unique (View has a "nodes" checkbox too).
  ImGui::SliderInt("nodes##autoNodes", &panel.autoNodes, 2, 40);
  ImGui::SameLine();
  if (ImGui::Button("Auto")) state.requestAutoSketchUniform(panel.autoNodes);
  if (ImGui::Button("Auto skeleton")) {
    if (panel.autoLeaves == PanelState::kWoodOnly)
      state.requestAutoSketchSkeletonWood();
    else
      state.requestAutoSketchSkeleton(panel.autoLeaves == PanelState::kInLeaf);
  }
  ImGui::SameLine();
  static const char* const kLeaves[] = {"leaf-off", "in leaf", "wood only"};
  ImGui::SetNextItemWidth(82);  // "wood only" and the arrow: Clear and Refit all stay on the row
  ImGui::Combo("##leaves", &panel.autoLeaves, kLeaves, 3);
  ImGui::SameLine();
}

}  // namespace

void drawPanels(viewer::ViewerState& state, PanelState& panel, int width, int height,
                const std::function<void()>& menuBar, const PanelFileActions& files) {
  ImGui::SetNextWindowPos(ImVec2(0, 0));
  ImGui::SetNextWindowSize(ImVec2(Layout::kPanelWidth, height - Layout::kStatusHeight));
  ImGui::Begin("treesketch", nullptr,
               ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse |
                   ImGuiWindowFlags_NoTitleBar | (menuBar ? ImGuiWindowFlags_MenuBar : 0));
  if (menuBar) menuBar();
  ImGui::PushItemWidth(150);
  ImGui::TextUnformatted("treesketch");
  ImGui::TextDisabled("%s", panel.inputName.c_str());
  ImGui::Text("%zu points, %zu nodes", state.cloud().size(), state.sketch().size());

  if (ImGui::CollapsingHeader("Files", ImGuiTreeNodeFlags_DefaultOpen)) {
    // The File menu's own actions (with their dialogs and overwrite questions): one way to save.
    const std::string& file = state.document().sketchPath().string();
    ImGui::TextDisabled("sketch file: %s", file.empty() ? "(none yet)" : file.c_str());
    auto fileButton = [&](const char* label, const std::function<void()>& action) {
      if ((ImGui::Button(label) || panel.press == label) && action) action();
    };
    fileButton("Open sketch...", files.openSketch);
    ImGui::SameLine();
    fileButton("Save sketch", files.save);
    ImGui::SameLine();
    fileButton("Save as...", files.saveAs);
    fileButton("Export mesh...", files.exportMesh);
    ImGui::InputText("png", &panel.screenshotPath);
    if (ImGui::Button("Screenshot")) panel.screenshotRequested = true;
  }
  if (ImGui::CollapsingHeader("Sketch", ImGuiTreeNodeFlags_DefaultOpen)) {
    automaticSketchRows(state, panel);
    if (ImGui::Button("Clear")) state.clearSketch();
    if (state.sketch().keptCircleCount() > 0) {
      ImGui::SameLine();
      if (ImGui::Button("Refit all")) state.refitAll();
    }
    ImGui::BeginDisabled(!state.canUndo());
    if (ImGui::Button("Undo")) state.undo();
    ImGui::EndDisabled();
    ImGui::SameLine();
    ImGui::BeginDisabled(!state.canRedo());
    if (ImGui::Button("Redo")) state.redo();
    ImGui::EndDisabled();
    if (state.canUndo()) {
      ImGui::SameLine();
      ImGui::TextDisabled("(%s)", state.history().undoLabel().c_str());
    }
  }
  if (ImGui::CollapsingHeader("Node", ImGuiTreeNodeFlags_DefaultOpen)) {
    // The section keeps one height whether a node is selected or not, so that selecting a node
    // never moves the controls below it (a click meant for one would hit another).
    const float top = ImGui::GetCursorPosY();
    selectedNodeSection(state);
    const float used = ImGui::GetCursorPosY() - top;
    const float keep = Layout::kNodeSectionRows * ImGui::GetFrameHeightWithSpacing();
    if (used < keep) ImGui::Dummy(ImVec2(1.0f, keep - used - ImGui::GetStyle().ItemSpacing.y));
  }
  if (ImGui::CollapsingHeader("Correction tools", ImGuiTreeNodeFlags_DefaultOpen)) toolsSection(state);
  if (ImGui::CollapsingHeader("View", ImGuiTreeNodeFlags_DefaultOpen)) displaySection(state);
  if (ImGui::CollapsingHeader("Help", panel.showHelp ? ImGuiTreeNodeFlags_DefaultOpen : 0)) {
    ImGui::PushTextWrapPos(0.0f);
    for (const viewer::KeyBinding& k : viewer::keyBindings())  // the README's table, from one source
      ImGui::TextDisabled("%s: %s", k.keys.c_str(), k.action.c_str());
    ImGui::PopTextWrapPos();
  }
  ImGui::Separator();
  messagesSection(state);
  panelTooltips();
  ImGui::PopItemWidth();
  ImGui::End();
  panel.press.clear();

  statusBar(state, width, height);
}

void drawMarkers(const viewer::ViewerState& state) {
  if (!state.view().display().showNodes) return;
  ImDrawList* dl = ImGui::GetBackgroundDrawList();
  geom::Viewport vp = state.view().orbit().viewport();
  dl->PushClipRect(ImVec2(static_cast<float>(vp.x), static_cast<float>(vp.y)),
                   ImVec2(static_cast<float>(vp.x + vp.width), static_cast<float>(vp.y + vp.height)));
  std::vector<viewer::NodeMarker> markers = state.scene().nodeMarkers();
  const bool labels = state.scene().labelsShown();
  auto find = [&](sketch::NodeId id) -> const viewer::NodeMarker* {
    for (const auto& m : markers)
      if (m.id == id) return &m;
    return nullptr;
  };
  for (const auto& m : markers) {
    const viewer::NodeMarker* p = m.parent == sketch::kNoNode ? nullptr : find(m.parent);
    if (!p || !m.visible || !p->visible) continue;
    const ImU32 colour = m.doomed ? IM_COL32(255, 70, 60, 240) : IM_COL32(255, 235, 120, 220);
    const ImVec2 a(float(p->screen.x()), float(p->screen.y())), b(float(m.screen.x()), float(m.screen.y()));
    dl->AddLine(a, b, colour, m.doomed ? 3.0f : 2.0f);
    // The edge's direction, parent to child: an arrowhead at its middle (edges shorter than the
    // markers have none).
    const float dx = b.x - a.x, dy = b.y - a.y, len = std::sqrt(dx * dx + dy * dy);
    if (len < 24.0f) continue;
    const float ux = dx / len, uy = dy / len, mx = a.x + 0.5f * dx + 4.0f * ux, my = a.y + 0.5f * dy + 4.0f * uy;
    dl->AddTriangleFilled(ImVec2(mx, my), ImVec2(mx - 8.0f * ux - 4.5f * uy, my - 8.0f * uy + 4.5f * ux),
                          ImVec2(mx - 8.0f * ux + 4.5f * uy, my - 8.0f * uy - 4.5f * ux), colour);
  }
  for (const auto& m : markers) {
    if (!m.visible) continue;
    ImVec2 c(float(m.screen.x()), float(m.screen.y()));
    const unsigned char* fill = m.status == NodeStatus::Fitted    ? kMarkerFitted
                                : m.status == NodeStatus::Skipped ? kMarkerSkipped
                                                                  : kMarkerPending;
    if (m.inCurrentView) {
      dl->AddCircleFilled(c, 6.0f, rgb(fill), 20);
    } else {
      dl->AddCircle(c, 6.0f, rgb(fill), 20, 2.5f);  // drawn under another view
    }
    dl->AddCircle(c, 7.0f, IM_COL32(20, 20, 20, 255), 20, 1.5f);
    if (m.doomed) {  // a Delete subtree waiting for its answer removes this node
      dl->AddCircleFilled(c, 6.0f, IM_COL32(230, 40, 30, 255), 20);
      dl->AddLine(ImVec2(c.x - 6, c.y - 6), ImVec2(c.x + 6, c.y + 6), IM_COL32(255, 255, 255, 255), 2.0f);
      dl->AddLine(ImVec2(c.x - 6, c.y + 6), ImVec2(c.x + 6, c.y - 6), IM_COL32(255, 255, 255, 255), 2.0f);
    }
    if (m.active) dl->AddCircle(c, 10.5f, IM_COL32(255, 230, 0, 255), 24, 2.0f);
    if (m.selected) dl->AddCircle(c, 14.0f, IM_COL32(255, 255, 255, 255), 24, 2.0f);
    if (!labels) continue;
    char label[16];
    std::snprintf(label, sizeof label, "%d", m.id);
    dl->AddText(ImVec2(c.x + 9, c.y - 18), IM_COL32(255, 255, 255, 230), label);
  }
  dl->PopClipRect();
}

void drawToolOverlay(const viewer::ViewerState& state) {
  ImDrawList* dl = ImGui::GetForegroundDrawList();
  const geom::Viewport vp = state.view().orbit().viewport();
  dl->PushClipRect(ImVec2(float(vp.x), float(vp.y)), ImVec2(float(vp.x + vp.width), float(vp.y + vp.height)));
  // The path of the drag being drawn (stroke, lasso, region), closed for the polygon tools.
  const std::vector<geom::Vec2>& path = state.tools().toolPath();
  if (path.size() >= 2) {
    using Tool = viewer::ViewerState::Tool;
    std::vector<ImVec2> pts;
    pts.reserve(path.size());
    for (const geom::Vec2& p : path) pts.emplace_back(float(p.x()), float(p.y()));
    const bool closed = state.tools().tool() == Tool::Lasso || state.tools().tool() == Tool::LassoWood ||
                        state.tools().tool() == Tool::Region;
    const ImU32 colour = state.tools().tool() == Tool::Lasso       ? IM_COL32(255, 90, 200, 255)
                         : state.tools().tool() == Tool::LassoWood ? IM_COL32(200, 140, 70, 255)
                                                                   : IM_COL32(90, 220, 255, 255);
    dl->AddPolyline(pts.data(), static_cast<int>(pts.size()), colour, closed ? ImDrawFlags_Closed : 0, 2.0f);
  }
  // The active tool, always on the canvas (the panel's buttons may be scrolled away).
  char text[96];
  std::snprintf(text, sizeof text, "tool: %s", viewer::toolLabel(state.tools().tool()));
  const ImVec2 size = ImGui::CalcTextSize(text);
  const ImVec2 at(float(vp.x) + 0.5f * (float(vp.width) - size.x), float(vp.y + vp.height) - size.y - 10.0f);
  dl->AddRectFilled(ImVec2(at.x - 4, at.y - 2), ImVec2(at.x + size.x + 4, at.y + size.y + 2), IM_COL32(0, 0, 0, 150), 3.0f);
  dl->AddText(at, IM_COL32(255, 255, 255, 240), text);
  dl->PopClipRect();
}

}  // namespace treesketch::gui
