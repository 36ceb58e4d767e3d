// Completion of the automatic model from the points it leaves unexplained (see
// CompletionRules in treesketch/skeleton/skeleton_sketch.h). A level set holds whatever lies at
// one geodesic distance: where twigs cross or lie within a voxel or two of each other (a dense
// crown, a twig along its limb), they are one piece and one node, and the twigs that do not pass
// through that node's tube are left out. Their points are still in the cloud, outside the model.
// The same pipeline run on those points alone models them; each part is grafted onto the model
// at its nearest node.
#pragma once

#include <cstdint>
#include <vector>

#include "treesketch/compare/model_fit.h"
#include "treesketch/geom/point_cloud.h"
#include "treesketch/skeleton/skeleton_sketch.h"
#include "treesketch/skeleton/voxel_graph.h"

namespace treesketch::skeleton::detail {

/// Indices of the points of `cloud` farther than `margin` (cloud units) outside the model's
/// surface: of all its points, or of those in `among` only (ascending indices).
///
/// `pieceMargin`, when given, holds a margin per piece of the model (by the model's piece index;
/// `margin` for pieces beyond it): a point is unexplained when its signed distance exceeds the
/// margin of the piece that gives it (compare::CylinderModelIndex::signedDistance).
///
/// With `grid` (a voxel graph of `cloud`: each point's voxel and the centroid of its points), a
/// voxel is searched once, at its centroid, for the pieces that can be nearest to any of its points
/// (CylinderModelIndex::nearPieces, within its points' spread s); with d the signed distance at
/// the centroid, max(d, 0) + s within the smallest of those pieces' margins: all its points are
/// explained; d - s beyond the largest: none is; the same bounds per point with its own distance
/// from the centroid, and the points still undecided are measured against those pieces only. The
/// result is the same as without `grid`, point for point (tests Completion.*).
std::vector<std::uint32_t> unexplainedPoints(const geom::PointCloud& cloud, const compare::CylinderModelIndex& model,
                                             double margin, const VoxelGraph* grid = nullptr,
                                             const std::vector<std::uint32_t>* among = nullptr,
                                             const std::vector<double>* pieceMargin = nullptr);

/// A part of one node (`part`, the skeleton of `points`) is a stub shorter than two level sets,
/// and its node the centroid of its points, halfway along it: a tube ending there leaves the
/// stub's outer half past its end. The node is moved to the point of `points` farthest outside
/// the model (`index`), the stub's tip. A part of any other size is left as it is.
void reachStubTip(std::vector<SkeletonNode>& part, const geom::PointCloud& points,
                  const compare::CylinderModelIndex& index);

/// Grafts `part` (the skeleton of some unexplained points: parent-first, root 0) onto `nodes`
/// (the skeleton; `model` is its fitted model, index for index up to the parts grafted since,
/// `pieces` that model's frustums and `index` their surface): the part is re-rooted at its node
/// nearest to the surface (its foot), which becomes a child of the node nearest to it. A part of
/// one node (a stub shorter than two level sets: a short shoot, a twig's tip past the model's
/// end) is one tube from the node it grows from to that node. The part's radius estimates are
/// capped by the node it grows from. Refused (returns false, `nodes` unchanged) when
/// - the part has no node;
/// - its foot lies farther than `maxGap` outside the model;
/// - none of its nodes lies farther outside than the radius of the piece nearest to it: a part
///   along a limb's side is that limb's own surface, missed by a tube too thin or off the limb's
///   axis (dense scans of the bushes' clustered stems: thin scribbles at their base), not a twig.
bool graftPart(std::vector<SkeletonNode>& nodes, const std::vector<SkeletonNode>& part,
               const std::vector<SkeletonNode>& model, const geom::CylinderModel& pieces,
               const compare::CylinderModelIndex& index, double maxGap);

}  // namespace treesketch::skeleton::detail
