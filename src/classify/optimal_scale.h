// Features at each point's own best neighbourhood size (see features.h): among a few candidate
// sizes k, the one whose covariance eigenvalues, normalised to sum to 1, have the least Shannon
// entropy (the neighbourhood that is most clearly a line, a plane or a blob), and the shape at that
// size. A limb's best size follows its radius (a patch too small looks flat, one that reaches
// around the limb is a line), a leaf's follows the leaf (beyond its edge the neighbourhood takes
// in other leaves and scatters), so the chosen size itself is a feature.
// Method: eigenentropy-based scale selection of Weinmann et al. (2015, "Semantic point cloud
// interpretation based on optimal neighborhoods, relevant features and efficient classifiers",
// ISPRS J. 105), evaluated at a few sizes from one k-nearest query.
#pragma once

#include <string>
#include <vector>

#include "treesketch/accel/point_index.h"
#include "treesketch/classify/features.h"

namespace treesketch::classify::detail {

/// Names of the optimal-scale features, in order.
std::vector<std::string> optimalScaleFeatureNames();

/// The optimal-scale features of the point `p` whose neighbours (nearest first, itself first) are
/// `nb` in `index`, into `out` (optimalScaleFeatureNames().size() values). `candidates`: the sizes
/// tried, increasing (those larger than the neighbours found are skipped; when none fits, all of
/// `nb` is used). `spacing` is the unit of the radius feature, `up` the up direction.
void optimalScaleFeatures(const accel::PointIndex& index, const geom::Vec3& p, const std::vector<accel::Neighbour>& nb,
                          const std::vector<int>& candidates, double spacing, const geom::Vec3& up, float* out);

}  // namespace treesketch::classify::detail
