// Helpers shared by the tests: temporary directories, paths to test data, whole-file text.
// (Running the treesketch executable is in cli/cli_support.h, for the tests in cli/.)
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>

#include "treesketch/geom/cylinder_model.h"

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
/// A model piece from a to b, radii r0 → r1, with its parent row (-1: none) and branch order
/// (-1: not given).
inline geom::ModelCylinder modelPiece(geom::Vec3 a, geom::Vec3 b, double r0, double r1, std::int64_t parent = -1,
                                      std::int32_t order = -1) {
  geom::ModelCylinder c;
  c.start = a;
  c.end = b;
  c.startRadius = r0;
  c.endRadius = r1;
  c.parent = parent;
  c.branchOrder = order;
  return c;
}
/// A random model in the cube [-1, 1]³ of `pieces` pieces 5-40 cm long, radii 1-10 cm: chains of
/// pieces, each starting at its parent's end (a joint: caps open), the radius there kept or
/// stepped, and forks off earlier pieces; about one piece in seven starts a chain of its own.
geom::CylinderModel randomJoinedModel(std::uint64_t seed, int pieces);

}  // namespace treesketch::test
