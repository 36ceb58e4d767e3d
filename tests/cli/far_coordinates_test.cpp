// The automatic model of a cloud moved far from its origin, as projected coordinates put it (a
// LAS file in UTM or national grid coordinates is 1e5 to 1e7 metres out): moved by 1e6 and 1e9 it
// is the same model — volume, crown and height within 0.5 % — and every output is written in the
// cloud's own coordinates (the mesh and the cylinder table are the unmoved ones plus the shift).
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <filesystem>
#include <string>

#include "cli_support.h"
#include "skeleton/synthetic_tree.h"
#include "test_support.h"
#include "treesketch/io/cylinder_table.h"
#include "treesketch/io/mesh_io.h"
#include "treesketch/io/point_cloud_io.h"

namespace treesketch {
namespace {

namespace fs = std::filesystem;
using test::quoted;

struct AutoModel {
  double volume = 0, crownArea = 0, cloudCrownArea = 0, height = 0;
  geom::BBox meshBox;
  geom::Vec3 firstStart = geom::Vec3::Zero();
};

/// `reconstruct --auto` of `cloud` moved by `shift` on every axis, written as `name`.
AutoModel modelMoved(const test::TempDir& dir, const geom::PointCloud& cloud, double shift, const std::string& name) {
  geom::PointCloud moved = cloud;
  for (auto& p : moved.positions) p = geom::Vec3(p.array() + shift);
  io::writePointCloud(dir / name, moved);
  std::string out;
  const std::string args = "reconstruct " + quoted(dir / name) + " --auto -o " + quoted(dir / "m.obj") +
                           " --cylinders " + quoted(dir / "m.csv") + " --report " + quoted(dir / "r.json");
  EXPECT_EQ(test::runCli(args, &out), 0) << out;
  AutoModel m;
  if (!fs::exists(dir / "r.json")) return m;
  const auto report = nlohmann::json::parse(test::readText(dir / "r.json"));
  m.volume = report["model"]["figures"]["volumeM3"].get<double>();
  m.crownArea = report["metrics"]["crownAreaM2"].get<double>();
  m.cloudCrownArea = report["metrics"]["cloud"]["crownAreaM2"].get<double>();
  m.height = report["metrics"]["heightM"].get<double>();
  for (const geom::Vec3& v : io::readMesh(dir / "m.obj").vertices) m.meshBox.add(v);
  m.firstStart = io::readCylinderTable(dir / "m.csv").model.cylinders.at(0).start;
  return m;
}

void expectSameModelWhenMoved(const geom::PointCloud& cloud, const std::string& ext) {
  test::TempDir dir;
  const AutoModel home = modelMoved(dir, cloud, 0.0, "home" + ext);
  ASSERT_GT(home.volume, 0);
  for (const double shift : {1e6, 1e9}) {
    SCOPED_TRACE(shift);
    const AutoModel far = modelMoved(dir, cloud, shift, "far" + ext);
    EXPECT_NEAR(far.volume, home.volume, 0.005 * home.volume);
    EXPECT_NEAR(far.crownArea, home.crownArea, 0.005 * home.crownArea);
    EXPECT_NEAR(far.cloudCrownArea, home.cloudCrownArea, 0.005 * home.cloudCrownArea);
    EXPECT_NEAR(far.height, home.height, 0.005 * home.height);
    // written back in the cloud's coordinates: the unmoved outputs plus the shift, to the millimetre
    const geom::Vec3 offset = geom::Vec3::Constant(shift);
    EXPECT_LT((far.meshBox.min - (home.meshBox.min + offset)).cwiseAbs().maxCoeff(), 1e-3);
    EXPECT_LT((far.meshBox.max - (home.meshBox.max + offset)).cwiseAbs().maxCoeff(), 1e-3);
    EXPECT_LT((far.firstStart - (home.firstStart + offset)).cwiseAbs().maxCoeff(), 1e-3);
  }
}

TEST(FarCoordinates, AGeneratedTreeMovedByAMillionAndABillionIsTheSameModel) {
  expectSameModelWhenMoved(test::sampleCylinders(test::threeLevelTree(), 0.03, 0.002, 9), ".ply");
}

// A real leaf-off scan (../shared/data/real/adtree_tree1.xyz, 11,855 points; skipped without it).
// Its crown area moved by 1e9 was 64 m² instead of 7.3 (the hull's area from raw coordinates).
TEST(FarCoordinates, ARealScanMovedByAMillionAndABillionIsTheSameModel) {
  const fs::path path = test::sharedDataDir() / "real" / "adtree_tree1.xyz";
  if (!fs::exists(path)) GTEST_SKIP() << "needs " << path;
  expectSameModelWhenMoved(io::readPointCloud(path), ".xyz");
}

}  // namespace
}  // namespace treesketch
