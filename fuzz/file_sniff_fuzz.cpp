// Fuzz harness: the format dispatch by file name — io::inspectFile (`treesketch info`),
// io::readPointCloud and io::readMesh on a path. The first input byte picks the file name's
// extension (known, upper-case, compressed, unknown, none), the rest is the file. Contract
// checked: bad input throws InputError and nothing else; what is accepted is a valid cloud/mesh.
#include <array>

#include "fuzz_support.h"
#include "treesketch/io/file_info.h"
#include "treesketch/io/mesh_io.h"
#include "treesketch/io/point_cloud_io.h"
#include "treesketch/util/error.h"

using namespace treesketch;

namespace {
constexpr std::array<const char*, 12> kExtensions = {".ply", ".obj", ".las", ".xyz", ".txt", ".csv",
                                                     ".pts", ".PLY", ".Las", ".laz", ".dat", ""};
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const char* extension = kExtensions[data[0] % kExtensions.size()];
  const std::filesystem::path path = fuzz::writeTempFile(extension, fuzz::asText(data + 1, size - 1));
  try {
    const io::FileInfo info = io::inspectFile(path);
    FUZZ_CHECK(!info.format.empty(), "inspectFile: no format named");
    if (info.isMesh)
      fuzz::checkMesh(info.mesh);
    else
      fuzz::checkCloud(info.cloud, 1);
  } catch (const InputError&) {
  }
  try {
    fuzz::checkCloud(io::readPointCloud(path), io::kMinCloudPoints);
  } catch (const InputError&) {
  }
  try {
    fuzz::checkMesh(io::readMesh(path));
  } catch (const InputError&) {
  }
  return 0;
}
