// The `treesketch reconstruct` subcommand, end to end.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "cli_support.h"
#include "fit/synthetic_cylinder.h"
#include "test_support.h"
#include "treesketch/io/mesh_io.h"
#include "treesketch/io/point_cloud_io.h"
#include "treesketch/io/sketch_file.h"

namespace treesketch {
namespace {

using geom::Vec3;

struct Files {
  test::TempDir dir;
  std::string cloud, sketch;
  Files() {
    std::mt19937_64 rng(4);
    geom::PointCloud c;
    test::CylinderSpec spec;
    spec.radius = 0.2;
    spec.points = 6000;
    test::addCylinder(c, spec, rng);
    cloud = (dir / "cloud.xyz").string();
    io::writePointCloud(cloud, c);
    sketch::Sketch s;
    sketch::SamplingParams p;
    p.lineEpsilon = 0.4;
    auto a = s.addPointNode(sketch::kNoNode, Vec3(0, 0.5, 0), Vec3::UnitY(), p);
    auto b = s.addPointNode(a, Vec3(0.02, 1.2, 0), Vec3::UnitY(), p);
    s.addPointNode(b, Vec3(0, 9.0, 0), Vec3::UnitY(), p);  // above the cloud: skipped
    sketch = (dir / "sketch.json").string();
    io::writeSketch(sketch, s);
  }
};

TEST(CmdReconstruct, WritesMeshAndReport) {
  Files f;
  std::string out;
  std::string mesh = (f.dir / "mesh.obj").string(), report = (f.dir / "report.json").string();
  int rc = test::runCli(
      "reconstruct " + f.cloud + " --sketch " + f.sketch + " -o " + mesh + " --report " + report + " --ring 8 --seed 3",
      &out);
  ASSERT_EQ(rc, 0) << out;
  EXPECT_NE(out.find("2 fitted, 1 skipped"), std::string::npos) << out;
  geom::TriMesh m = io::readMesh(mesh);
  EXPECT_EQ(m.triangles.size(), 2u * 8 + 2u * 8);  // one band, two caps
  auto j = nlohmann::json::parse(test::readText(report));
  ASSERT_EQ(j["nodes"].size(), 3u);
  EXPECT_EQ(j["nodes"][0]["status"], "fitted");
  EXPECT_NEAR(j["nodes"][0]["radius"].get<double>(), 0.2, 0.004);
  EXPECT_EQ(j["nodes"][2]["status"], "skipped");
  EXPECT_FALSE(j["nodes"][2]["reason"].get<std::string>().empty());
  EXPECT_EQ(j["ringVertices"], 8);
}

TEST(CmdReconstruct, BadInputs) {
  Files f;
  std::string out;
  std::string mesh = (f.dir / "m.obj").string();
  EXPECT_EQ(
      test::runCli("reconstruct " + (f.dir / "missing.xyz").string() + " --sketch " + f.sketch + " -o " + mesh, &out),
      3)
      << out;
  test::writeText(f.dir / "bad.json", "{ not json");
  EXPECT_EQ(test::runCli("reconstruct " + f.cloud + " --sketch " + (f.dir / "bad.json").string() + " -o " + mesh, &out),
            3)
      << out;
  EXPECT_EQ(
      test::runCli("reconstruct " + f.cloud + " --sketch " + f.sketch + " -o " + (f.dir / "m.stl").string(), &out), 2)
      << out;
  EXPECT_EQ(test::runCli("reconstruct " + f.cloud + " --sketch " + f.sketch + " -o " + mesh + " --ring 2", &out), 2);
  EXPECT_EQ(test::runCli("reconstruct " + f.cloud + " --sketch " + f.sketch + " -o " + f.cloud, &out), 4) << out;
  EXPECT_FALSE(std::filesystem::exists(mesh));
}

}  // namespace
}  // namespace treesketch
