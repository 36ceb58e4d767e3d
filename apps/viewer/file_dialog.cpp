#include "file_dialog.h"

#include <imgui.h>
#include <imgui_stdlib.h>

#include <cstdio>

namespace treesketch::gui {

namespace fs = std::filesystem;

void FileDialog::open(Mode mode, const std::string& title, const viewer::FileFilter& filter, const fs::path& folder,
                      const std::string& typed, Accept accept) {
  mode_ = mode;
  title_ = title;
  filter_ = filter;
  allFiles_ = false;
  typed_ = typed;
  accept_ = std::move(accept);
  error_.clear();
  confirmReplace_.clear();
  open_ = true;
  std::error_code ec;
  fs::path start = folder;
  if (start.empty() || !fs::is_directory(start, ec)) start = fs::current_path(ec);
  navigate(start);
}

void FileDialog::cancel() {
  open_ = false;
  accept_ = nullptr;
}

void FileDialog::navigate(const fs::path& folder) {
  listing_ = viewer::listDirectory(folder, allFiles_ ? viewer::allFilesFilter() : filter_, showHidden_);
  folderText_ = listing_.directory.string();
  error_ = listing_.error;
  selected_ = -1;
  confirmReplace_.clear();
}

void FileDialog::refresh() { navigate(listing_.directory); }

void FileDialog::accept() {
  if (!open_) return;
  fs::path p = viewer::resolveTypedPath(listing_.directory, typed_);
  std::error_code ec;
  if (typed_.empty() || fs::is_directory(p, ec)) {
    if (!typed_.empty()) {
      navigate(p);
      if (listing_.ok()) typed_.clear();
    } else {
      error_ = mode_ == Mode::Open ? "choose a file (double click) or type its name" : "type a file name";
    }
    return;
  }
  if (mode_ == Mode::Open) {
    if (!fs::exists(p, ec)) {
      error_ = p.string() + ": no such file";
      return;
    }
  } else {
    p = viewer::pathForSave(listing_.directory, typed_, filter_);
    if (fs::is_directory(p.parent_path(), ec) == false) {
      error_ = p.parent_path().string() + ": no such folder";
      return;
    }
    if (fs::exists(p, ec) && confirmReplace_ != p) {
      confirmReplace_ = p;
      error_ = p.filename().string() + " exists: press Save again to replace it";
      return;
    }
  }
  std::string message = accept_ ? accept_(p) : std::string();
  if (message.empty()) {
    open_ = false;
    accept_ = nullptr;
  } else {
    error_ = message;
  }
}

// The folder's entries, in a child window `listHeight` pixels high: a click chooses, a double click
// enters a folder or accepts a file.
void FileDialog::drawEntries(float listHeight) {
  if (ImGui::BeginChild("##entries", ImVec2(0, listHeight), true)) {
    for (int i = 0; i < static_cast<int>(listing_.entries.size()); ++i) {
      const viewer::FileEntry e = listing_.entries[static_cast<std::size_t>(i)];  // a copy: accept may re-list
      char label[600];
      if (e.directory)
        std::snprintf(label, sizeof label, "[folder] %s", e.name.c_str());
      else
        std::snprintf(label, sizeof label, "%s", e.name.c_str());
      ImGui::PushID(i);
      if (ImGui::Selectable(label, selected_ == i, ImGuiSelectableFlags_AllowDoubleClick)) {
        selected_ = i;
        if (!e.directory) setTyped(e.name);
        if (ImGui::IsMouseDoubleClicked(0)) {
          if (e.directory) {
            navigate(listing_.directory / e.name);
            ImGui::PopID();
            break;
          }
          accept();
          ImGui::PopID();
          break;
        }
      }
      if (!e.directory) {
        ImGui::SameLine(ImGui::GetContentRegionAvail().x - 60);
        ImGui::TextDisabled("%.1f MB", static_cast<double>(e.size) / 1e6);
      }
      ImGui::PopID();
    }
    if (listing_.entries.empty() && listing_.ok()) ImGui::TextDisabled("(no matching files here)");
  }
  ImGui::EndChild();
}

void FileDialog::draw() {
  const char* popupId = "##treesketch_file_dialog";
  if (open_ && !ImGui::IsPopupOpen(popupId)) ImGui::OpenPopup(popupId);
  ImGuiViewport* vp = ImGui::GetMainViewport();
  ImGui::SetNextWindowPos(ImVec2(vp->Pos.x + vp->Size.x * 0.5f, vp->Pos.y + vp->Size.y * 0.5f), ImGuiCond_Always,
                          ImVec2(0.5f, 0.5f));
  ImGui::SetNextWindowSize(ImVec2(640, 460), ImGuiCond_Appearing);
  if (!ImGui::BeginPopupModal(popupId, nullptr, ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_NoTitleBar)) return;
  if (!open_) {
    ImGui::CloseCurrentPopup();
    ImGui::EndPopup();
    return;
  }
  ImGui::TextUnformatted(title_.c_str());
  ImGui::Separator();
  if (ImGui::Button("Up")) navigate(listing_.directory.parent_path());
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("The parent folder");
  ImGui::SameLine();
  ImGui::SetNextItemWidth(-1);
  if (ImGui::InputText("##folder", &folderText_, ImGuiInputTextFlags_EnterReturnsTrue))
    navigate(viewer::resolveTypedPath(listing_.directory, folderText_));
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("The folder shown; type another and press Enter");

  float listHeight = ImGui::GetContentRegionAvail().y - 4 * ImGui::GetFrameHeightWithSpacing();
  drawEntries(listHeight);

  ImGui::SetNextItemWidth(-200);
  bool enter = ImGui::InputText("##typed", &typed_, ImGuiInputTextFlags_EnterReturnsTrue);
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("A file name, or a path relative to the folder shown, absolute, or ~/...; a folder is entered");
  ImGui::SameLine();
  std::string filterLabel = allFiles_ ? viewer::allFilesFilter().label() : filter_.label();
  ImGui::SetNextItemWidth(-1);
  if (ImGui::BeginCombo("##filter", filterLabel.c_str())) {
    if (ImGui::Selectable(filter_.label().c_str(), !allFiles_)) allFiles_ = false, refresh();
    if (ImGui::Selectable(viewer::allFilesFilter().label().c_str(), allFiles_)) allFiles_ = true, refresh();
    ImGui::EndCombo();
  }
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("Which files are listed");
  if (ImGui::Checkbox("hidden files", &showHidden_)) refresh();
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("List files and folders whose name starts with a dot");
  if (!error_.empty()) {
    ImGui::SameLine();
    ImGui::TextColored(ImVec4(1.0f, 0.35f, 0.3f, 1), "%s", error_.c_str());
  }
  if (ImGui::Button(mode_ == Mode::Open ? "Open" : "Save", ImVec2(100, 0)) || enter) accept();
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip(mode_ == Mode::Open ? "Open the typed or chosen file (a folder is entered)"
                                          : "Save to the typed name (the extension is added if missing)");
  ImGui::SameLine();
  if (ImGui::Button("Cancel", ImVec2(100, 0)) || ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_Escape))) cancel();
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("Close without opening or saving");
  if (!open_) ImGui::CloseCurrentPopup();
  ImGui::EndPopup();
}

}  // namespace treesketch::gui
