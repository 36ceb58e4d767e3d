// The `treesketch demo` subcommand (apps/cli/cmd_demo.cpp), run through the CLI.
#include <gtest/gtest.h>

#include "cli_support.h"
#include "test_support.h"
#include "treesketch/gen/skeleton_io.h"
#include "treesketch/gen/tree_generator.h"
#include "treesketch/io/mesh_io.h"
#include "treesketch/io/point_cloud_io.h"

namespace treesketch::gen {
namespace {

TEST(CmdDemo, WritesTheTreeTheScanAndASummary) {
  test::TempDir dir;
  const auto out = dir / "demo";  // does not exist yet: the demo creates it
  std::string output;
  ASSERT_EQ(test::runCli("demo --out " + test::quoted(out) + " --seed 5 --subdiv 3", &output), 0) << output;
  EXPECT_NE(output.find("wood fraction"), std::string::npos) << output;

  TreeOptions o;
  o.seed = 5;
  GeneratedTree expected = generateTree(o);
  Skeleton skeleton = readSkeletonJson(out / "tree_skeleton.json");
  ASSERT_EQ(skeleton.branches.size(), expected.skeleton.branches.size());
  EXPECT_EQ(skeleton.branches.back().sections.back().centre, expected.skeleton.branches.back().sections.back().centre);

  geom::TriMesh branches = io::readMesh(out / "tree_branches.obj");
  EXPECT_EQ(branches.triangles.size(), expected.branches.mesh.triangles.size());
  EXPECT_NEAR(branches.vertices[100].x(), expected.branches.mesh.vertices[100].x(), 1e-5);
  geom::TriMesh leaves = io::readMesh(out / "tree_leaves.obj");
  EXPECT_EQ(leaves.triangles.size(), expected.leaves.triangles.size());

  geom::PointCloud cloud = io::readPointCloud(out / "cloud.ply");
  EXPECT_GT(cloud.size(), 100u);
  geom::BBox box = expected.branches.mesh.bounds();
  box.add(expected.leaves.bounds());
  for (const geom::Vec3& p : cloud.positions) {
    ASSERT_GE(p.y(), box.min.y() - 1e-6);
    ASSERT_LE(p.y(), box.max.y() + 1e-6);
  }
  std::string summary = test::readText(out / "summary.txt");
  EXPECT_NE(summary.find("wood fraction"), std::string::npos);
  EXPECT_NE(summary.find("branches: " + std::to_string(expected.skeleton.branches.size())), std::string::npos);
}

TEST(CmdDemo, BadOptionsAndUnwritableOutput) {
  test::TempDir dir;
  EXPECT_EQ(test::runCli("demo --out " + test::quoted(dir / "a") + " --subdiv 0"), 2);
  EXPECT_EQ(test::runCli("demo --out " + test::quoted(dir / "a") + " --preset palm"), 2);
  test::writeText(dir / "file", "x");
  // The output "directory" is below a regular file: cannot be created.
  EXPECT_EQ(test::runCli("demo --out " + test::quoted(dir / "file" / "sub") + " --subdiv 1"), 4);
}

}  // namespace
}  // namespace treesketch::gen
