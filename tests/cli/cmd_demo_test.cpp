// The `treesketch demo` subcommand (apps/cli/cmd_demo.cpp), run through the CLI.
#include <gtest/gtest.h>

#include <sstream>
#include <vector>

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

// The demo shows the automatic model beside the thesis's sketches, with the files a user gets.
TEST(CmdDemo, ShowsTheAutomaticModelAndItsFiles) {
  test::TempDir dir;
  const auto out = dir / "demo";
  std::string output;
  ASSERT_EQ(test::runCli("demo --out " + test::quoted(out) + " --subdiv 5", &output), 0) << output;
  EXPECT_NE(output.find("automatic model (wood points)"), std::string::npos) << output;
  EXPECT_NE(output.find("\n  auto "), std::string::npos) << output;
  EXPECT_NE(output.find("\n  auto-leaf "), std::string::npos) << output;
  for (const char* f : {"recon_auto.obj", "cylinders_auto.csv", "qsm_auto.txt", "metrics_auto.json", "report_auto.json",
                        "auto.png"})
    EXPECT_GT(std::filesystem::file_size(out / f), 100u) << f;
  // The automatic model finds far more of the tree than the uniform sketch (forward RMS, the last
  // number of its row); the row is read, not assumed. (A sketch that fits few nodes can have a
  // small backward error: what little it built lies on the tree.)
  const auto row = [&](const std::string& name) {
    const std::size_t at = output.find("\n  " + name + " ");
    std::istringstream in(output.substr(at + 3 + name.size()));
    double v[9] = {};
    char bar;
    in >> v[0] >> v[1] >> v[2] >> bar >> v[3] >> v[4] >> v[5] >> bar >> v[6] >> v[7] >> v[8];
    return std::vector<double>(v, v + 9);
  };
  const std::vector<double> automatic = row("auto"), uniform = row("uniform");
  EXPECT_GT(automatic[8], 0.0);
  EXPECT_LT(automatic[8], 0.5 * uniform[8]);
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
