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
/// With `grid` (a voxel graph of `cloud`: each point's voxel and the centroid of its points), a
/// voxel is decided for all its points at once from the distance d at its centroid and its
/// points' spread s (farthest from the centroid): outside the model the signed distance is the
/// exact distance to the surface, which changes no faster than the position, and a point within
/// s of a centroid inside the model is no farther than s outside it. So max(d, 0) + s <= margin:
/// all are explained; d - s > margin: none is. Only the other voxels' points are measured one by
/// one. The result is the same as without `grid` (test Completion.*); on the 1M-point bench tree
/// the completion took 0.18 s instead of 0.75 s (bench/README.md).
std::vector<std::uint32_t> unexplainedPoints(const geom::PointCloud& cloud, const compare::CylinderModelIndex& model,
                                             double margin, const VoxelGraph* grid = nullptr,
                                             const std::vector<std::uint32_t>* among = nullptr,
                                             const std::vector<double>* pieceMargin = nullptr);

/// Grafts `part` (the skeleton of some unexplained points: parent-first, root 0) onto `nodes`
/// (the skeleton; `model` is its fitted model, index for index up to the parts grafted since,
/// `pieces` that model's frustums and `index` their surface): the part is re-rooted at its node
/// nearest to the surface (its foot), which becomes a child of the node nearest to it. The part's
/// radius estimates are capped by the node it grows from. Refused (returns false, `nodes`
/// unchanged) when
/// - the part has fewer than two nodes (no tube);
/// - its foot lies farther than `maxGap` outside the model;
/// - none of its nodes lies farther outside than the radius of the piece nearest to it: a part
///   along a limb's side is that limb's own surface, missed by a tube too thin or off the limb's
///   axis (dense scans of the bushes' clustered stems: thin scribbles at their base), not a twig.
bool graftPart(std::vector<SkeletonNode>& nodes, const std::vector<SkeletonNode>& part,
               const std::vector<SkeletonNode>& model, const geom::CylinderModel& pieces,
               const compare::CylinderModelIndex& index, double maxGap);

}  // namespace treesketch::skeleton::detail
