// Wavefront OBJ triangle meshes: "v" and "f" lines; polygons are fan-triangulated; "f a/b/c"
// forms and negative (relative) indices are accepted; vt/vn/vp/usemtl/mtllib/g/o/s/l lines and
// comments are ignored. The writer emits "v" and "f" lines only.
#pragma once

#include <cstddef>
#include <filesystem>
#include <istream>
#include <ostream>
#include <string>

#include "treesketch/geom/point_cloud.h"
#include "treesketch/geom/tri_mesh.h"

namespace treesketch::io {

/// What readObj saw besides the triangles it returns.
struct ObjStats {
  std::size_t polygons = 0;      ///< "f" lines
  std::size_t nonTriangles = 0;  ///< "f" lines with more than 3 corners (fan-triangulated)
  std::size_t ignoredLines = 0;  ///< vt/vn/usemtl/g/o/s/l/... lines
};

/// Reads an OBJ mesh. Vertices must be defined before the faces that use them (as every common
/// exporter does). "v x y z [w | r g b]" keeps x y z. Throws InputError naming the line for: a
/// bad number, NaN/Inf, a face with fewer than 3 corners, index 0 or out of range, an unknown
/// keyword that is not a known-ignorable one, no triangles at all (a file with no faces is not
/// a mesh), and an empty file. `stats` (optional) receives counts of what was seen.
geom::TriMesh readObj(std::istream& in, const std::string& source, ObjStats* stats = nullptr);
geom::TriMesh readObj(const std::filesystem::path& path, ObjStats* stats = nullptr);

/// Reads only the "v" lines of an OBJ as a point cloud (a mesh given where a cloud is
/// expected reads as its vertices); faces are ignored but other lines are checked as in readObj.
geom::PointCloud readObjVertices(std::istream& in, const std::string& source);

/// Writes "v x y z" (shortest exact decimal) and "f a b c" (1-based) lines. Colour and quality
/// are not written (use PLY). Throws OutputError for a non-finite coordinate, OptionsError for an
/// index out of range.
void writeObj(std::ostream& out, const geom::TriMesh& mesh);
void writeObj(const std::filesystem::path& path, const geom::TriMesh& mesh);

}  // namespace treesketch::io
