#include "treesketch/viewer/demo_scene.h"

#include <gtest/gtest.h>

#include "treesketch/util/error.h"

namespace treesketch::viewer {
namespace {

TEST(DemoScene, ScansAnUprightTree) {
  DemoSceneOptions o;
  o.rays = 3000;
  o.leaves = false;
  geom::PointCloud cloud = demoTreeCloud(o);
  EXPECT_GT(cloud.size(), 300u);
  EXPECT_LE(cloud.size(), 3100u);
  geom::BBox b = cloud.bounds();
  EXPECT_GT(b.extent().y(), 2.0);  // metres, Y up: taller than a couple of metres
  EXPECT_GT(b.extent().y(), b.extent().x());
  EXPECT_EQ(demoTreeCloud(o).positions, cloud.positions);  // deterministic
}

TEST(DemoScene, RejectsBadOptions) {
  DemoSceneOptions o;
  o.rays = 0;
  EXPECT_THROW(demoTreeCloud(o), OptionsError);
  o.rays = 100;
  o.preset = "no-such-tree";
  EXPECT_THROW(demoTreeCloud(o), OptionsError);
}

}  // namespace
}  // namespace treesketch::viewer
