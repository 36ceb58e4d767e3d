#include "treesketch/viewer/demo_scene.h"

#include <vector>

#include "treesketch/gen/tree_generator.h"
#include "treesketch/scan/sphere_scan.h"
#include "treesketch/util/error.h"

namespace treesketch::viewer {

geom::PointCloud demoTreeCloud(const DemoSceneOptions& options, const ProgressFn& progress) {
  if (options.rays == 0) throw OptionsError("demo scene: the scan needs at least one ray");
  gen::TreeOptions tree = gen::presetOptions(options.preset);
  tree.seed = options.seed;
  tree.up = geom::UpAxis::Y;
  tree.leaves = options.leaves;
  gen::GeneratedTree generated = gen::generateTree(tree);
  std::vector<geom::TriMesh> meshes{generated.branches.mesh};
  if (options.leaves && !generated.leaves.empty()) meshes.push_back(generated.leaves);
  scan::SphereScanOptions scanOptions;
  scanOptions.rays = options.rays;
  scanOptions.seed = options.seed;
  return scan::sphereScan(meshes, scanOptions, progress).cloud;
}

}  // namespace treesketch::viewer
