// PLY (Stanford polygon file format): ascii, binary_little_endian and binary_big_endian, any of
// the PLY scalar types (char/int8 ... double/float64). Reads point clouds (the vertex element)
// and triangle meshes (vertex + face lists, polygons fan-triangulated); writes binary little
// endian with optional per-point station/mesh ints, scanner position and per-vertex colour and
// MeshLab "quality". Implemented in src/io/ply_header.cpp (the header), ply_read.cpp and ply_write.cpp.
#pragma once

#include <cstdint>
#include <filesystem>
#include <istream>
#include <optional>
#include <ostream>
#include <string>
#include <string_view>
#include <vector>

#include "treesketch/geom/point_cloud.h"
#include "treesketch/geom/tri_mesh.h"
#include "treesketch/io/read_options.h"

namespace treesketch::io {

enum class PlyFormat { Ascii, BinaryLittleEndian, BinaryBigEndian };
enum class PlyType { Int8, UInt8, Int16, UInt16, Int32, UInt32, Float32, Float64 };

struct PlyProperty {
  std::string name;
  PlyType type = PlyType::Float32;  ///< the value type (the item type of a list)
  bool isList = false;
  PlyType countType = PlyType::UInt8;  ///< only for lists
};

struct PlyElement {
  std::string name;
  std::uint64_t count = 0;
  std::vector<PlyProperty> properties;
  /// Index of the property called `name`, or -1.
  int find(std::string_view name) const;
};

struct PlyHeader {
  PlyFormat format = PlyFormat::Ascii;
  std::vector<std::string> comments;  ///< "comment" and "obj_info" lines, without the keyword
  std::vector<PlyElement> elements;
  std::size_t dataOffset = 0;   ///< byte offset of the first byte after "end_header\n"
  std::size_t headerLines = 0;  ///< number of header lines, "ply" to "end_header" inclusive
  /// The element called `name`, or nullptr.
  const PlyElement* find(std::string_view name) const;
};

/// "ascii", "binary_little_endian", "binary_big_endian".
const char* toString(PlyFormat f);
/// PLY's canonical type name: "char", "uchar", "short", "ushort", "int", "uint", "float", "double".
const char* toString(PlyType t);
/// Bytes of one value of type `t` in a binary body (1, 2, 4 or 8). Inline: the binary reader
/// asks for every value it reads.
constexpr std::size_t typeSize(PlyType t) {
  switch (t) {
    case PlyType::Int8:
    case PlyType::UInt8:
      return 1;
    case PlyType::Int16:
    case PlyType::UInt16:
      return 2;
    case PlyType::Int32:
    case PlyType::UInt32:
    case PlyType::Float32:
      return 4;
    case PlyType::Float64:
      return 8;
  }
  return 1;
}
/// True for char ... uint, false for float and double.
constexpr bool isIntegerType(PlyType t) { return t != PlyType::Float32 && t != PlyType::Float64; }

/// Parses the header at the start of `data`. Throws InputError (with the header line) for a
/// missing "ply" magic, missing/unsupported format line, unknown keyword or type, a property
/// outside an element, a bad count, or a missing end_header.
PlyHeader parsePlyHeader(std::string_view data, const std::string& source);
/// The comment by which a PLY says its up axis: "comment up_axis y" or "comment up_axis z".
/// treesketch writes it for clouds that know their up (geom::PointCloud::up).
inline constexpr const char* kPlyUpKey = "up_axis";
/// The up axis a header's `up_axis` comment declares (y or z, any case), or none.
std::optional<geom::UpAxis> declaredUpAxis(const PlyHeader& header);
/// Reads only the header of a PLY file (reads at most the first 64 KiB).
PlyHeader readPlyHeader(const std::filesystem::path& path);

/// Reads the vertex element's x/y/z (any scalar types) as a point cloud, plus integer
/// properties "station" and "mesh" into PointCloud::station / meshId and "scanner_x",
/// "scanner_y", "scanner_z" (all three) into PointCloud::scanner when present. Other
/// properties and elements (faces, edges, lists) are skipped, so a PLY mesh reads as its
/// vertices. Throws InputError (line for ascii, byte offset for binary) for: truncated data,
/// a non-number, NaN/Inf coordinates, no vertex element or no x/y/z, fewer than
/// options.minPoints points. Allocation is capped by the bytes actually present.
geom::PointCloud readPlyPointCloud(std::istream& in, const std::string& source, const CloudReadOptions& options = {});
geom::PointCloud readPlyPointCloud(const std::filesystem::path& path, const CloudReadOptions& options = {});

/// Reads a PLY mesh: vertex x/y/z plus optional red/green/blue (uchar, or float in 0..1) and
/// "quality"; the face element's "vertex_indices" (or "vertex_index") list of any count/index
/// types; polygons are fan-triangulated. Throws InputError for the same as above plus: no face
/// element or no index list, a face with fewer than 3 indices, an index out of range, no
/// triangles at all.
geom::TriMesh readPlyMesh(std::istream& in, const std::string& source);
geom::TriMesh readPlyMesh(const std::filesystem::path& path);

/// Writes a binary little-endian PLY: double x/y/z (doubles keep UTM coordinates exact), plus
/// "int station" / "int mesh" and "double scanner_x scanner_y scanner_z" (the position of the
/// scanner that measured the point: per-point scalar fields, as CloudCompare and PDAL read extra
/// PLY properties) when the cloud has them (one per point). Throws OutputError for a non-finite
/// coordinate; OptionsError for inconsistent attribute arrays.
void writePlyPointCloud(std::ostream& out, const geom::PointCloud& cloud);
void writePlyPointCloud(const std::filesystem::path& path, const geom::PointCloud& cloud);

/// Writes a binary little-endian PLY mesh as MeshLab reads it: double x/y/z, then uchar
/// red/green/blue and float quality when the mesh has them, and faces as "list uchar int
/// vertex_indices". Throws OutputError for a non-finite coordinate; OptionsError for an index
/// out of range or attribute arrays of the wrong size.
void writePlyMesh(std::ostream& out, const geom::TriMesh& mesh);
void writePlyMesh(const std::filesystem::path& path, const geom::TriMesh& mesh);

}  // namespace treesketch::io
