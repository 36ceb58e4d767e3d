// Skeleton models as frustums and as OBJ polylines.
#include "treesketch/skeleton/skeleton_export.h"

#include <iomanip>

#include "treesketch/util/atomic_file.h"
#include "treesketch/util/error.h"

namespace treesketch::skeleton {

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
