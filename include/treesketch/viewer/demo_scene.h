// The viewer's built-in demo: a procedural tree (gen::generateTree, a named preset) scanned with
// the thesis's sphere scanner, so the tool opens on something to sketch without any file.
#pragma once

#include <cstdint>
#include <string>

#include "treesketch/geom/point_cloud.h"
#include "treesketch/util/progress.h"

namespace treesketch::viewer {

struct DemoSceneOptions {
  /// Tree preset (gen::presetNames()); "default" is a ~8 m broadleaf tree.
  std::string preset = "default";
  std::uint64_t seed = 1;
  /// Rays of the sphere scan (about as many points, minus misses). 30,000 keeps software
  /// rendering (llvmpipe, ~100 ms per 200k points) interactive; real use wants 300k+.
  std::uint64_t rays = 30000;
  /// Scan the leaves too (as a real scanner would see the tree).
  bool leaves = true;
};

/// The demo cloud (metres, Y up). Throws OptionsError for an unknown preset or zero rays.
geom::PointCloud demoTreeCloud(const DemoSceneOptions& options = {}, const ProgressFn& progress = {});

}  // namespace treesketch::viewer
