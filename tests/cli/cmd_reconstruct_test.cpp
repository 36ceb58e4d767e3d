// The `treesketch reconstruct` subcommand, end to end.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "cli_support.h"
#include "fit/synthetic_cylinder.h"
#include "test_support.h"
#include "treesketch/io/mesh_io.h"
#include "treesketch/io/point_cloud_io.h"
#include "treesketch/io/cylinder_table.h"
#include "treesketch/io/sketch_file.h"
#include "treesketch/model/tree_model.h"
#include "treesketch/recon/reconstruction.h"

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

// A person's sketch gives every output the automatic model gives, and the files are exactly what
// the library's one model writer makes of the same reconstruction.
TEST(CmdReconstruct, ASketchWritesEveryModelOutputAsTheLibraryDoes) {
  Files f;
  std::string out;
  const auto p = [&](const char* name) { return (f.dir / name).string(); };
  ASSERT_EQ(test::runCli("reconstruct " + f.cloud + " --sketch " + f.sketch + " -o " + p("m.obj") + " --cylinders " +
                             p("c.csv") + " --qsm " + p("q.txt") + " --metrics " + p("metrics.json") + " --report " +
                             p("r.json") + " --ring 8 --seed 3",
                         &out),
            0)
      << out;
  EXPECT_NE(out.find("tree metrics:"), std::string::npos) << out;
  EXPECT_NE(out.find("model fit:"), std::string::npos) << out;

  recon::ReconstructionOptions opt = recon::sketchReconstructionOptions();
  opt.seed = 3;
  opt.sweep.ringVertices = 8;
  const geom::PointCloud cloud = io::readPointCloud(f.cloud);
  const sketch::Sketch sk = io::readSketch(f.sketch);
  const model::TreeModel tree = model::fromReconstruction(recon::reconstruct(cloud, sk, opt), sk.up);
  ASSERT_EQ(tree.cylinders.size(), 1u);  // two fitted nodes, one skipped
  const model::ModelMeasures measures = model::measure(tree, cloud);
  model::OutputPaths lib;
  lib.cylinders = p("lib.csv");
  lib.qsm = p("lib.txt");
  lib.metrics = p("lib_metrics.json");
  model::writeOutputs(tree, measures, lib);
  EXPECT_EQ(test::readText(p("c.csv")), test::readText(lib.cylinders));
  EXPECT_EQ(test::readText(p("q.txt")), test::readText(lib.qsm));
  EXPECT_EQ(test::readText(p("metrics.json")), test::readText(lib.metrics));
  const auto report = nlohmann::json::parse(test::readText(p("r.json")));
  EXPECT_EQ(report["metrics"], nlohmann::json::parse(test::readText(lib.metrics)));
  EXPECT_EQ(report["model"], model::reportJson(measures, nlohmann::json::object())["model"]);
  EXPECT_EQ(report["nodes"].size(), 3u);
  const io::CylinderTable table = io::readCylinderTable(p("c.csv"));
  ASSERT_EQ(table.model.size(), 1u);
  EXPECT_NEAR(table.model.cylinders[0].endRadius, 0.2, 0.004);
}

// Fitted nodes that no fitted node joins (a sketch whose trunk misses the cloud: floating pieces)
// are refused, naming the nodes that did not fit; a bridged gap inside one piece is named too.
TEST(CmdReconstruct, FittedNodesInSeparatePiecesAreRefused) {
  Files f;
  sketch::Sketch s;
  sketch::SamplingParams sp;
  sp.lineEpsilon = 0.4;
  const auto root = s.addPointNode(sketch::kNoNode, Vec3(0, 9.0, 0), Vec3::UnitY(), sp);  // off the cloud
  s.addPointNode(root, Vec3(0, 0.5, 0), Vec3::UnitY(), sp);
  s.addPointNode(root, Vec3(0, 1.2, 0), Vec3::UnitY(), sp);
  const std::string two = (f.dir / "two.json").string();
  io::writeSketch(two, s);
  std::string out;
  const std::string mesh = (f.dir / "m.obj").string();
  EXPECT_EQ(test::runCli("reconstruct " + f.cloud + " --sketch " + two + " -o " + mesh, &out), 5) << out;
  EXPECT_NE(out.find("2 separate pieces"), std::string::npos) << out;
  EXPECT_NE(out.find("nodes that did not fit: " + std::to_string(root)), std::string::npos) << out;
  EXPECT_FALSE(std::filesystem::exists(mesh));
  // The fixture's sketch: its third node (above the cloud) is named, the model is written.
  EXPECT_EQ(test::runCli("reconstruct " + f.cloud + " --sketch " + f.sketch + " -o " + mesh, &out), 0) << out;
  EXPECT_NE(out.find("nodes that did not fit: "), std::string::npos) << out;
  // ... with how many fitted and, by kind, why the other did not.
  EXPECT_NE(out.find("fits: 2 of 3 fitted; 1 not: no points in the slice"), std::string::npos) << out;
}

TEST(CmdReconstruct, AModelOutputWithNoCylinderIsRefusedNotSkipped) {
  Files f;
  sketch::Sketch s;
  sketch::SamplingParams sp;
  sp.lineEpsilon = 0.4;
  s.addPointNode(sketch::kNoNode, Vec3(0, 0.5, 0), Vec3::UnitY(), sp);  // one node: a disc, no cylinder
  const std::string one = (f.dir / "one.json").string();
  io::writeSketch(one, s);
  std::string out;
  const std::string csv = (f.dir / "c.csv").string();
  EXPECT_EQ(test::runCli("reconstruct " + f.cloud + " --sketch " + one + " -o " + (f.dir / "m.obj").string() +
                             " --cylinders " + csv,
                         &out),
            5)
      << out;
  EXPECT_NE(out.find("no cylinder"), std::string::npos) << out;
  EXPECT_FALSE(std::filesystem::exists(csv));
}

TEST(Cli, AMistypedCommandIsNamedWithTheNearestOne) {
  std::string out;
  EXPECT_EQ(test::runCli("reconstrcut cloud.xyz", &out), 2) << out;
  EXPECT_NE(out.find("unknown command 'reconstrcut'"), std::string::npos) << out;
  EXPECT_NE(out.find("did you mean 'reconstruct'"), std::string::npos) << out;
  EXPECT_EQ(test::runCli("reconstrcut --help", &out), 2) << out;
  EXPECT_NE(out.find("did you mean 'reconstruct'"), std::string::npos) << out;
  EXPECT_EQ(test::runCli("zzzzzzzzzzzz", &out), 2) << out;
  EXPECT_EQ(out.find("did you mean"), std::string::npos) << out;
  EXPECT_EQ(test::runCli("--help", &out), 0) << out;
}

}  // namespace
}  // namespace treesketch
