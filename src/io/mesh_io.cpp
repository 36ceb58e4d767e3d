#include "treesketch/io/mesh_io.h"

#include "io/io_util.h"
#include "treesketch/io/obj.h"
#include "treesketch/io/ply.h"
#include "treesketch/util/error.h"

namespace treesketch::io {

MeshFormat meshFormatFromPath(const std::filesystem::path& path) {
  std::string ext = detail::lowerExtension(path);
  if (ext == ".obj") return MeshFormat::Obj;
  if (ext == ".ply") return MeshFormat::Ply;
  throw InputError(path.string() + ": unknown mesh extension '" + ext + "', expected .obj or .ply");
}

geom::TriMesh readMesh(const std::filesystem::path& path) {
  return meshFormatFromPath(path) == MeshFormat::Obj ? readObj(path) : readPlyMesh(path);
}

geom::TriMesh readMesh(std::istream& in, const std::string& source, MeshFormat format) {
  return format == MeshFormat::Obj ? readObj(in, source) : readPlyMesh(in, source);
}

void writeMesh(const std::filesystem::path& path, const geom::TriMesh& mesh) {
  std::string ext = detail::lowerExtension(path);
  if (ext == ".obj") return writeObj(path, mesh);
  if (ext == ".ply") return writePlyMesh(path, mesh);
  throw OutputError(path.string() + ": cannot write a mesh as '" + ext + "', expected .obj or .ply");
}

void writeMesh(std::ostream& out, MeshFormat format, const geom::TriMesh& mesh) {
  if (format == MeshFormat::Obj)
    writeObj(out, mesh);
  else
    writePlyMesh(out, mesh);
}

}  // namespace treesketch::io
