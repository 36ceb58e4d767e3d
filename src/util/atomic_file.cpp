#include "treesketch/util/atomic_file.h"

#include <unistd.h>

#include <atomic>
#include <fstream>
#include <string>

#include "treesketch/util/error.h"

namespace treesketch {

namespace fs = std::filesystem;

namespace {
std::atomic<bool> gCreateDirectories{false};
}  // namespace

void setCreateOutputDirectories(bool create) { gCreateDirectories.store(create); }

void writeFileAtomically(const fs::path& path, const std::function<void(std::ostream&)>& write, bool binary) {
  static std::atomic<unsigned> counter{0};
  fs::path dir = path.parent_path().empty() ? fs::path(".") : path.parent_path();
  std::error_code made;
  if (!fs::is_directory(dir) && gCreateDirectories.load()) fs::create_directories(dir, made);
  if (!fs::is_directory(dir)) {
    std::string why = path.string() + ": directory '" + dir.string() + "' does not exist";
    if (gCreateDirectories.load()) why += " and cannot be created";
    if (made) why += " (" + made.message() + ")";
    throw OutputError(why);
  }
  std::string name = ".";  // built step by step: GCC 12 warns (-Wrestrict, falsely) on one long sum
  name += path.filename().string();
  name += ".tmp";
  name += std::to_string(::getpid());
  name += '_';
  name += std::to_string(counter.fetch_add(1));
  const fs::path tmp = dir / name;
  try {
    {
      std::ofstream out(tmp, binary ? std::ios::binary | std::ios::out : std::ios::out);
      if (!out) throw OutputError(path.string() + ": cannot create temporary file '" + tmp.string() + "'");
      write(out);
      out.flush();
      if (!out) throw OutputError(path.string() + ": write failed (disk full or I/O error)");
    }
    std::error_code ec;
    fs::rename(tmp, path, ec);
    if (ec) throw OutputError(path.string() + ": cannot rename temporary file: " + ec.message());
  } catch (...) {
    std::error_code ignored;
    fs::remove(tmp, ignored);
    throw;
  }
}

void checkNotAnInput(const fs::path& output, std::initializer_list<fs::path> inputs) {
  std::error_code ec;
  if (!fs::exists(output, ec)) return;
  for (const auto& in : inputs) {
    if (fs::exists(in, ec) && fs::equivalent(output, in, ec)) {
      throw OutputError(output.string() + ": refusing to overwrite an input file");
    }
  }
}

}  // namespace treesketch
