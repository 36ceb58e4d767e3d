// Reading and writing point clouds by file extension: .ply, .xyz/.txt/.csv/.pts/.asc, .las and
// .laz (compressed LAS), .obj (its vertices). Writers: .ply (binary) and .xyz/.txt.
#pragma once

#include <filesystem>
#include <istream>
#include <ostream>
#include <string>

#include "treesketch/geom/point_cloud.h"
#include "treesketch/io/read_options.h"

namespace treesketch::io {

enum class CloudFormat { Ply, Xyz, Las, Obj };

/// The format of a cloud file by its extension (case-insensitive; .laz is Las). Throws
/// InputError for an unknown extension (listing the supported ones).
CloudFormat cloudFormatFromPath(const std::filesystem::path& path);

/// Reads a point cloud in the format its extension names. Decision: a mesh file given where a
/// cloud is expected (PLY with faces, OBJ) reads as its vertices. Every reader rejects files with
/// fewer than options.minPoints points (default kMinCloudPoints = 4), NaN/Inf coordinates,
/// truncation and garbage with an InputError naming the file and the line or byte offset.
geom::PointCloud readPointCloud(const std::filesystem::path& path, const CloudReadOptions& options = {});
/// Same from a stream; `source` names it in messages.
geom::PointCloud readPointCloud(std::istream& in, const std::string& source, CloudFormat format,
                                const CloudReadOptions& options = {});

/// Writes `cloud` as binary PLY (.ply, with station/mesh attributes when present) or text XYZ
/// (.xyz, .txt; positions only), atomically. Throws OutputError for another extension.
void writePointCloud(const std::filesystem::path& path, const geom::PointCloud& cloud);
/// Same to a stream (format Ply or Xyz; OutputError otherwise).
void writePointCloud(std::ostream& out, CloudFormat format, const geom::PointCloud& cloud);

}  // namespace treesketch::io
