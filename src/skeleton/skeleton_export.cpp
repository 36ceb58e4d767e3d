// Cylinder table and OBJ polyline writers for skeleton models.
#include "treesketch/skeleton/skeleton_export.h"

#include <iomanip>

#include "treesketch/util/atomic_file.h"
#include "treesketch/util/error.h"

namespace treesketch::skeleton {

void writeCylinderCsv(std::ostream& out, const std::vector<SkeletonNode>& nodes) {
  out << kCylinderCsvHeader << '\n';
  out << std::setprecision(9);
  // The start radii as the model has them (cylinderModelFromNodes: a piece per non-root node, in
  // node order; a branch's first piece starts with its own radius).
  const geom::CylinderModel model = cylinderModelFromSkeleton(nodes);
  std::size_t piece = 0;
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    const auto& n = nodes[i];
    if (n.parent < 0) continue;
    const double startRadius = model.cylinders[piece++].startRadius;
    const auto& p = nodes[n.parent];
    const std::int64_t parentCylinder = p.parent < 0 ? -1 : n.parent;
    out << i << ',' << parentCylinder << ',' << p.position.x() << ',' << p.position.y() << ',' << p.position.z() << ','
        << n.position.x() << ',' << n.position.y() << ',' << n.position.z() << ',' << n.radius << ','
        << (n.position - p.position).norm() << ',' << n.branchOrder << ',' << startRadius << '\n';
  }
  if (!out) throw OutputError("cylinder table: write failed");
}

void writeCylinderCsv(const std::filesystem::path& path, const std::vector<SkeletonNode>& nodes) {
  writeFileAtomically(
      path, [&](std::ostream& out) { writeCylinderCsv(out, nodes); }, false);
}

void writeSkeletonObj(std::ostream& out, const std::vector<SkeletonNode>& nodes) {
  out << "# treesketch skeleton: " << nodes.size() << " nodes\n";
  out << std::setprecision(9);
  for (const auto& n : nodes) out << "v " << n.position.x() << ' ' << n.position.y() << ' ' << n.position.z() << '\n';
  for (std::size_t i = 0; i < nodes.size(); ++i)
    if (nodes[i].parent >= 0) out << "l " << nodes[i].parent + 1 << ' ' << i + 1 << '\n';
  if (!out) throw OutputError("skeleton OBJ: write failed");
}

void writeSkeletonObj(const std::filesystem::path& path, const std::vector<SkeletonNode>& nodes) {
  writeFileAtomically(
      path, [&](std::ostream& out) { writeSkeletonObj(out, nodes); }, false);
}

geom::CylinderModel cylinderModelFromSkeleton(const std::vector<SkeletonNode>& nodes) {
  std::vector<geom::ModelNode> m(nodes.size());
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    m[i].position = nodes[i].position;
    m[i].radius = nodes[i].radius;
    m[i].parent = nodes[i].parent;
    m[i].branchOrder = nodes[i].branchOrder;
  }
  return geom::cylinderModelFromNodes(m);
}

}  // namespace treesketch::skeleton
