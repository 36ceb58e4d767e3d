#include "treesketch/viewer/file_browser.h"

#include <algorithm>
#include <cstdlib>

#include "treesketch/util/text.h"

namespace treesketch::viewer {

namespace fs = std::filesystem;

bool FileFilter::matches(const fs::path& path) const {
  if (extensions.empty()) return true;
  std::string ext = lowercase(path.extension().string());
  return std::find(extensions.begin(), extensions.end(), ext) != extensions.end();
}

std::string FileFilter::label() const {
  std::string s = name + " (";
  if (extensions.empty()) s += "*";
  for (std::size_t i = 0; i < extensions.size(); ++i) s += (i ? " *" : "*") + extensions[i];
  return s + ")";
}

FileFilter cloudFileFilter() {
  return {"Point clouds and meshes", {".xyz", ".txt", ".csv", ".pts", ".asc", ".las", ".laz", ".ply", ".obj"}};
}
FileFilter sketchFileFilter() { return {"Sketches", {".json"}}; }
FileFilter meshFileFilter() { return {"Meshes", {".obj", ".ply"}}; }
FileFilter allFilesFilter() { return {"All files", {}}; }

DirectoryListing listDirectory(const fs::path& directory, const FileFilter& filter, bool showHidden) {
  DirectoryListing out;
  std::error_code ec;
  fs::path abs = fs::absolute(directory, ec);
  out.directory = (ec ? directory : abs).lexically_normal();
  if (out.directory.has_relative_path() && out.directory.filename().empty())
    out.directory = out.directory.parent_path();  // "/a/b/" -> "/a/b"
  if (!fs::is_directory(out.directory, ec)) {
    out.error = out.directory.string() + ": " + (fs::exists(out.directory, ec) ? "not a folder" : "no such folder");
    return out;
  }
  std::vector<FileEntry> dirs, files;
  fs::directory_iterator it(out.directory, fs::directory_options::skip_permission_denied, ec);
  if (ec) {
    out.error = out.directory.string() + ": cannot read the folder (" + ec.message() + ")";
    return out;
  }
  for (; it != fs::directory_iterator(); it.increment(ec)) {
    if (ec) break;
    std::string name = it->path().filename().string();
    if (!showHidden && !name.empty() && name[0] == '.') continue;
    std::error_code e2;
    if (it->is_directory(e2)) {
      dirs.push_back({name, true, 0});
    } else if (!e2 && it->is_regular_file(e2) && filter.matches(it->path())) {
      std::uintmax_t size = it->file_size(e2);
      files.push_back({name, false, e2 ? 0 : size});
    }
  }
  if (ec) out.error = out.directory.string() + ": listing stopped (" + ec.message() + ")";
  auto byName = [](const FileEntry& a, const FileEntry& b) {
    std::string la = lowercase(a.name), lb = lowercase(b.name);
    return la != lb ? la < lb : a.name < b.name;
  };
  std::sort(dirs.begin(), dirs.end(), byName);
  std::sort(files.begin(), files.end(), byName);
  if (out.directory.has_relative_path()) out.entries.push_back({"..", true, 0});
  out.entries.insert(out.entries.end(), dirs.begin(), dirs.end());
  out.entries.insert(out.entries.end(), files.begin(), files.end());
  return out;
}

namespace {
std::string trim(const std::string& s) {
  std::size_t b = s.find_first_not_of(" \t\r\n"), e = s.find_last_not_of(" \t\r\n");
  return b == std::string::npos ? std::string() : s.substr(b, e - b + 1);
}
}  // namespace

fs::path resolveTypedPath(const fs::path& current, const std::string& typed) {
  std::string t = trim(typed);
  if (t.empty()) return current.lexically_normal();
  if (t == "~" || t.rfind("~/", 0) == 0) {
    const char* home = std::getenv("HOME");
    if (home && *home) t = std::string(home) + t.substr(1);
  }
  fs::path p(t);
  if (p.is_relative()) p = current / p;
  p = p.lexically_normal();
  if (p.has_relative_path() && p.filename().empty()) p = p.parent_path();
  return p;
}

fs::path pathForSave(const fs::path& current, const std::string& typed, const FileFilter& filter) {
  fs::path p = resolveTypedPath(current, typed);
  if (!p.has_extension() && !filter.extensions.empty()) p += filter.extensions.front();
  return p;
}

}  // namespace treesketch::viewer
