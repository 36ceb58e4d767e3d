// A skeleton model as frustums (what every output of a model is written from: model/tree_model.h)
// and as an OBJ polyline (`v` per node, `l` per segment), written atomically
// (util/atomic_file.h): a failed write leaves no partial file.
#pragma once

#include <filesystem>
#include <ostream>
#include <vector>

#include "treesketch/geom/cylinder_model.h"
#include "treesketch/skeleton/skeleton.h"

namespace treesketch::skeleton {

/// The model as frustums (geom::CylinderModel, what compare::measureModelFit takes): one per
/// parent→child link, with the two nodes' radii, branch order of the child.
geom::CylinderModel cylinderModelFromSkeleton(const std::vector<SkeletonNode>& nodes);

/// OBJ polyline: a comment line, `v x y z` for every node in order, `l p c` (1-based) for every
/// parent→child link.
void writeSkeletonObj(std::ostream& out, const std::vector<SkeletonNode>& nodes);
void writeSkeletonObj(const std::filesystem::path& path, const std::vector<SkeletonNode>& nodes);

}  // namespace treesketch::skeleton
