// Helpers shared by the tests: temporary directories, paths to test data, whole-file text.
// (Running the treesketch executable is in cli/cli_support.h, for the tests in cli/.)
#pragma once

#include <filesystem>
#include <string>

namespace treesketch::test {

/// A fresh empty directory under the system temp dir, removed when the object dies.
class TempDir {
 public:
  TempDir();
  ~TempDir();
  const std::filesystem::path& path() const { return path_; }
  std::filesystem::path operator/(const std::string& name) const { return path_ / name; }

 private:
  std::filesystem::path path_;
};

/// ../shared/data (third-party data; may be absent: tests using it call GTEST_SKIP then).
std::filesystem::path sharedDataDir();
/// Writes `text` to `path` (binary, exact bytes).
void writeText(const std::filesystem::path& path, const std::string& text);
/// Reads a whole file.
std::string readText(const std::filesystem::path& path);
}  // namespace treesketch::test
