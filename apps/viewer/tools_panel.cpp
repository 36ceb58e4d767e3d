// The "Correction tools" section of the side panel: the tool buttons (same as the
// keys G, X, Shift+X, R, P, H), the lassos, the wood/leaf classification (K), and the selected
// node's depth along the view ray.
// Kept in its own file so the panel layout (panels.cpp) only calls it.
#include <imgui.h>

#include <cmath>

#include "panels.h"

namespace treesketch::gui {

void toolsSection(viewer::ViewerState& state) {
  using Tool = viewer::ViewerState::Tool;
  // Tooltips: tooltips.cpp's table, like every panel control.
  auto toolButton = [&](const char* label, Tool tool) {
    const bool on = state.tools().tool() == tool;
    if (on) ImGui::PushStyleColor(ImGuiCol_Button, ImVec4(0.2f, 0.5f, 0.3f, 1));
    if (ImGui::Button(label)) state.setTool(on ? Tool::Select : tool);
    if (on) ImGui::PopStyleColor();
  };
  toolButton("Add nodes (N)", Tool::AddNodes);
  ImGui::SameLine();
  toolButton("Stroke (G)", Tool::Stroke);
  ImGui::SameLine();
  toolButton("Lasso (X)", Tool::Lasso);
  toolButton("Wood lasso (Shift+X)", Tool::LassoWood);
  ImGui::SameLine();
  toolButton("Region (R)", Tool::Region);
  toolButton("Re-attach (P)", Tool::Reattach);
  ImGui::BeginDisabled(state.tools().selected() == sketch::kNoNode);
  if (ImGui::Button("Automatic below selected (H)")) state.automaticBelow(state.tools().selected());
  ImGui::EndDisabled();
  const std::size_t woodLassos = state.sketch().woodLassoCount();
  ImGui::Text("%zu not-wood, %zu wood lasso(s)", state.sketch().notWood().size() - woodLassos, woodLassos);
  ImGui::SameLine();
  ImGui::BeginDisabled(state.sketch().notWood().empty());
  if (ImGui::Button("Clear##notWood")) state.clearNotWood();
  ImGui::EndDisabled();
  ImGui::BeginDisabled(state.jobs().busy());
  if (ImGui::Button("Classify wood/leaf (K)")) state.startClassifyJob();
  ImGui::EndDisabled();
  ImGui::SameLine();
  if (state.woodClasses())
    ImGui::Text("%zu of %zu points wood", state.woodPointCount(), state.cloud().size());
  else
    ImGui::TextDisabled("not classified");
  const double depth = state.selectedDepth();
  if (std::isfinite(depth)) ImGui::Text("selected circle: %.3f from the eye", depth);
  if (state.tools().selected() != sketch::kNoNode) {
    const viewer::NodeFitView fit = state.scene().nodeFit(state.tools().selected());
    if (std::isfinite(fit.depth)) ImGui::Text("depth along its view ray: %.3f", fit.depth);
    if (!fit.warning.empty()) {
      ImGui::PushTextWrapPos(0.0f);
      if (fit.depthJump)
        ImGui::TextColored(ImVec4(1.0f, 0.6f, 0.2f, 1), "depth: %s", fit.warning.c_str());
      else
        ImGui::TextDisabled("depth: %s", fit.warning.c_str());
      ImGui::PopTextWrapPos();
    }
  }
}

}  // namespace treesketch::gui
