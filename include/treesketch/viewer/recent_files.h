// The desktop tool's recent files: the clouds and sketches opened or saved lately, newest first,
// kept in a small text file in the user's configuration folder so the File menu lists them in the
// next session as well. Plain C++, no GL. A missing file is an empty list; a corrupt one is ignored
// with a message (the tool never fails to start because of it).
#pragma once

#include <cstddef>
#include <filesystem>
#include <istream>
#include <ostream>
#include <string>
#include <vector>

namespace treesketch::viewer {

enum class RecentKind { Cloud, Sketch };
const char* toString(RecentKind kind);

struct RecentFile {
  RecentKind kind = RecentKind::Cloud;
  std::filesystem::path path;  ///< absolute
  bool operator==(const RecentFile& o) const { return kind == o.kind && path == o.path; }
};

/// The configuration folder: $XDG_CONFIG_HOME/treesketch, else $HOME/.config/treesketch (the XDG
/// base directory rule); empty when neither variable is set (then nothing is remembered).
std::filesystem::path configDirectory();

class RecentFiles {
 public:
  /// Entries kept (design choice: 10, as most editors' File menus).
  static constexpr std::size_t kMaxEntries = 10;

  /// Puts `path` (made absolute) first, removing an older entry of the same kind and path and the
  /// oldest beyond kMaxEntries.
  void add(RecentKind kind, const std::filesystem::path& path);
  /// Removes an entry (a file that is gone, say).
  void remove(const RecentFile& entry);
  /// Newest first.
  const std::vector<RecentFile>& entries() const { return entries_; }
  /// Entries of one kind, newest first.
  std::vector<RecentFile> entries(RecentKind kind) const;

  /// Reads the list: first line "treesketch-recent 1", then one "cloud|sketch<TAB>PATH" a line.
  /// Returns "" on success or for a missing file (empty list), else a one-line message naming the
  /// file and line; the list is then left empty (a corrupt file is ignored, never fatal).
  std::string load(const std::filesystem::path& file);
  std::string load(std::istream& in, const std::string& source);
  /// Writes the list atomically, creating the folder. Returns "" or a one-line message.
  std::string save(const std::filesystem::path& file) const;
  void write(std::ostream& out) const;

 private:
  std::vector<RecentFile> entries_;
};

/// The recent-files file inside `configDir` ("recent_files.txt"); empty when configDir is.
std::filesystem::path recentFilesPath(const std::filesystem::path& configDir);

}  // namespace treesketch::viewer
