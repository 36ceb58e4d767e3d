#include "dialogs.h"

#include <imgui.h>

namespace treesketch::gui {

void drawRecoveryDialog(viewer::ViewerState& state) {
  const char* title = "Restore earlier work?##recovery";
  if (state.recoveryPending() && !ImGui::IsPopupOpen(title)) ImGui::OpenPopup(title);
  ImGui::SetNextWindowSize(ImVec2(460, 0));
  if (!ImGui::BeginPopupModal(title, nullptr, ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoMove)) return;
  ImGui::PushTextWrapPos(0.0f);
  ImGui::Text(
      "An earlier session of this cloud ended without saving its sketch (a crash, or the window was "
      "closed). Its autosave is:");
  ImGui::TextDisabled("%s", state.autosavePath().string().c_str());
  if (state.recoveryError().empty())
    ImGui::Text("%zu nodes. It will not be overwritten until you choose.", state.recoveryNodes());
  else
    ImGui::TextColored(ImVec4(1.0f, 0.35f, 0.3f, 1), "It cannot be read: %s", state.recoveryError().c_str());
  ImGui::PopTextWrapPos();
  ImGui::Separator();
  using Choice = viewer::ViewerState::RecoveryChoice;
  ImGui::BeginDisabled(!state.recoveryError().empty());
  if (ImGui::Button("Restore")) state.resolveRecovery(Choice::Restore);
  ImGui::EndDisabled();
  ImGui::SameLine();
  if (ImGui::Button("Discard")) state.resolveRecovery(Choice::Discard);
  ImGui::SameLine();
  if (ImGui::Button("Keep for later")) state.resolveRecovery(Choice::Keep);
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("Renames the file (kept-<date>); load it later with Load sketch");
  if (!state.recoveryPending()) ImGui::CloseCurrentPopup();
  ImGui::EndPopup();
}

void drawConfirmDialog(viewer::ViewerState& state) {
  const char* title = "Replace the sketch?##confirm";
  if (state.confirmationPending() && !ImGui::IsPopupOpen(title)) ImGui::OpenPopup(title);
  ImGui::SetNextWindowSize(ImVec2(420, 0));
  if (!ImGui::BeginPopupModal(title, nullptr, ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoMove)) return;
  ImGui::PushTextWrapPos(0.0f);
  ImGui::TextUnformatted(state.confirmationQuestion().c_str());
  ImGui::PopTextWrapPos();
  ImGui::Separator();
  if (ImGui::Button("Replace")) state.answerConfirmation(true);
  ImGui::SameLine();
  if (ImGui::Button("Keep my sketch") || ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_Escape)))
    state.answerConfirmation(false);
  if (!state.confirmationPending()) ImGui::CloseCurrentPopup();
  ImGui::EndPopup();
}

}  // namespace treesketch::gui
