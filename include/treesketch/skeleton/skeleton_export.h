// Writing a skeleton model: a cylinder table (CSV, one row per parent→child segment, TreeQSM-
// style columns) and an OBJ polyline (`v` per node, `l` per segment). Both are written
// atomically (util/atomic_file.h): a failed write leaves no partial file.
#pragma once

#include <filesystem>
#include <ostream>
#include <vector>

#include "treesketch/geom/cylinder_model.h"
#include "treesketch/skeleton/skeleton.h"

namespace treesketch::skeleton {

/// Header line of the cylinder table.
inline constexpr const char* kCylinderCsvHeader =
    "id,parent,start_x,start_y,start_z,end_x,end_y,end_z,radius,length,branch_order,start_radius";

/// One row per non-root node i: the segment from its parent's
/// position to its own, radius = the node's radius, length in world units, branch order of the
/// node, start_radius = the parent's radius, or the node's own where the row starts a branch (the
/// row is the frustum of cylinderModelFromSkeleton; io/cylinder_table.h reads it back). Cylinder ids are the node
/// indices; `parent` is the parent node's cylinder id, or -1 when the parent is the root (which
/// has no cylinder). Numbers with 9 significant digits. Empty or single-node skeleton → header
/// only.
void writeCylinderCsv(std::ostream& out, const std::vector<SkeletonNode>& nodes);
/// Same, to a file (atomic). Throws OutputError when it cannot be written.
void writeCylinderCsv(const std::filesystem::path& path, const std::vector<SkeletonNode>& nodes);

/// The model as frustums (geom::CylinderModel, what compare::measureModelFit takes): one per
/// parent→child link, with the two nodes' radii, branch order of the child.
geom::CylinderModel cylinderModelFromSkeleton(const std::vector<SkeletonNode>& nodes);

/// OBJ polyline: a comment line, `v x y z` for every node in order, `l p c` (1-based) for every
/// parent→child link.
void writeSkeletonObj(std::ostream& out, const std::vector<SkeletonNode>& nodes);
void writeSkeletonObj(const std::filesystem::path& path, const std::vector<SkeletonNode>& nodes);

}  // namespace treesketch::skeleton
