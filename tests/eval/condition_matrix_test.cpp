#include "treesketch/eval/condition_matrix.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <set>
#include <string>
#include <vector>

#include "test_support.h"
#include "treesketch/eval/evaluation.h"
#include "treesketch/util/error.h"

namespace treesketch::eval {
namespace {

std::set<std::string> namesOf(const std::vector<ScanCondition>& m) {
  std::set<std::string> names;
  for (const auto& c : m) names.insert(c.name);
  return names;
}

const ScanCondition& byName(const std::vector<ScanCondition>& m, const std::string& name) {
  for (const auto& c : m)
    if (c.name == name) return c;
  throw std::runtime_error("no condition " + name);
}

TEST(ConditionMatrix, NamesAreUnique) {
  for (const char* which : {"quick", "full"}) {
    auto m = conditionMatrix(which);
    ASSERT_FALSE(m.empty()) << which;
    EXPECT_EQ(namesOf(m).size(), m.size()) << which;
    for (const auto& c : m) {
      EXPECT_FALSE(c.name.empty());
      EXPECT_EQ(c.name.find(','), std::string::npos) << "names go into CSV cells unquoted: " << c.name;
      EXPECT_TRUE(c.leafOn || c.leafOff) << c.name;
    }
  }
  EXPECT_THROW(conditionMatrix("huge"), OptionsError);
}

TEST(ConditionMatrix, FullMatrixCoversEveryFactor) {
  auto m = fullMatrix();
  // The former setting is one row, unchanged.
  const ScanCondition& ref = byName(m, "reference");
  const ScanCondition former = referenceCondition();
  EXPECT_EQ(ref.pattern, "sphere");
  EXPECT_EQ(ref.targetPoints, 160000u);
  EXPECT_EQ(ref.sphereJitterDeg, 0.0);
  EXPECT_EQ(ref.targetPoints, former.targetPoints);
  EXPECT_TRUE(ref.leafOn && ref.leafOff);

  std::set<int> stations, subdivisions;
  std::set<double> steps, noise;
  std::uint64_t woodMin = UINT64_MAX, woodMax = 0;
  bool leafOn = false, leafOff = false;
  for (const auto& c : m) {
    leafOn |= c.leafOn;
    leafOff |= c.leafOff;
    EXPECT_TRUE(c.leafOff) << c.name << ": every row runs leaf-off";
    if (c.pattern == "tls") {
      stations.insert(c.stations);
      steps.insert(c.stepDeg);
      noise.insert(c.rangeNoiseMm);
      EXPECT_EQ(c.stationHeightM, 1.5) << c.name << ": a person's height";
      EXPECT_EQ(c.stationHeightDiagonal, 0.0) << c.name;
      EXPECT_EQ(c.rangeNoiseDiagonal, 0.0) << c.name;
      EXPECT_GT(c.stepDeg, 0.0) << c.name;
      // One factor at a time around the base.
      int differs = (c.stations != 4) + (c.stepDeg != 0.2) + (c.rangeNoiseMm != 5.0) + (c.terrainSlopeDeg >= 0);
      EXPECT_LE(differs, 1) << c.name;
      EXPECT_EQ(differs == 0, c.factor == "base") << c.name;
    } else {
      ASSERT_EQ(c.pattern, "sphere") << c.name;
      if (c.sphereSubdivisions > 0) {
        subdivisions.insert(c.sphereSubdivisions);
        EXPECT_NEAR(c.sphereJitterDeg, 1.0, 0.5) << c.name << ": the thesis's narrow jitter";
        EXPECT_EQ(c.targetPoints + c.targetWoodPoints, 0u) << c.name << ": no point-count scaling";
        EXPECT_EQ(c.factor, "sphere rays");
      }
      if (c.targetWoodPoints > 0) {
        woodMin = std::min(woodMin, c.targetWoodPoints);
        woodMax = std::max(woodMax, c.targetWoodPoints);
        EXPECT_EQ(c.factor, "wood points");
      }
    }
  }
  EXPECT_EQ(stations, (std::set<int>{1, 2, 4, 8}));
  EXPECT_EQ(*steps.begin(), 0.1);
  EXPECT_EQ(*steps.rbegin(), 0.5);
  EXPECT_EQ(*noise.begin(), 0.0);
  EXPECT_EQ(*noise.rbegin(), 25.0);  // a mobile scanner's
  EXPECT_EQ(noise.count(10.0), 1u);
  EXPECT_GE(noise.size(), 3u);
  EXPECT_EQ(subdivisions, (std::set<int>{6, 7, 8}));
  EXPECT_LE(woodMin, 5000u);
  EXPECT_GE(woodMax, 1000000u);
  EXPECT_TRUE(leafOn && leafOff);
  // Exactly the one-station row is judged on backward error only.
  for (const auto& c : m) EXPECT_EQ(c.backwardOnly(), c.name == "tls-1-station") << c.name;
}

TEST(ConditionMatrix, QuickIsASubsetOfFull) {
  auto full = fullMatrix();
  auto quick = quickMatrix();
  bool leafOn = false, backwardOnly = false;
  std::set<std::string> factors;
  for (const auto& q : quick) {
    const ScanCondition& f = byName(full, q.name);
    EXPECT_EQ(describeCondition(q), describeCondition(f)) << q.name << ": same settings as the full row";
    EXPECT_TRUE(!q.leafOn || f.leafOn) << q.name;
    EXPECT_TRUE(!q.leafOff || f.leafOff) << q.name;
    leafOn |= q.leafOn;
    backwardOnly |= q.backwardOnly();
    factors.insert(q.factor);
  }
  EXPECT_TRUE(leafOn);
  EXPECT_TRUE(backwardOnly);
  EXPECT_GE(factors.size(), 4u);
}

TEST(ConditionMatrix, SelectsConditionsByName) {
  auto m = selectConditions(fullMatrix(), {"wood-5k", "reference"});
  ASSERT_EQ(m.size(), 2u);
  EXPECT_EQ(m[0].name, "reference");  // the matrix's order
  EXPECT_EQ(m[1].name, "wood-5k");
  try {
    selectConditions(fullMatrix(), {"reference", "nope"});
    FAIL() << "expected OptionsError";
  } catch (const OptionsError& e) {
    EXPECT_NE(std::string(e.what()).find("nope"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("tls-base"), std::string::npos) << "lists the known names";
  }
  std::string table = conditionTable(fullMatrix());
  for (const auto& c : fullMatrix()) EXPECT_NE(table.find("| " + c.name + " |"), std::string::npos) << c.name;
}

TEST(ConditionMatrix, ConvertsPhysicalUnitsWithTheTreeScale) {
  EXPECT_DOUBLE_EQ(mmToUnits(5.0, kEzTreeMetresPerUnit), 0.05);  // decimetres
  EXPECT_DOUBLE_EQ(mmToUnits(5.0, 1.0), 0.005);                  // metres
  EXPECT_DOUBLE_EQ(metresToUnits(1.5, kEzTreeMetresPerUnit), 15.0);
  EXPECT_DOUBLE_EQ(mmToUnits(0.0, 0.1), 0.0);
  EXPECT_THROW(mmToUnits(1.0, 0.0), OptionsError);
  EXPECT_THROW(metresToUnits(1.0, -1.0), OptionsError);
  EXPECT_THROW(metresToUnits(1.0, NAN), OptionsError);

  // End to end: a wall scanned by one station with 10 mm range noise. Its points scatter about
  // the wall by the noise in scene units: 0.1 at 0.1 m per unit, 0.01 at 1 m per unit.
  TreeCase wall;
  wall.name = "wall";
  wall.branches.vertices = {{-5, 0, 0}, {5, 0, 0}, {5, 10, 0}, {-5, 10, 0}};
  wall.branches.triangles = {{0, 1, 2}, {0, 2, 3}};
  wall.axes.push_back({});
  wall.axes[0].points = {{0, 0, 0}, {0, 10, 0}};
  wall.axes[0].parent = -1;
  ScanCondition c = byName(fullMatrix(), "tls-1-station");
  c.rangeNoiseMm = 10.0;
  c.stepDeg = 0.5;
  for (double mpu : {0.1, 1.0}) {
    wall.metresPerUnit = mpu;
    TreeScan s = scanTree(wall, c, false, 3);
    ASSERT_GT(s.cloud.size(), 1000u);
    EXPECT_EQ(s.stepDeg, 0.5);
    EXPECT_GT(s.rays, s.cloud.size());
    double sum = 0, sum2 = 0;
    for (const auto& p : s.cloud.positions) {
      sum += p.z();
      sum2 += p.z() * p.z();
    }
    double n = static_cast<double>(s.cloud.size());
    double sd = std::sqrt(std::max(sum2 / n - (sum / n) * (sum / n), 0.0));
    double sigma = mmToUnits(10.0, mpu);
    // Rays meet the wall within ~35° of its normal: the spread along z is sigma * cos(angle).
    EXPECT_GT(sd, 0.75 * sigma) << mpu;
    EXPECT_LT(sd, 1.1 * sigma) << mpu;
  }
}

TEST(TreeSplit, DeveloperTreesSplitSevenAndSevenWithTheOriginalsInTuning) {
  const auto& tune = developerTuneTrees();
  const auto& held = developerHeldOutTrees();
  EXPECT_EQ(tune.size(), 7u);
  EXPECT_EQ(held.size(), 7u);
  std::set<std::string> all(tune.begin(), tune.end());
  for (const auto& h : held) EXPECT_TRUE(all.insert(h).second) << h << " is in both halves";
  EXPECT_EQ(all.size(), 14u);
  for (const char* original : {"aspen_medium_s101", "pine_medium_s13977", "oak_medium_s35729", "bush_2_s45590"})
    EXPECT_EQ(treeHalf(original), TreeHalf::Tune) << original;
  for (const auto& t : tune) EXPECT_EQ(treeHalf(t), TreeHalf::Tune) << t;
  for (const auto& h : held) EXPECT_EQ(treeHalf(h), TreeHalf::HeldOut) << h;
  // Every preset family is in both halves.
  for (const char* family : {"aspen", "pine", "oak", "bush", "ash"}) {
    auto has = [&](const std::vector<std::string>& l) {
      return std::any_of(l.begin(), l.end(), [&](const std::string& n) { return n.rfind(family, 0) == 0; });
    };
    EXPECT_TRUE(has(tune) && has(held)) << family;
  }
}

TEST(TreeSplit, CoversTheSharedTreeFolder) {
  auto dir = test::sharedDataDir() / "trees";
  if (!std::filesystem::exists(dir)) GTEST_SKIP() << "no " << dir;
  // Every tree of the folder falls in exactly one half; the documented 14 are all in the lists.
  std::set<std::string> listed(developerTuneTrees().begin(), developerTuneTrees().end());
  listed.insert(developerHeldOutTrees().begin(), developerHeldOutTrees().end());
  int tune = 0, held = 0, inLists = 0;
  for (const auto& e : std::filesystem::directory_iterator(dir)) {
    const std::string f = e.path().filename().string();
    const std::string suffix = ".branches.obj";
    if (f.size() <= suffix.size() || f.compare(f.size() - suffix.size(), suffix.size(), suffix) != 0) continue;
    std::string name = f.substr(0, f.size() - suffix.size());
    (treeHalf(name) == TreeHalf::Tune ? tune : held)++;
    inLists += listed.count(name) > 0;
    EXPECT_NE(splitSelects("tune", treeHalf(name)), splitSelects("held-out", treeHalf(name))) << name;
    EXPECT_TRUE(splitSelects("all", treeHalf(name)));
  }
  EXPECT_GT(tune, 0);
  EXPECT_GT(held, 0);
  if (inLists == 14) {
    EXPECT_EQ(tune, held);
  }
}

TEST(TreeSplit, OtherNamesGoByAStableHash) {
  // Deterministic, and both halves get a fair share of arbitrary names.
  int tune = 0;
  for (int i = 0; i < 200; ++i) {
    std::string name = "tree_" + std::to_string(i);
    TreeHalf h = treeHalf(name);
    EXPECT_EQ(h, treeHalf(name));
    tune += h == TreeHalf::Tune;
  }
  EXPECT_GT(tune, 70);
  EXPECT_LT(tune, 130);
  // The built-in trees the quick matrix runs on fall in different halves, so its report shows both.
  auto builtin = builtinTrees(2);
  EXPECT_NE(treeHalf(builtin[0].name), treeHalf(builtin[1].name));
  EXPECT_STREQ(halfName(TreeHalf::Tune), "tune");
  EXPECT_STREQ(halfName(TreeHalf::HeldOut), "held-out");
  EXPECT_THROW(splitSelects("half", TreeHalf::Tune), OptionsError);
}

}  // namespace
}  // namespace treesketch::eval
