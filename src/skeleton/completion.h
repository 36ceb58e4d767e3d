// Completion of the automatic model from the points it leaves unexplained (see
// CompletionRules in treesketch/skeleton/skeleton_sketch.h). A level set holds whatever lies at
// one geodesic distance: where twigs cross or lie within a voxel or two of each other (a dense
// crown, a twig along its limb), they are one piece and one node, and the twigs that do not pass
// through that node's tube are left out. Their points are still in the cloud, outside the model.
// The same pipeline run on those points alone models them; each part is grafted onto the model
// at its nearest node.
#pragma once

#include <vector>

#include "treesketch/compare/model_fit.h"
#include "treesketch/geom/point_cloud.h"
#include "treesketch/skeleton/skeleton_sketch.h"

namespace treesketch::skeleton::detail {

/// The points of `cloud` farther than `margin` (cloud units) outside the model's surface.
geom::PointCloud unexplainedPoints(const geom::PointCloud& cloud, const compare::CylinderModelIndex& model,
                                   double margin);

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
