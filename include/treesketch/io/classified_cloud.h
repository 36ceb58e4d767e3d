// Writing a classified cloud: every point with its class code and a per-point probability.
//  - PLY (binary little endian): double x/y/z, `uchar classification` (the code) and `float
//    <probabilityName>` (a scalar field, as CloudCompare and PDAL read extra PLY properties).
//  - LAS 1.4, point data record format 6: the class code in the classification byte and the
//    probability as a float "extra byte" (described by an Extra Bytes VLR, LAS 1.4 R15 §2.6), so
//    PDAL, LAStools and CloudCompare show it by name. Coordinates are stored at 0.1 mm (coarser
//    only when the cloud spans more than 200 km); intensity is kept when the cloud has it.
#pragma once

#include <cstdint>
#include <filesystem>
#include <ostream>
#include <string>
#include <vector>

#include "treesketch/geom/point_cloud.h"

namespace treesketch::io {

/// Writes `cloud` with `codes` and `probability` (one each per point) to `path` (.ply or .las,
/// atomically). Throws OptionsError when the arrays do not match the cloud, OutputError for another
/// extension (naming the two), a non-finite coordinate or a failed write.
void writeClassifiedCloud(const std::filesystem::path& path, const geom::PointCloud& cloud,
                          const std::vector<std::uint8_t>& codes, const std::vector<float>& probability,
                          const std::string& probabilityName = "wood_probability");
/// The same to a stream, as PLY (las = false) or LAS (las = true).
void writeClassifiedCloud(std::ostream& out, bool las, const geom::PointCloud& cloud,
                          const std::vector<std::uint8_t>& codes, const std::vector<float>& probability,
                          const std::string& probabilityName = "wood_probability");

}  // namespace treesketch::io
