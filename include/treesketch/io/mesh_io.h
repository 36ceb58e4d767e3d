// Reading and writing triangle meshes by file extension: .obj and .ply.
#pragma once

#include <filesystem>
#include <istream>
#include <ostream>
#include <string>

#include "treesketch/geom/tri_mesh.h"

namespace treesketch::io {

enum class MeshFormat { Obj, Ply };

/// The format of a mesh file by its extension (case-insensitive); InputError for any other,
/// listing the supported ones.
MeshFormat meshFormatFromPath(const std::filesystem::path& path);

/// Reads a mesh (see readObj / readPlyMesh for what is accepted and rejected). A file with no
/// faces is rejected: it is a point cloud, not a mesh.
geom::TriMesh readMesh(const std::filesystem::path& path);
geom::TriMesh readMesh(std::istream& in, const std::string& source, MeshFormat format);

/// Writes OBJ (geometry only) or binary PLY (with colour/quality when present), atomically.
/// Throws OutputError for an unsupported extension.
void writeMesh(const std::filesystem::path& path, const geom::TriMesh& mesh);
void writeMesh(std::ostream& out, MeshFormat format, const geom::TriMesh& mesh);

}  // namespace treesketch::io
