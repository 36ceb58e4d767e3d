#include "treesketch/viewer/recent_files.h"

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "treesketch/util/atomic_file.h"

namespace treesketch::viewer {

namespace fs = std::filesystem;

namespace {
constexpr const char* kMagic = "treesketch-recent 1";
}

const char* toString(RecentKind kind) { return kind == RecentKind::Cloud ? "cloud" : "sketch"; }

fs::path configDirectory() {
  const char* xdg = std::getenv("XDG_CONFIG_HOME");
  if (xdg && *xdg && fs::path(xdg).is_absolute()) return fs::path(xdg) / "treesketch";
  const char* home = std::getenv("HOME");
  if (home && *home) return fs::path(home) / ".config" / "treesketch";
  return {};
}

fs::path recentFilesPath(const fs::path& configDir) {
  return configDir.empty() ? fs::path() : configDir / "recent_files.txt";
}

void RecentFiles::add(RecentKind kind, const fs::path& path) {
  std::error_code ec;
  fs::path abs = fs::absolute(path, ec);
  if (ec) abs = path;
  RecentFile entry{kind, abs.lexically_normal()};
  if (entry.path.string().find_first_of("\r\n") != std::string::npos) return;  // cannot be one line of the file
  remove(entry);
  entries_.insert(entries_.begin(), entry);
  if (entries_.size() > kMaxEntries) entries_.resize(kMaxEntries);
}

void RecentFiles::remove(const RecentFile& entry) {
  entries_.erase(std::remove(entries_.begin(), entries_.end(), entry), entries_.end());
}

std::vector<RecentFile> RecentFiles::entries(RecentKind kind) const {
  std::vector<RecentFile> out;
  for (const RecentFile& e : entries_)
    if (e.kind == kind) out.push_back(e);
  return out;
}

std::string RecentFiles::load(const fs::path& file) {
  entries_.clear();
  std::error_code ec;
  if (file.empty() || !fs::exists(file, ec)) return {};
  std::ifstream in(file, std::ios::binary);
  if (!in) return file.string() + ": cannot read the recent files list; it is ignored";
  return load(in, file.string());
}

std::string RecentFiles::load(std::istream& in, const std::string& source) {
  entries_.clear();
  std::vector<RecentFile> read;
  std::string line;
  std::size_t lineNo = 0;
  auto corrupt = [&](const std::string& what) {
    entries_.clear();
    return source + ":" + std::to_string(lineNo) + ": " + what + "; the recent files list is ignored";
  };
  while (std::getline(in, line)) {
    ++lineNo;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (lineNo == 1) {
      if (line != kMagic) return corrupt("expected the first line '" + std::string(kMagic) + "'");
      continue;
    }
    if (line.empty()) continue;
    std::size_t tab = line.find('\t');
    if (tab == std::string::npos) return corrupt("expected 'cloud' or 'sketch', a tab and a path");
    std::string kind = line.substr(0, tab), path = line.substr(tab + 1);
    if ((kind != "cloud" && kind != "sketch") || path.empty())
      return corrupt("expected 'cloud' or 'sketch', a tab and a path");
    RecentFile e{kind == "cloud" ? RecentKind::Cloud : RecentKind::Sketch, fs::path(path)};
    if (std::find(read.begin(), read.end(), e) == read.end() && read.size() < kMaxEntries) read.push_back(e);
  }
  if (lineNo == 0) return corrupt("the file is empty");
  entries_ = std::move(read);
  return {};
}

void RecentFiles::write(std::ostream& out) const {
  out << kMagic << "\n";
  for (const RecentFile& e : entries_) out << toString(e.kind) << "\t" << e.path.string() << "\n";
}

std::string RecentFiles::save(const fs::path& file) const {
  if (file.empty()) return "no configuration folder ($XDG_CONFIG_HOME and $HOME unset): recent files not saved";
  try {
    std::error_code ec;
    fs::create_directories(file.parent_path(), ec);
    writeFileAtomically(file, [&](std::ostream& out) { write(out); });
  } catch (const std::exception& e) {
    return std::string("recent files not saved: ") + e.what();
  }
  return {};
}

}  // namespace treesketch::viewer
