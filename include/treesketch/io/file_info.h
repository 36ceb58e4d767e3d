// What a cloud or mesh file holds, for `treesketch info`: its format details (PLY format and
// properties, LAS version / point format / scale / offset / header bounds, LAZ compressor /
// items / chunk size, OBJ counts) and the
// loaded data, from which counts, bounds, diagonal and area follow.
#pragma once

#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "treesketch/geom/point_cloud.h"
#include "treesketch/geom/tri_mesh.h"

namespace treesketch::io {

struct FileInfo {
  std::string format;  ///< e.g. "PLY binary_little_endian", "LAS 1.2", "LAZ (compressed LAS) 1.4", "OBJ", "XYZ text"
  /// Format details in file order, as (key, value) text pairs.
  std::vector<std::pair<std::string, std::string>> details;
  bool isMesh = false;  ///< true: `mesh` is filled; false: `cloud` is filled
  geom::TriMesh mesh;
  geom::PointCloud cloud;
};

/// Reads `path` fully. .obj and PLY files with a face element are read as meshes, everything
/// else as clouds (accepting any non-empty cloud). Throws InputError as the readers do.
FileInfo inspectFile(const std::filesystem::path& path);

}  // namespace treesketch::io
