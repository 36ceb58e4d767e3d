#include "dialogs.h"

#include <imgui.h>

#include <algorithm>
#include <cstdio>
#include <string>

namespace treesketch::gui {

void drawRecoveryDialog(viewer::ViewerState& state) {
  const char* title = "Restore earlier work?##recovery";
  if (state.document().recoveryPending() && !ImGui::IsPopupOpen(title)) ImGui::OpenPopup(title);
  ImGui::SetNextWindowSize(ImVec2(460, 0));
  if (!ImGui::BeginPopupModal(title, nullptr, ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoMove)) return;
  ImGui::PushTextWrapPos(0.0f);
  ImGui::Text(
      "An earlier session of this cloud ended without saving its sketch (a crash, or the window was "
      "closed). Its autosave is:");
  ImGui::TextDisabled("%s", state.document().autosavePath().string().c_str());
  if (state.document().recoveryError().empty())
    ImGui::Text("%zu nodes. It will not be overwritten until you choose.", state.document().recoveryNodes());
  else
    ImGui::TextColored(ImVec4(1.0f, 0.35f, 0.3f, 1), "It cannot be read: %s", state.document().recoveryError().c_str());
  ImGui::PopTextWrapPos();
  ImGui::Separator();
  using Choice = viewer::ViewerState::RecoveryChoice;
  ImGui::BeginDisabled(!state.document().recoveryError().empty());
  if (ImGui::Button("Restore")) state.resolveRecovery(Choice::Restore);
  ImGui::EndDisabled();
  ImGui::SameLine();
  if (ImGui::Button("Discard")) state.resolveRecovery(Choice::Discard);
  ImGui::SameLine();
  if (ImGui::Button("Keep for later")) state.resolveRecovery(Choice::Keep);
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("Renames the file (kept-<date>); load it later with Load sketch");
  if (!state.document().recoveryPending()) ImGui::CloseCurrentPopup();
  ImGui::EndPopup();
}

void drawUpWarning(viewer::ViewerState& state) {
  if (!state.upWarningShown()) return;
  const geom::Viewport vp = state.view().orbit().viewport();
  ImGui::SetNextWindowPos(ImVec2(float(vp.x + 10), float(vp.y + 10)));
  ImGui::SetNextWindowSize(ImVec2(float(std::min(vp.width - 20, 620.0)), 0));
  ImGui::SetNextWindowBgAlpha(0.85f);
  ImGui::Begin("##upWarning", nullptr,
               ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_NoFocusOnAppearing |
                   ImGuiWindowFlags_NoMove);
  ImGui::PushTextWrapPos(0.0f);
  ImGui::TextColored(ImVec4(1.0f, 0.8f, 0.3f, 1), "%s", state.lyingDownWarning().c_str());
  ImGui::PopTextWrapPos();
  ImGui::TextUnformatted("Up axis:");
  const viewer::UpDirection all[] = {viewer::UpDirection::PosX, viewer::UpDirection::NegX, viewer::UpDirection::PosY,
                                     viewer::UpDirection::NegY, viewer::UpDirection::PosZ, viewer::UpDirection::NegZ};
  for (viewer::UpDirection d : all) {
    ImGui::SameLine();
    std::string label = std::string(viewer::toString(d)) + "##upWarning";
    if (ImGui::Button(label.c_str())) state.setUpDirection(d);
  }
  ImGui::SameLine();
  if (ImGui::Button("Dismiss##upWarning")) state.view().dismissUpWarning();
  ImGui::End();
}

void drawJobProgress(viewer::ViewerState& state) {
  if (!state.jobs().busy()) return;
  viewer::JobProgress p = state.jobs().progress();
  const geom::Viewport vp = state.view().orbit().viewport();
  ImGui::SetNextWindowPos(ImVec2(float(vp.x + vp.width * 0.5), float(vp.y + vp.height - 100)), 0, ImVec2(0.5f, 1.0f));
  ImGui::SetNextWindowSize(ImVec2(440, 0));
  // NoFocusOnAppearing: the job may start while a modal question is open (a script, or a key);
  // Dear ImGui 1.86 asserts when a window that takes the focus appears under an open modal.
  ImGui::Begin("Working##job", nullptr,
               ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoCollapse |
                   ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_NoFocusOnAppearing);
  ImGui::TextUnformatted(p.what.c_str());
  char overlay[32];
  std::snprintf(overlay, sizeof overlay, "step %d of %d", p.step, p.steps);
  ImGui::ProgressBar(static_cast<float>(p.fraction), ImVec2(-1, 0), overlay);
  ImGui::BeginDisabled(p.cancelling);
  if (ImGui::Button("Cancel##job")) state.jobs().cancel();
  ImGui::EndDisabled();
  ImGui::SameLine();
  ImGui::TextDisabled("the view still moves; edits wait");
  ImGui::End();
}

void drawConfirmDialog(viewer::ViewerState& state) {
  // One dialog for every question the state asks (replace hand edits, load another cloud's
  // sketch, replace another file, delete a subtree): the question says what yes does.
  const char* title = "Are you sure?##confirm";
  if (state.confirmationPending() && !ImGui::IsPopupOpen(title)) ImGui::OpenPopup(title);
  ImGui::SetNextWindowSize(ImVec2(420, 0));
  // In the view's corner, so that what the question is about (the nodes a Delete subtree would
  // remove, drawn in red) stays in sight.
  const geom::Viewport vp = state.view().orbit().viewport();
  ImGui::SetNextWindowPos(ImVec2(float(vp.x + 10), float(vp.y + 10)));
  if (!ImGui::BeginPopupModal(title, nullptr, ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoMove)) return;
  ImGui::PushTextWrapPos(0.0f);
  ImGui::TextUnformatted(state.confirmationQuestion().c_str());
  ImGui::PopTextWrapPos();
  ImGui::Separator();
  if (ImGui::Button("Yes")) state.answerConfirmation(true);
  ImGui::SameLine();
  if (ImGui::Button("No") || ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_Escape)))
    state.answerConfirmation(false);
  if (!state.confirmationPending()) ImGui::CloseCurrentPopup();
  ImGui::EndPopup();
}

}  // namespace treesketch::gui
