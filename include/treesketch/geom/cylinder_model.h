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

/// The branches of a cylinder model: which pieces continue which, and each branch's order.
/// A branch is a chain of pieces, each the continuation ("extension") of the one before; it starts
/// at a root piece or where a piece leaves its parent's branch. The stem is the branch from the
/// lowest root (order 0); a branch leaving a branch of order k has order k + 1.
struct BranchStructure {
  std::vector<std::int32_t> order;         ///< per piece: the branch order (0 = stem)
  std::vector<std::int64_t> branch;        ///< per piece: the index of its branch (0 = the stem)
  std::vector<std::int64_t> position;      ///< per piece: its place in its branch, 0 = the first
  std::vector<std::int64_t> extension;     ///< per piece: the child piece that continues its branch, -1 if none
  std::vector<std::int32_t> branchOrder;   ///< per branch: its order
  std::vector<std::int64_t> branchParent;  ///< per branch: the branch it leaves, -1 for none
  std::size_t branches() const { return branchOrder.size(); }
};

/// Finds the branches. When every piece gives its branch order (>= 0), the model's orders decide:
/// a child continues its parent's branch when it has the parent's order (the thickest such child
/// if several). When any piece has no order (-1), they are derived: at every piece the child with
/// the largest start radius continues the branch (ties: the one pointing most along the parent),
/// every other child starts a branch one order up. Roots: the lowest along `up` is the stem (order
/// 0); another root starts a branch of order 1 (order 0 when the model's orders say so). Pieces
/// are visited from the roots, so any piece order works. Empty model → empty structure. Throws
/// OptionsError when a parent index is out of range or the parent links form a cycle.
BranchStructure branchStructure(const CylinderModel& model, UpAxis up);

/// A node of a tree model: position, radius and parent (index in the same list, -1 for a root).
struct ModelNode {
  Vec3 position = Vec3::Zero();
  double radius = 0;
  std::int64_t parent = -1;
  std::int32_t branchOrder = -1;
};

/// One frustum per node that has a parent, from the parent's position and radius to the node's
/// (the shape a tube swept through the nodes' rings has), in node order; a node whose branch order
/// is above its parent's starts a branch, and its piece starts with the smaller of the two radii
/// (the branch's own cylinder, not a cone of the parent's thickness). A piece's parent is the
/// parent node's own piece (-1 when the parent node is a root); its branch order is the node's.
/// Throws OptionsError when a parent index is out of range.
CylinderModel cylinderModelFromNodes(const std::vector<ModelNode>& nodes);

}  // namespace treesketch::geom
