// `treesketch reconstruct --auto` and `sketch auto --method skeleton`, run as processes.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <optional>
#include <nlohmann/json.hpp>
#include <string>

#include "cli_support.h"
#include "marked_las.h"
#include "skeleton/synthetic_tree.h"
#include "test_support.h"
#include "treesketch/io/cylinder_table.h"
#include "treesketch/io/mesh_io.h"
#include "treesketch/io/point_cloud_io.h"
#include "treesketch/io/sketch_file.h"

namespace treesketch {
namespace {

using test::quoted;

/// Writes the Y-shaped test tree's cloud to DIR/c.ply; returns that path, quoted for the shell.
std::string yTreeCloud(const test::TempDir& dir) {
  io::writePointCloud(dir / "c.ply", test::sampleCylinders(test::yTree(), 0.02, 0.003, 7));
  return quoted(dir / "c.ply");
}

TEST(CmdAuto, ReconstructAutoWritesMeshSketchAndCylinders) {
  test::TempDir dir;
  io::writePointCloud(dir / "c.ply", test::sampleCylinders(test::yTree(), 0.02, 0.003, 7));
  for (const std::string extra : {"", " --leaf-on"}) {
    std::string out;
    const int rc = test::runCli("reconstruct " + quoted(dir / "c.ply") + " --auto" + extra + " --sketch " +
                                    quoted(dir / "s.json") + " --cylinders " + quoted(dir / "c.csv") + " -o " +
                                    quoted(dir / "m.ply"),
                                &out);
    ASSERT_EQ(rc, 0) << extra << ": " << out;
    EXPECT_NE(out.find("fits accepted"), std::string::npos) << out;
    EXPECT_NE(out.find("leaf pieces not fitted"), std::string::npos) << out;
    EXPECT_FALSE(io::readMesh(dir / "m.ply").empty()) << extra;
    EXPECT_GE(io::readSketch(dir / "s.json").size(), 3u) << extra;
    std::ifstream csv(dir / "c.csv");
    std::string header, row;
    ASSERT_TRUE(std::getline(csv, header) && std::getline(csv, row)) << extra;
    std::filesystem::remove(dir / "m.ply");
  }
}

TEST(CmdAuto, LeafOnNeedsAuto) {
  test::TempDir dir;
  io::writePointCloud(dir / "c.ply", test::sampleCylinders(test::yTree(), 0.02, 0.003, 7));
  std::string out;
  EXPECT_EQ(test::runCli("reconstruct " + quoted(dir / "c.ply") + " --sketch " + quoted(dir / "s.json") +
                             " --leaf-on -o " + quoted(dir / "m.ply"),
                         &out),
            2)
      << out;
  EXPECT_NE(out.find("--leaf-on"), std::string::npos) << out;
  EXPECT_FALSE(std::filesystem::exists(dir / "m.ply"));
}

TEST(CmdAuto, SketchAutoSkeletonLeafOn) {
  test::TempDir dir;
  io::writePointCloud(dir / "c.ply", test::sampleCylinders(test::yTree(), 0.02, 0.003, 7));
  std::string out;
  const int rc = test::runCli(
      "sketch auto " + quoted(dir / "c.ply") + " --method skeleton --leaf-on -o " + quoted(dir / "s.json"), &out);
  ASSERT_EQ(rc, 0) << out;
  EXPECT_GE(io::readSketch(dir / "s.json").size(), 3u);
}

// The saved automatic sketch rebuilds the automatic mesh (`reconstruct --sketch` uses its kept
// circles); --refit fits every node from the cloud instead.
TEST(CmdAuto, SavedSketchRebuildsTheAutomaticMeshAndRefitFitsIt) {
  test::TempDir dir;
  const std::string cloud = yTreeCloud(dir), sketchFile = quoted(dir / "s.json");
  std::string out;
  ASSERT_EQ(
      test::runCli("reconstruct " + cloud + " --auto --sketch " + sketchFile + " -o " + quoted(dir / "auto.ply"), &out),
      0)
      << out;
  const sketch::Sketch sk = io::readSketch(dir / "s.json");
  ASSERT_GE(sk.keptCircleCount(), 3u);
  const std::string again = "reconstruct " + cloud + " --sketch " + sketchFile + " --report " + quoted(dir / "r.json");
  ASSERT_EQ(test::runCli(again + " -o " + quoted(dir / "again.ply"), &out), 0) << out;
  EXPECT_NE(out.find(std::to_string(sk.keptCircleCount()) + " kept circles"), std::string::npos) << out;
  const geom::TriMesh a = io::readMesh(dir / "auto.ply"), b = io::readMesh(dir / "again.ply");
  ASSERT_EQ(a.triangles, b.triangles);
  ASSERT_EQ(a.vertices.size(), b.vertices.size());
  for (std::size_t v = 0; v < a.vertices.size(); ++v) EXPECT_LT((a.vertices[v] - b.vertices[v]).norm(), 1e-6);
  EXPECT_NE(test::readText(dir / "r.json").find("\"kept\": true"), std::string::npos);
  ASSERT_EQ(test::runCli(again + " --refit -o " + quoted(dir / "refit.ply"), &out), 0) << out;
  EXPECT_NE(out.find(" 0 kept circles"), std::string::npos) << out;
  // `sketch auto --method skeleton` saves the same handed-over model.
  ASSERT_EQ(test::runCli("sketch auto " + cloud + " --method skeleton -o " + quoted(dir / "s2.json"), &out), 0) << out;
  EXPECT_EQ(io::readSketch(dir / "s2.json").keptCircleCount(), sk.keptCircleCount());
  // --refit is for sketch files.
  EXPECT_EQ(test::runCli("reconstruct " + cloud + " --auto --refit -o " + quoted(dir / "x.ply"), &out), 2) << out;
  EXPECT_NE(out.find("--refit"), std::string::npos) << out;
  EXPECT_FALSE(std::filesystem::exists(dir / "x.ply"));
}

}  // namespace
}  // namespace treesketch

namespace treesketch {
namespace {

// Stray points far from the tree are set aside, counted in the summary line and the report, and
// written to --outliers; the model is the one made without them.
TEST(CmdAuto, StrayPointsAreSetAsideCountedAndWrittenOut) {
  test::TempDir dir;
  const geom::PointCloud clean = test::sampleCylinders(test::yTree(), 0.02, 0.003, 7);
  geom::PointCloud withStrays = clean;
  withStrays.positions.emplace_back(1e6, 0, 0);    // 1,000 km out
  withStrays.positions.emplace_back(0, 50.0, 20);  // 50 m out
  io::writePointCloud(dir / "clean.ply", clean);
  io::writePointCloud(dir / "strays.ply", withStrays);
  std::string out;
  ASSERT_EQ(test::runCli("reconstruct " + quoted(dir / "clean.ply") + " --auto --report " + quoted(dir / "r0.json") +
                             " -o " + quoted(dir / "m0.ply"),
                         &out),
            0)
      << out;
  EXPECT_NE(out.find("no stray point set aside"), std::string::npos) << out;
  ASSERT_EQ(test::runCli("reconstruct " + quoted(dir / "strays.ply") + " --auto --report " + quoted(dir / "r.json") +
                             " --outliers " + quoted(dir / "out.xyz") + " -o " + quoted(dir / "m.ply"),
                         &out),
            0)
      << out;
  EXPECT_NE(out.find("2 stray points set aside (2 far from the tree"), std::string::npos) << out;
  const auto r0 = nlohmann::json::parse(test::readText(dir / "r0.json"));
  const auto r = nlohmann::json::parse(test::readText(dir / "r.json"));
  EXPECT_EQ(r0["strayPoints"]["setAside"], 0);
  EXPECT_EQ(r["strayPoints"]["setAside"], 2);
  EXPECT_EQ(r["strayPoints"]["far"], 2);
  EXPECT_EQ(r["points"], clean.size() + 2);
  EXPECT_EQ(r["metrics"]["volumeM3"], r0["metrics"]["volumeM3"]);
  EXPECT_EQ(r["metrics"]["heightM"], r0["metrics"]["heightM"]);
  io::CloudReadOptions any;
  any.minPoints = 1;
  const geom::PointCloud set = io::readPointCloud(dir / "out.xyz", any);
  ASSERT_EQ(set.size(), 2u);
  EXPECT_EQ(set.positions[0].x(), 1e6);
  // --outliers belongs to the automatic model
  EXPECT_EQ(test::runCli("reconstruct " + quoted(dir / "strays.ply") + " --sketch " + quoted(dir / "s.json") +
                             " --outliers " + quoted(dir / "o.xyz") + " -o " + quoted(dir / "x.ply"),
                         &out),
            2)
      << out;
}

// A LAS file's withheld points never reach the model; its points classified as noise are set
// aside, counted in the summary line and the report, and kept with markedNoise.enabled=false; a
// bad value for that setting is refused naming it.
TEST(CmdAuto, MarkedNoiseIsSetAsideAndWithheldPointsNeverReachTheModel) {
  test::TempDir dir;
  const test::MarkedLas las = test::markedTreeLas(6);
  test::writeText(dir / "tree.las", las.bytes);
  const std::string base = "reconstruct " + quoted(dir / "tree.las") + " --auto --up z -o " + quoted(dir / "m.ply");
  std::string out;
  ASSERT_EQ(test::runCli(base + " --report " + quoted(dir / "r.json"), &out), 0) << out;
  EXPECT_NE(out.find("(" + std::to_string(las.marked) + " marked as noise by the file, "), std::string::npos) << out;
  ASSERT_EQ(test::runCli(base + " --report " + quoted(dir / "kept.json") + " --set markedNoise.enabled=false", &out), 0)
      << out;
  const auto r = nlohmann::json::parse(test::readText(dir / "r.json"));
  const auto kept = nlohmann::json::parse(test::readText(dir / "kept.json"));
  EXPECT_EQ(r["points"], las.treePoints);  // the withheld points are not read
  EXPECT_EQ(r["strayPoints"]["far"], 0);
  EXPECT_EQ(r["strayPoints"]["markedNoise"], las.marked);
  EXPECT_GE(r["strayPoints"]["setAside"], las.marked);
  EXPECT_EQ(kept["points"], las.treePoints);
  EXPECT_EQ(kept["strayPoints"]["markedNoise"], 0);
  EXPECT_LT(kept["strayPoints"]["setAside"], las.marked);  // the marked points on the tree are modelled
  for (const char* bad : {"markedNoise.enabled=2", "markedNoise.enabled=perhaps"}) {
    EXPECT_EQ(test::runCli(base + " --set " + bad, &out), 2) << bad << "\n" << out;
    EXPECT_NE(out.find("markedNoise.enabled"), std::string::npos) << out;
  }
}

/// The exact volume of an ez-tree test tree's branch mesh (its JSON skeleton's sections: frustums
/// between consecutive sections, scaled by the share of its circle a polygon of `segment_count`
/// sides holds), in model units³.
double scannedVolume(const std::filesystem::path& json) {
  const auto doc = nlohmann::json::parse(test::readText(json));
  double total = 0;
  for (const auto& b : doc["skeleton"]["branches"]) {
    const double n = b["segment_count"].get<double>();
    const double share = n / (2 * M_PI) * std::sin(2 * M_PI / n);
    const auto& s = b["sections"];
    for (std::size_t k = 1; k < s.size(); ++k) {
      const double r0 = s[k - 1]["radius"].get<double>(), r1 = s[k]["radius"].get<double>();
      double len2 = 0;
      for (int a = 0; a < 3; ++a) {
        const double d = s[k]["center"][a].get<double>() - s[k - 1]["center"][a].get<double>();
        len2 += d * d;
      }
      total += share * M_PI * std::sqrt(len2) * (r0 * r0 + r0 * r1 + r1 * r1) / 3;
    }
  }
  return total;
}

// A scan whose noise is the size of the tree's stems (a 2.7 m bush, 1-3 cm stems, under a
// mobile-scanner-like 25 mm of range noise): the few circles that fit are blobs of noise, so the
// radii are inferred from the crown and said to be. Before, the pipe law anchored on three such
// circles made the bush 11 times its wood.
TEST(CmdAuto, AScanAsNoisyAsItsStemsIsModelledFromItsCrown) {
  const auto trees = test::sharedDataDir() / "trees";
  if (!std::filesystem::exists(trees / "bush_2_s45590.json")) GTEST_SKIP() << "no " << trees;
  test::TempDir dir;
  std::string out;
  ASSERT_EQ(test::runCli("scan " + quoted(trees / "bush_2_s45590.branches.obj") + " -o " + quoted(dir / "c.ply") +
                       " --pattern tls --up y --units-metres 0.1 --step 0.4 --noise 0.025",
                   &out),
            0)
      << out;
  ASSERT_EQ(test::runCli("reconstruct " + quoted(dir / "c.ply") + " --auto --up y -o " + quoted(dir / "m.ply") +
                       " --report " + quoted(dir / "r.json"),
                   &out),
            0)
      << out;
  const auto report = nlohmann::json::parse(test::readText(dir / "r.json"));
  EXPECT_EQ(report["model"]["measuredVolumeShare"].get<double>(), 0.0) << out;
  const double ratio = report["metrics"]["volumeM3"].get<double>() / scannedVolume(trees / "bush_2_s45590.json");
  EXPECT_GT(ratio, 0.5) << out;
  EXPECT_LT(ratio, 2.5) << out;
}

}  // namespace
}  // namespace treesketch

namespace treesketch {
namespace {

TEST(CmdAuto, WoodOnlyNeedsAuto) {
  test::TempDir dir;
  std::string out;
  EXPECT_EQ(test::runCli("reconstruct " + yTreeCloud(dir) + " --sketch s.json --wood-only -o " + quoted(dir / "m.ply"),
                         &out),
            2)
      << out;
  EXPECT_NE(out.find("--wood-only needs --auto"), std::string::npos) << out;
}

// Trees in leaf modelled from the points the wood/leaf classification calls wood (../shared/data/real;
// skipped without it): a palm and a 22 m tropical tree. With every point, the palm's fronds became
// 7.3 m³ of tubes (form factor 6.5) holding 8 % of its points deeper than 2 cm; its wood is its stem.
// What the classification calls leaf may hold wood: the volume's range reaches up to every point's model.
// The tropical tree has a published TreeQSM model of its stem (263.7 L).
TEST(CmdAuto, WoodOnlyModelsATreeInLeafFromItsWood) {
  const auto real = test::sharedDataDir() / "real";
  if (!std::filesystem::exists(real / "pytlidar_tree_1.las")) GTEST_SKIP() << "no " << real;
  test::TempDir dir;
  for (const char* file : {"pytlidar_tree_1.las", "itsme_tree_1_pc.txt"}) {
    std::string out;
    ASSERT_EQ(test::runCli("reconstruct " + quoted(real / file) + " --auto --leaf-on --wood-only --up z -o " +
                               quoted(dir / "m.ply") + " --report " + quoted(dir / "r.json"),
                           &out),
              0)
        << out;
    const auto report = nlohmann::json::parse(test::readText(dir / "r.json"));
    EXPECT_TRUE(report["woodOnly"].get<bool>());
    EXPECT_LT(report["woodPoints"].get<double>(), 0.5 * report["points"].get<double>()) << file;
    EXPECT_LE(report["model"]["fit"]["insideDeeper2cm"].get<double>(), 0.05) << file;
    const double volume = report["metrics"]["volumeM3"].get<double>();
    const double dbh = report["metrics"]["dbhModelM"].get<double>(), height = report["metrics"]["heightM"].get<double>();
    EXPECT_LE(volume / (M_PI / 4 * dbh * dbh * height), 4.0) << file;
    if (std::string(file) == "itsme_tree_1_pc.txt") {
      EXPECT_GT(volume, 0.75 * 0.2637) << out;
      EXPECT_LT(volume, 1.33 * 0.2637) << out;
    }
    // The range reaches up to the model of every point: the palm's fronds as tubes, several times
    // its stem's wood.
    const double high = report["model"]["volumeRangeM3"][1].get<double>();
    EXPECT_GE(high, volume) << file;
    if (std::string(file) == "pytlidar_tree_1.las") EXPECT_GT(high, 3.0 * volume) << out;
    EXPECT_NE(report["verdict"].dump().find("a model of every point holds"), std::string::npos) << file;
  }
}

// A sparse scan keeps the circles it has: adtree_tree1 with 30 % of its points (3.5k; this draw)
// fits 37 circles on its stem and limbs, 3.6 % of its 1,041 nodes, and its stem is not tracked.
// With a 5 % share required they were thrown away for the crown's guess.
TEST(CmdAuto, ASparseScanKeepsTheCirclesItHas) {
  const auto file = test::sharedDataDir() / "real" / "adtree_tree1.xyz";
  if (!std::filesystem::exists(file)) GTEST_SKIP() << "no " << file;
  test::TempDir dir;
  const geom::PointCloud full = io::readPointCloud(file);
  geom::PointCloud sparse;
  std::uint64_t state = 2;
  for (const geom::Vec3& p : full.positions) {
    state = state * 6364136223846793005ULL + 1442695040888963407ULL;  // a fixed draw: 30 % of the points
    if ((state >> 33) % 10 < 3) sparse.positions.push_back(p);
  }
  io::writePointCloud(dir / "sparse.xyz", sparse);
  double volume[2] = {0, 0};
  for (int k = 0; k < 2; ++k) {
    std::string out;
    ASSERT_EQ(test::runCli("reconstruct " + quoted(k == 0 ? file : dir / "sparse.xyz") + " --auto --up z -o " +
                               quoted(dir / "m.ply") + " --report " + quoted(dir / "r.json"),
                           &out),
              0)
        << out;
    const auto report = nlohmann::json::parse(test::readText(dir / "r.json"));
    volume[k] = report["metrics"]["volumeM3"].get<double>();
    EXPECT_GT(report["model"]["measuredVolumeShare"].get<double>(), 0.1) << out;
  }
  EXPECT_GT(volume[1], 0.5 * volume[0]);
  EXPECT_LT(volume[1], 1.5 * volume[0]);
}

// The TreeLS spruce in leaf modelled from its wood (`reconstruct --auto --leaf-on --wood-only`):
// its cylinder table, and the cloud's bounds in `box`. Empty when ../shared/data is not there.
std::optional<io::CylinderTable> spruceWoodModel(const test::TempDir& dir, geom::BBox& box) {
  const auto file = test::sharedDataDir() / "real" / "treels_spruce_decoded.xyz";
  if (!std::filesystem::exists(file)) return std::nullopt;
  std::string out;
  EXPECT_EQ(test::runCli("reconstruct " + quoted(file) + " --auto --leaf-on --wood-only --up z -o " +
                             quoted(dir / "m.ply") + " --cylinders " + quoted(dir / "c.csv"),
                         &out),
            0)
      << out;
  box = io::readPointCloud(file).bounds();
  return io::readCylinderTable(dir / "c.csv");
}

// Every tube stays within the cloud: a tip is moved along its direction to the last of its own
// points, never to those of a limb that goes on beside it. The TreeLS spruce's wood, modelled with
// its repeated points set aside, had a tip carried 11 m out of the crown in a straight tube.
TEST(CmdAuto, NoTubeLeavesTheCloud) {
  test::TempDir dir;
  geom::BBox box;
  const std::optional<io::CylinderTable> model = spruceWoodModel(dir, box);
  if (!model) GTEST_SKIP() << "no ../shared/data/real/treels_spruce_decoded.xyz";
  const double margin = 0.1;  // metres: a tube's radius beyond the outermost points
  const io::CylinderTable& table = *model;
  for (const geom::ModelCylinder& c : table.model.cylinders)
    for (const geom::Vec3& end : {c.start, c.end})
      for (int a = 0; a < 3; ++a) {
        EXPECT_GE(end[a], box.min[a] - margin) << end.transpose();
        EXPECT_LE(end[a], box.max[a] + margin) << end.transpose();
      }
  EXPECT_GT(table.model.cylinders.size(), 100u);
}

// A conifer's stem is one branch from its foot into its crown. The TreeLS spruce's wood-only cloud
// has a skirt of dead branches round its lowest 1.5 m: its stem's branch wandered 0.8 m through
// them (rooted among them, joined to the stem 1.5 m up) and ended at 3 m, the rest of the stem
// carried as limbs; the trunk diameter came from those branches (20 cm against the points' 25).
TEST(CmdAuto, AConifersStemIsOneBranchFromItsFoot) {
  test::TempDir dir;
  geom::BBox box;
  const std::optional<io::CylinderTable> model = spruceWoodModel(dir, box);
  if (!model) GTEST_SKIP() << "no ../shared/data/real/treels_spruce_decoded.xyz";
  const double height = box.max.z() - box.min.z();
  const io::CylinderTable& table = *model;
  double stemLength = 0;
  std::vector<geom::Vec3> stem;
  for (const geom::ModelCylinder& c : table.model.cylinders)
    if (c.branchOrder == 0) {
      stemLength += (c.end - c.start).norm();
      stem.push_back(c.start);
      stem.push_back(c.end);
    }
  EXPECT_GT(stemLength, 0.6 * height);
  // Its lowest 3 m stand within 10 cm of one vertical line (the stem leans by under 2 cm there).
  geom::Vec3 mean = geom::Vec3::Zero();
  int n = 0;
  for (const geom::Vec3& p : stem)
    if (p.z() < box.min.z() + 3.0) {
      mean += p;
      ++n;
    }
  ASSERT_GT(n, 2);
  mean /= n;
  for (const geom::Vec3& p : stem)
    if (p.z() < box.min.z() + 3.0) EXPECT_LT(std::hypot(p.x() - mean.x(), p.y() - mean.y()), 0.1) << p.transpose();
}

}  // namespace
}  // namespace treesketch
