// A tree in leaf's two models: of the points the wood/leaf classification calls wood, and of every
// point (tree_model.h: woodOnlyCloud, everyPointVolume, classifiedWoodVolume; the volume range's ends).
#include <cstdint>
#include <string>
#include <vector>

#include "treesketch/classify/classify.h"
#include "treesketch/cloud/stray_points.h"
#include "treesketch/model/tree_model.h"
#include "treesketch/skeleton/skeleton_sketch.h"
#include "treesketch/util/error.h"

namespace treesketch::model {

namespace {

/// Fewer points classified as wood than this are no tree's wood to model.
constexpr std::size_t kMinWoodPoints = 100;

/// The indices of the points of `cloud` the classification calls wood (woodModellingOptions).
std::vector<std::uint32_t> classifiedWoodIndices(const geom::PointCloud& cloud, geom::UpAxis up) {
  const classify::Classification c = classify::classifyWood(cloud, up, classify::woodModellingOptions());
  std::vector<std::uint32_t> wood;
  for (std::size_t i = 0; i < cloud.size() && i < c.wood.size(); ++i)
    if (c.wood[i]) wood.push_back(static_cast<std::uint32_t>(i));
  return wood;
}

double modelVolume(const TreeModel& model) {
  double v = 0;
  for (const geom::ModelCylinder& c : model.cylinders.cylinders) v += c.volume();
  return v;
}

}  // namespace

geom::PointCloud woodOnlyCloud(const geom::PointCloud& cloud, geom::UpAxis up, const std::string& source) {
  const std::vector<std::uint32_t> wood = classifiedWoodIndices(cloud, up);
  if (wood.size() < kMinWoodPoints)
    throw DegenerateInputError(source + ": --wood-only: " + std::to_string(wood.size()) + " of " +
                               std::to_string(cloud.size()) +
                               " points classified as wood, too few to model (run without --wood-only)");
  return cloud::selectPoints(cloud, wood);
}

double everyPointVolume(const geom::PointCloud& cloud, const skeleton::AutoSkeletonOptions& options, geom::UpAxis up) {
  return modelVolume(fromAutoSkeleton(skeleton::autoSkeletonSketch(cloud, options), up));
}

double classifiedWoodVolume(const geom::PointCloud& cloud, const skeleton::AutoSkeletonOptions& options,
                            geom::UpAxis up) {
  const std::vector<std::uint32_t> wood = classifiedWoodIndices(cloud, up);
  if (wood.size() < kMinWoodPoints) return -1.0;
  return modelVolume(fromAutoSkeleton(skeleton::autoSkeletonSketch(cloud::selectPoints(cloud, wood), options), up));
}

}  // namespace treesketch::model
