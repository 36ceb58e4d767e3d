// A cylinder model of a tree (a QSM, "quantitative structure model"): a list of cylinders or
// frustums (truncated cones), each from a start point to an end point with a radius at each end.
// A skeleton model's parent→child segments are frustums with the two nodes' radii; TreeQSM's and
// SimpleForest's tables are plain cylinders (both radii equal). Plain data; the readers are in
// io/cylinder_table.h, the measures against a cloud in compare/model_fit.h.
#pragma once

#include <cstdint>
#include <vector>

#include "treesketch/geom/types.h"

namespace treesketch::geom {

/// One piece of the model. A solid frustum with flat end caps: the points within radius r(t) of
/// the segment's axis at axial position t, r going linearly from startRadius to endRadius.
struct ModelCylinder {
  Vec3 start = Vec3::Zero();
  Vec3 end = Vec3::Zero();
  double startRadius = 0;         ///< model units, >= 0
  double endRadius = 0;           ///< model units, >= 0
  std::int64_t parent = -1;       ///< index of the parent piece in the same model; -1 for none
  std::int32_t branchOrder = -1;  ///< 0 = trunk; -1 when the model does not say

  double length() const { return (end - start).norm(); }
  /// Exact volume of the frustum: π L (r0² + r0 r1 + r1²) / 3 (= π r² L for a cylinder).
  double volume() const;
  /// Axis-aligned box holding the whole solid (the two end discs' boxes; exact).
  BBox bounds() const;
};

struct CylinderModel {
  std::vector<ModelCylinder> cylinders;

  bool empty() const { return cylinders.empty(); }
  std::size_t size() const { return cylinders.size(); }
};

/// A node of a tree model: position, radius and parent (index in the same list, -1 for a root).
struct ModelNode {
  Vec3 position = Vec3::Zero();
  double radius = 0;
  std::int64_t parent = -1;
  std::int32_t branchOrder = -1;
};

/// One frustum per node that has a parent, from the parent's position and radius to the node's
/// (the shape a tube swept through the nodes' rings has), in node order. A piece's parent is the
/// parent node's own piece (-1 when the parent node is a root); its branch order is the node's.
/// Throws OptionsError when a parent index is out of range.
CylinderModel cylinderModelFromNodes(const std::vector<ModelNode>& nodes);

}  // namespace treesketch::geom
