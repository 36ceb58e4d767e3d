// PLY writing: binary little-endian point clouds (double coordinates, optional station and mesh
// ids) and meshes (optional colour and MeshLab quality). Reading is in ply_header.cpp and
// ply_read.cpp.
#include "io/io_util.h"
#include "treesketch/io/ply.h"
#include "treesketch/util/atomic_file.h"
#include "treesketch/util/error.h"

namespace treesketch::io {

void writePlyPointCloud(std::ostream& out, const geom::PointCloud& cloud) {
  cloud.checkConsistent();
  bool st = !cloud.station.empty(), me = !cloud.meshId.empty(), sc = !cloud.scanner.empty();
  std::string buf = "ply\nformat binary_little_endian 1.0\ncomment written by treesketch\n";
  if (cloud.up) buf += std::string("comment ") + kPlyUpKey + " " + geom::toString(*cloud.up) + "\n";
  buf +=
      "element vertex " + std::to_string(cloud.size()) + "\nproperty double x\nproperty double y\nproperty double z\n";
  if (st) buf += "property int station\n";
  if (me) buf += "property int mesh\n";
  if (sc) buf += "property double scanner_x\nproperty double scanner_y\nproperty double scanner_z\n";
  buf += "end_header\n";
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    const geom::Vec3& p = cloud.positions[i];
    if (!p.allFinite()) throw OutputError("ply writer: point " + std::to_string(i) + " has a non-finite coordinate");
    detail::storeLE(buf, p.x());
    detail::storeLE(buf, p.y());
    detail::storeLE(buf, p.z());
    if (st) detail::storeLE(buf, cloud.station[i]);
    if (me) detail::storeLE(buf, cloud.meshId[i]);
    if (sc) {
      const geom::Vec3& o = cloud.scanner[i];
      if (!o.allFinite())
        throw OutputError("ply writer: point " + std::to_string(i) + " has a non-finite scanner position");
      detail::storeLE(buf, o.x());
      detail::storeLE(buf, o.y());
      detail::storeLE(buf, o.z());
    }
    detail::flushIfFull(out, buf);
  }
  detail::writeAll(out, buf);
}

void writePlyPointCloud(const std::filesystem::path& path, const geom::PointCloud& cloud) {
  writeFileAtomically(path, [&](std::ostream& out) { writePlyPointCloud(out, cloud); });
}

void writePlyMesh(std::ostream& out, const geom::TriMesh& mesh) {
  mesh.checkConsistent();
  bool col = !mesh.colors.empty(), qual = !mesh.quality.empty();
  std::string buf = "ply\nformat binary_little_endian 1.0\ncomment written by treesketch\nelement vertex " +
                    std::to_string(mesh.vertices.size()) +
                    "\nproperty double x\nproperty double y\nproperty double z\n";
  if (col) buf += "property uchar red\nproperty uchar green\nproperty uchar blue\n";
  if (qual) buf += "property float quality\n";
  buf += "element face " + std::to_string(mesh.triangles.size()) +
         "\nproperty list uchar int vertex_indices\nend_header\n";
  for (std::size_t i = 0; i < mesh.vertices.size(); ++i) {
    const geom::Vec3& p = mesh.vertices[i];
    if (!p.allFinite()) throw OutputError("ply writer: vertex " + std::to_string(i) + " has a non-finite coordinate");
    detail::storeLE(buf, p.x());
    detail::storeLE(buf, p.y());
    detail::storeLE(buf, p.z());
    if (col) buf.append(reinterpret_cast<const char*>(mesh.colors[i].data()), 3);
    if (qual) detail::storeLE(buf, static_cast<float>(mesh.quality[i]));
    detail::flushIfFull(out, buf);
  }
  for (const auto& t : mesh.triangles) {
    buf += static_cast<char>(3);
    for (auto idx : t) detail::storeLE(buf, static_cast<std::int32_t>(idx));
    detail::flushIfFull(out, buf);
  }
  detail::writeAll(out, buf);
}

void writePlyMesh(const std::filesystem::path& path, const geom::TriMesh& mesh) {
  writeFileAtomically(path, [&](std::ostream& out) { writePlyMesh(out, mesh); });
}

}  // namespace treesketch::io
