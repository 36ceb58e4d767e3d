// What the desktop tool's open/save dialogs show, in plain C++ (no GL): a folder's entries
// (folders first, then files matching the dialog's extensions, each sorted by name), and how a
// typed path is understood. The dialog itself (apps/viewer/file_dialog.cpp) only draws this.
// Nothing here throws for a folder that cannot be read: the listing carries the message.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace treesketch::viewer {

/// Which files a dialog lists: a name and lower-case extensions with the dot (".las").
struct FileFilter {
  std::string name;
  std::vector<std::string> extensions;  ///< empty: every file
  /// True when `path`'s extension (case-insensitive) is one of `extensions`, or there are none.
  bool matches(const std::filesystem::path& path) const;
  /// "Point clouds (*.xyz *.txt ...)".
  std::string label() const;
};

/// The dialogs' filters: what `treesketch-gui` opens as a cloud (clouds and meshes, which are
/// scanned: .xyz .txt .csv .pts .asc .las .laz .ply .obj), sketches (.json) and exported meshes
/// (.obj .ply).
FileFilter cloudFileFilter();
FileFilter sketchFileFilter();
FileFilter meshFileFilter();
FileFilter allFilesFilter();

struct FileEntry {
  std::string name;  ///< file name only
  bool directory = false;
  std::uintmax_t size = 0;  ///< bytes (files)
};

struct DirectoryListing {
  std::filesystem::path directory;  ///< absolute, normalised
  std::vector<FileEntry> entries;   ///< folders first ("..", when there is a parent, leads), then files
  std::string error;                ///< non-empty when the folder could not be read
  bool ok() const { return error.empty(); }
};

/// Lists `directory`: sub-folders and the files `filter` matches, each group sorted by name
/// (case-insensitive); hidden entries (".name") only when `showHidden`. Entries that cannot be
/// inspected (a broken link) are skipped. A missing or unreadable folder gives an empty listing
/// with `error` set.
DirectoryListing listDirectory(const std::filesystem::path& directory, const FileFilter& filter,
                               bool showHidden = false);

/// The path a typed text means, seen from the dialog's `current` folder: "~" and "~/x" are the
/// home folder, a relative path is relative to `current`; the result is normalised (no "." or
/// ".." parts). Empty text gives `current`.
std::filesystem::path resolveTypedPath(const std::filesystem::path& current, const std::string& typed);

/// The path a save dialog writes for `typed` (resolved as above): when it has no extension the
/// filter's first one is added ("tree" -> "tree.json").
std::filesystem::path pathForSave(const std::filesystem::path& current, const std::string& typed,
                                  const FileFilter& filter);

}  // namespace treesketch::viewer
