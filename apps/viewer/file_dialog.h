// The open/save file dialog, made with Dear ImGui (no other dependency): a folder's entries
// (folders first, then the files the filter matches, from viewer::listDirectory), a filter choice
// (the dialog's own or all files), a typed path (relative to the folder shown, or absolute, or
// "~/..."), and a red line for whatever went wrong (a folder that cannot be read, a file that is
// not there, an open that failed): errors are shown, never fatal. The logic — navigate, accept,
// cancel — is in plain methods so a --script session can drive it exactly as a click does.
#pragma once

#include <filesystem>
#include <functional>
#include <string>

#include "treesketch/viewer/file_browser.h"

namespace treesketch::gui {

class FileDialog {
 public:
  enum class Mode { Open, Save };
  /// Called with the chosen file; returns "" when done (the dialog closes) or a message (shown in
  /// the dialog, which stays open).
  using Accept = std::function<std::string(const std::filesystem::path&)>;

  /// Opens the dialog titled `title` in `folder` (the current folder when empty or missing), with
  /// `typed` in the path box (a save dialog's suggested name).
  void open(Mode mode, const std::string& title, const viewer::FileFilter& filter, const std::filesystem::path& folder,
            const std::string& typed, Accept accept);
  bool isOpen() const { return open_; }
  void cancel();
  /// Shows `folder` (an error line when it cannot be read; the listing is then empty).
  void navigate(const std::filesystem::path& folder);
  /// What the Open/Save button does with the typed path: a folder is entered; a file is handed to
  /// the accept callback (for Open it must exist; for Save the filter's extension is added when
  /// there is none, and an existing file is replaced only after a second press).
  void accept();
  void setTyped(const std::string& typed) {
    typed_ = typed;
    confirmReplace_.clear();
  }

  const viewer::DirectoryListing& listing() const { return listing_; }
  const std::string& error() const { return error_; }

  /// Draws the dialog (a modal window) for this frame when it is open.
  void draw();

 private:
  void drawEntries(float listHeight);
  void refresh();

  bool open_ = false;
  bool popupShown_ = false;
  Mode mode_ = Mode::Open;
  std::string title_;
  viewer::FileFilter filter_;
  bool allFiles_ = false;
  bool showHidden_ = false;
  std::string typed_;
  std::string folderText_;
  std::string error_;
  std::filesystem::path confirmReplace_;
  viewer::DirectoryListing listing_;
  Accept accept_;
  int selected_ = -1;
};

}  // namespace treesketch::gui
