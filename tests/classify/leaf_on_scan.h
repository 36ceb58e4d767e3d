// A leaf-on test scan for the classification tests: a tree from the project's own generator (not
// one of the ez-tree trees the models were trained on), scanned with the thesis's sphere pattern,
// each point labelled with the mesh it hit (the scanner's labels are the truth).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "treesketch/gen/tree_generator.h"
#include "treesketch/geom/point_cloud.h"
#include "treesketch/scan/sphere_scan.h"

namespace treesketch::test {

inline geom::PointCloud leafOnScan() {
  const gen::GeneratedTree tree = gen::generateTree(gen::presetOptions("default"));
  scan::SphereScanOptions s;
  s.rays = 300000;
  s.jitterDeg = 26.0;  // the cone over the whole tree
  s.rangeNoise = 0.003;
  s.recordMesh = true;
  return scan::sphereScan(std::vector<geom::TriMesh>{tree.branches.mesh, tree.leaves}, s).cloud;
}

/// The points called wood against the scanner's labels (mesh 0, the branches, is wood).
struct WoodCounts {
  std::size_t truePositives = 0, falsePositives = 0, falseNegatives = 0;
};

inline WoodCounts woodCounts(const geom::PointCloud& cloud, const std::vector<std::uint8_t>& wood) {
  WoodCounts n;
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    const bool truth = cloud.meshId[i] == 0;
    n.truePositives += truth && wood[i];
    n.falsePositives += !truth && wood[i];
    n.falseNegatives += truth && !wood[i];
  }
  return n;
}

}  // namespace treesketch::test
