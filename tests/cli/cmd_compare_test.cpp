// The `treesketch compare` subcommand, run as a process.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <sstream>

#include "cli_support.h"
#include "compare/test_meshes.h"
#include "test_support.h"
#include "treesketch/io/mesh_io.h"

namespace treesketch::compare {
namespace {

using test::runCli;
using test::TempDir;

void writeObj(const std::filesystem::path& path, const geom::TriMesh& m) {
  std::ostringstream s;
  for (const auto& v : m.vertices) s << "v " << v.x() << " " << v.y() << " " << v.z() << "\n";
  for (const auto& t : m.triangles) s << "f " << t[0] + 1 << " " << t[1] + 1 << " " << t[2] + 1 << "\n";
  test::writeText(path, s.str());
}

class CompareCli : public ::testing::Test {
 protected:
  void SetUp() override {
    writeObj(dir / "a.obj", testing::grid(8, 1.0, 0.0));
    writeObj(dir / "b.obj", testing::grid(3, 1.0, 0.25));
    std::ostringstream cloud;
    for (int j = 0; j <= 10; ++j)
      for (int i = 0; i <= 10; ++i) cloud << i * 0.1 << " " << j * 0.1 << " 0.5\n";
    test::writeText(dir / "c.xyz", cloud.str());
  }
  std::string path(const std::string& name) const { return test::quoted(dir / name); }
  TempDir dir;
};

TEST_F(CompareCli, TableJsonAndErrorMesh) {
  std::string out;
  int rc = runCli("compare " + path("a.obj") + " " + path("b.obj") + " --samples 200 --json " + path("r.json") +
                      " --error-mesh " + path("e.ply") + " --bins 4",
                  &out);
  ASSERT_EQ(rc, 0) << out;
  EXPECT_NE(out.find("forward"), std::string::npos) << out;
  EXPECT_NE(out.find("backward"), std::string::npos) << out;
  EXPECT_NE(out.find("Hausdorff distance: 0.25 "), std::string::npos) << out;
  nlohmann::json j = nlohmann::json::parse(test::readText(dir / "r.json"));
  EXPECT_NEAR(j["hausdorff"].get<double>(), 0.25, 1e-12);
  EXPECT_NEAR(j["forward"]["rms"].get<double>(), 0.25, 1e-12);
  EXPECT_EQ(j["forward"]["samples"]["vertex"], 81);
  EXPECT_EQ(j["forward"]["samples"]["edge"], 200);
  EXPECT_EQ(j["backward"]["samples"]["vertex"], 16);
  EXPECT_EQ(j["forward"]["histogram"]["counts"].size(), 4u);
  geom::TriMesh e = io::readMesh(dir / "e.ply");
  ASSERT_EQ(e.vertices.size(), 81u);
  ASSERT_EQ(e.colors.size(), 81u);
  ASSERT_EQ(e.quality.size(), 81u);
  for (double q : e.quality) EXPECT_NEAR(q, 0.25, 1e-6);
}

TEST_F(CompareCli, PointCloudTargetOneWayAndSearchDistance) {
  std::string out;
  ASSERT_EQ(runCli("compare " + path("a.obj") + " " + path("c.xyz") + " --one-way --no-edge --no-face --json " +
                       path("r.json"),
                   &out),
            0)
      << out;
  EXPECT_EQ(out.find("backward"), std::string::npos) << out;
  nlohmann::json j = nlohmann::json::parse(test::readText(dir / "r.json"));
  EXPECT_FALSE(j.contains("backward"));
  EXPECT_GE(j["forward"]["min"].get<double>(), 0.5 - 1e-12);
  EXPECT_EQ(j["forward"]["samples"]["used"], 81);
  ASSERT_EQ(runCli("compare " + path("a.obj") + " " + path("b.obj") + " --max-dist 0.2 --json " + path("d.json"), &out),
            0)
      << out;
  j = nlohmann::json::parse(test::readText(dir / "d.json"));
  EXPECT_EQ(j["forward"]["samples"]["used"], 0);
  EXPECT_EQ(j["forward"]["samples"]["dropped"], 3 * 81);
  EXPECT_TRUE(j["hausdorff"].is_null());
}

TEST_F(CompareCli, BadInputsAndOptionsGiveDistinctExitCodes) {
  std::string out;
  EXPECT_EQ(runCli("compare " + path("a.obj") + " " + path("missing.obj"), &out), 3) << out;
  test::writeText(dir / "bad.obj", "v 0 0 0\nv 1 0 0\nf 1 2 3\n");
  EXPECT_EQ(runCli("compare " + path("bad.obj") + " " + path("b.obj"), &out), 3) << out;
  EXPECT_EQ(runCli("compare " + path("a.obj") + " " + path("b.obj") + " --bins 0", &out), 2) << out;
  EXPECT_EQ(runCli("compare " + path("a.obj") + " " + path("b.obj") + " --no-vertex --no-edge --no-face", &out), 2)
      << out;
  EXPECT_EQ(runCli("compare " + path("a.obj") + " " + path("b.obj") + " --error-mesh " + path("e.obj"), &out), 2)
      << out;
  EXPECT_EQ(
      runCli("compare " + path("a.obj") + " " + path("b.obj") + " --range 2 1 --error-mesh " + path("e.ply"), &out), 2)
      << out;
  EXPECT_EQ(runCli("compare " + path("a.obj") + " " + path("b.obj") + " --json " + path("b.obj"), &out), 4) << out;
  EXPECT_EQ(runCli("compare " + path("a.obj"), &out), 2) << out;
}

}  // namespace
}  // namespace treesketch::compare
