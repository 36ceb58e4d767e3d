// The one tree model: its volume's range and its verdict.
#include "treesketch/model/tree_model.h"

#include <gtest/gtest.h>

#include <cmath>

#include "skeleton/synthetic_tree.h"

namespace treesketch::model {
namespace {

using geom::Vec3;

/// A model of one upright cylinder of `radius` from z = 0 to z = 4, in four pieces; `measured`
/// says whether its radii rest on fitted circles.
TreeModel stem(double radius, bool measured) {
  std::vector<geom::ModelNode> nodes(5);
  for (int i = 0; i < 5; ++i) {
    nodes[i].position = Vec3(0, 0, i);
    nodes[i].radius = radius;
    nodes[i].parent = i - 1;
    nodes[i].branchOrder = 0;
  }
  TreeModel m;
  m.cylinders = geom::cylinderModelFromNodes(nodes);
  m.measured.assign(m.cylinders.size(), measured ? 1 : 0);
  m.up = geom::UpAxis::Z;
  return m;
}

geom::PointCloud stemScan(double radius) {
  return test::sampleCylinders({{Vec3(0, 0, 0), Vec3(0, 0, 4), radius, -1}}, 0.01, 0.002, 3);
}

TEST(TreeModel, AModelOnItsPointsIsTrustedWithANarrowRange) {
  const geom::PointCloud cloud = stemScan(0.1);
  const ModelMeasures m = measure(stem(0.1, true), cloud);
  EXPECT_EQ(m.verdict.level, Verdict::Level::Trusted) << m.verdictLine();
  EXPECT_DOUBLE_EQ(m.measuredVolumeShare, 1.0);
  EXPECT_NEAR(m.volumeLow / m.figures.volume, 0.81, 1e-9);
  EXPECT_NEAR(m.volumeHigh / m.figures.volume, 1.21, 1e-9);
  EXPECT_NEAR(m.formFactor, 1.0, 0.05);  // a cylinder: its own DBH and height
  const nlohmann::json report = reportJson(m, nlohmann::json::object());
  EXPECT_EQ(report["verdict"]["level"], "trusted");
  EXPECT_EQ(report["model"]["volumeRangeM3"].size(), 2u);
}

TEST(TreeModel, TubesThickerThanThePointsAreNotTrustedAndSaySo) {
  const geom::PointCloud cloud = stemScan(0.05);
  const ModelMeasures m = measure(stem(0.2, true), cloud);  // 4× the points' radius
  EXPECT_EQ(m.verdict.level, Verdict::Level::NotTrusted);
  ASSERT_FALSE(m.verdict.reasons.empty());
  EXPECT_NE(m.verdict.reasons.front().find("deeper than 2 cm inside"), std::string::npos) << m.verdictLine();
  EXPECT_NE(m.verdictLine().find("--leaf-on"), std::string::npos);  // the advice for a leaf-off run
  MeasureOptions leafOn;
  leafOn.leafOn = true;
  EXPECT_EQ(measure(stem(0.2, true), cloud, leafOn).verdictLine().find("--leaf-on"), std::string::npos);
}

TEST(TreeModel, AModelOfEveryPointOfATreeInLeafIsNeverTrustedForItsVolume) {
  // A model that explains its points well, made with --leaf-on from every point: its tubes may run
  // through the foliage, and nothing in its fit tells them from wood. Made from the wood only, the
  // same model keeps the wood-only reason instead.
  const geom::PointCloud cloud = stemScan(0.05);
  MeasureOptions leafOn;
  leafOn.leafOn = true;
  const ModelMeasures every = measure(stem(0.05, true), cloud, leafOn);
  EXPECT_GE(every.verdict.level, Verdict::Level::Uncertain);
  EXPECT_NE(every.verdictLine().find("through the foliage"), std::string::npos) << every.verdictLine();
  EXPECT_NE(every.verdictLine().find("--wood-only"), std::string::npos) << every.verdictLine();
  leafOn.woodOnly = true;
  EXPECT_EQ(measure(stem(0.05, true), cloud, leafOn).verdictLine().find("through the foliage"), std::string::npos);
}

TEST(TreeModel, AModelOnPointsDrawnTogetherIsNeverTrustedForItsVolume) {
  // A scan whose noise blurs its branches at the voxel's scale is modelled on its points drawn
  // together: its thin branches' radii are the pipe model's, whatever the fit says. (A 4-station
  // scan of a synthetic oak under 25 mm of noise, 39 % over its wood, was called trusted.)
  const geom::PointCloud cloud = stemScan(0.05);
  MeasureOptions drawn;
  drawn.noise = 0.02;
  const ModelMeasures own = measure(stem(0.05, true), cloud, drawn);
  EXPECT_EQ(own.verdictLine().find("drawn together"), std::string::npos) << own.verdictLine();
  drawn.contraction = 0.04;
  const ModelMeasures m = measure(stem(0.05, true), cloud, drawn);
  EXPECT_GE(m.verdict.level, Verdict::Level::Uncertain);
  EXPECT_NE(m.verdictLine().find("drawn together by 40.0 mm"), std::string::npos) << m.verdictLine();
  EXPECT_NEAR(m.contractionMetres, 0.04, 1e-12);
}

TEST(TreeModel, AModelThatStopsWellBelowTheCloudsTopSaysSo) {
  // A drone scan of a 25 m tree in leaf: its wood-only model stopped at 12 m, where the
  // classification called the sparse upper stem leaf, and its volume was called uncertain only for
  // being the wood's lower figure. The cloud here goes on 4 m above the model's 4 m stem.
  geom::PointCloud tall = test::sampleCylinders({{Vec3(0, 0, 0), Vec3(0, 0, 8), 0.1, -1}}, 0.01, 0.002, 3);
  const ModelMeasures every = measure(stem(0.1, true), tall);
  EXPECT_EQ(every.verdict.level, Verdict::Level::NotTrusted) << every.verdictLine();
  EXPECT_NE(every.verdictLine().find("reaches 4.0 m of the cloud's 8.0 m"), std::string::npos) << every.verdictLine();
  MeasureOptions wood;
  wood.leafOn = wood.woodOnly = true;
  const ModelMeasures woodOnly = measure(stem(0.1, true), tall, wood);
  EXPECT_NE(woodOnly.verdictLine().find("the classification calls it leaf"), std::string::npos)
      << woodOnly.verdictLine();
  // A crown's outer twigs and leaves a little above the model's top are a tree's own.
  const geom::PointCloud near = test::sampleCylinders({{Vec3(0, 0, 0), Vec3(0, 0, 4.8), 0.1, -1}}, 0.01, 0.002, 3);
  EXPECT_EQ(measure(stem(0.1, true), near).verdictLine().find("reaches"), std::string::npos);
}

TEST(TreeModel, AWoodOnlyModelsRangeReachesUpToTheModelOfEveryPoint) {
  // The points the classification calls leaf may hold wood: on the synthetic trees in leaf the
  // wood-only model's own range held the true volume in 64 of 98 scans, with the volume of a model
  // of every point as its upper end in 90.
  const geom::PointCloud cloud = stemScan(0.1);
  MeasureOptions wood;
  wood.leafOn = wood.woodOnly = true;
  const ModelMeasures own = measure(stem(0.1, true), cloud, wood);
  EXPECT_EQ(own.verdictLine().find("every point"), std::string::npos) << own.verdictLine();
  wood.everyPointVolume = 3.0 * own.figures.volume;  // cloud units³; here 1 unit = 1 m
  const ModelMeasures every = measure(stem(0.1, true), cloud, wood);
  EXPECT_NEAR(every.volumeHigh, 3.0 * own.figures.volume, 1e-12);
  EXPECT_NEAR(every.volumeLow, own.volumeLow, 1e-12);
  EXPECT_NE(every.verdictLine().find("the range's upper end"), std::string::npos) << every.verdictLine();
  wood.everyPointVolume = 0.5 * own.figures.volume;  // below the range's own upper end: it stays
  const ModelMeasures less = measure(stem(0.1, true), cloud, wood);
  EXPECT_NEAR(less.volumeHigh, own.volumeHigh, 1e-12);
  EXPECT_EQ(less.verdictLine().find("the range's upper end"), std::string::npos) << less.verdictLine();
  wood.woodOnly = false;  // a model of every point has no such ceiling
  wood.everyPointVolume = 3.0 * own.figures.volume;
  EXPECT_NEAR(measure(stem(0.1, true), cloud, wood).volumeHigh, own.volumeHigh, 1e-12);
}

TEST(TreeModel, AModelOfEveryPointInLeafHasARangeDownToItsClassifiedWood) {
  // Every point of a tree in leaf modelled takes the foliage for wood: 2–11 times the trees' wood on
  // the synthetic scans. The range's lower end goes down to the model of the points classified as
  // wood (on those scans the range then held the truth in 94 of 98, 82 without).
  const geom::PointCloud cloud = stemScan(0.1);
  MeasureOptions leafOn;
  leafOn.leafOn = true;
  const ModelMeasures own = measure(stem(0.1, true), cloud, leafOn);
  leafOn.classifiedWoodVolume = 0.2 * own.figures.volume;  // cloud units³; here 1 unit = 1 m
  const ModelMeasures floor = measure(stem(0.1, true), cloud, leafOn);
  EXPECT_NEAR(floor.volumeLow, 0.2 * own.figures.volume, 1e-12);
  EXPECT_NEAR(floor.volumeHigh, own.volumeHigh, 1e-12);
  EXPECT_NE(floor.verdictLine().find("the range's lower end"), std::string::npos) << floor.verdictLine();
  leafOn.classifiedWoodVolume = 0.95 * own.figures.volume;  // above the range's own lower end: it stays
  const ModelMeasures above = measure(stem(0.1, true), cloud, leafOn);
  EXPECT_NEAR(above.volumeLow, own.volumeLow, 1e-12);
  EXPECT_NE(above.verdictLine().find("classified as wood holds"), std::string::npos) << above.verdictLine();
  EXPECT_EQ(above.verdictLine().find("the range's lower end"), std::string::npos) << above.verdictLine();
  leafOn.woodOnly = true;  // a model of the wood itself has no such floor
  leafOn.classifiedWoodVolume = 0.2 * own.figures.volume;
  EXPECT_NEAR(measure(stem(0.1, true), cloud, leafOn).volumeLow, own.volumeLow, 1e-12);
}

TEST(TreeModel, AStemThatDisagreesWithThePointsAtBreastHeightIsNamed) {
  const geom::PointCloud cloud = stemScan(0.1);
  const ModelMeasures thin = measure(stem(0.08, true), cloud);  // a DBH 20 % under the points' circle
  ASSERT_TRUE(thin.metrics.cloudDbh.ok) << thin.metrics.cloudDbh.reason;
  EXPECT_NEAR(thin.metrics.cloudDbh.diameter, 0.2, 0.01);
  EXPECT_GE(thin.verdict.level, Verdict::Level::Uncertain);
  EXPECT_NE(thin.verdictLine().find("at breast height"), std::string::npos) << thin.verdictLine();
  const ModelMeasures close = measure(stem(0.092, true), cloud);  // 8 % under: within the two spreads
  EXPECT_EQ(close.verdictLine().find("at breast height"), std::string::npos) << close.verdictLine();
}

TEST(TreeModel, TheScansNoiseLowersTheRangeOfMeasuredRadiiInQuadrature) {
  const geom::PointCloud cloud = stemScan(0.1);
  MeasureOptions noisy;
  noisy.noise = 0.03;  // 3 cm: the radius may be √(0.1² − 0.06²) = 0.08, less its 10 %
  const ModelMeasures m = measure(stem(0.1, true), cloud, noisy);
  EXPECT_NEAR(m.volumeLow / m.figures.volume, 0.8 * 0.8 * 0.81, 1e-9);
  EXPECT_NEAR(m.volumeHigh / m.figures.volume, 1.21, 1e-9);  // noise thickens a circle, never thins it
  noisy.noise = 0.06;  // a tube under two noises thick may be the noise's own blob
  EXPECT_NEAR(measure(stem(0.1, true), cloud, noisy).volumeLow, 0.0, 1e-12);
  // Inferred radii take the same allowance before their own factor: under two noises, nothing.
  EXPECT_NEAR(measure(stem(0.1, false), cloud, noisy).volumeLow, 0.0, 1e-12);
  noisy.noise = 0.03;
  EXPECT_NEAR(measure(stem(0.1, false), cloud, noisy).volumeLow / m.figures.volume, 0.64 * 4.0 / 9.0, 1e-9);
  noisy.noise = -1;  // unknown noise: their own factor alone
  EXPECT_NEAR(measure(stem(0.1, false), cloud, noisy).volumeLow / m.figures.volume, 4.0 / 9.0, 1e-9);
}

TEST(TreeModel, ARadiusUnderOneAndAHalfRangeNoisesIsNotMeasured) {
  // An automatic model of a 10 cm stem and a 1 cm twig, both on fitted circles: under 10 mm of
  // range noise the twig's points are a blob the circle took its shape from, so its radius counts
  // as inferred; the stem's stays measured. Without a reading of the noise both stay measured.
  skeleton::AutoSkeletonResult r;
  for (int i = 0; i < 6; ++i) {
    skeleton::SkeletonNode n;
    n.position = i < 3 ? Vec3(0, 0, i) : Vec3(i - 2, 0, 2);
    n.radius = i < 3 ? 0.1 : 0.01;
    n.parent = i - 1;
    n.branchOrder = i < 3 ? 0 : 1;
    r.model.push_back(n);
  }
  r.radiusMeasured.assign(r.model.size(), 1);
  const TreeModel clean = fromAutoSkeleton(r, geom::UpAxis::Z);
  for (char m : clean.measured) EXPECT_TRUE(m);
  r.rangeNoise = 0.01;
  const TreeModel noisy = fromAutoSkeleton(r, geom::UpAxis::Z);
  ASSERT_EQ(noisy.measured.size(), 5u);
  EXPECT_TRUE(noisy.measured[0] && noisy.measured[1]);
  for (std::size_t i = 3; i < 5; ++i) EXPECT_FALSE(noisy.measured[i]) << i;
  r.rangeNoise = 0.005;  // the twig is two noises thick: measured again
  for (char m : fromAutoSkeleton(r, geom::UpAxis::Z).measured) EXPECT_TRUE(m);
}

TEST(TreeModel, InferredRadiiWidenTheRangeAndAreNamed) {
  const geom::PointCloud cloud = stemScan(0.1);
  const ModelMeasures m = measure(stem(0.1, false), cloud);
  EXPECT_DOUBLE_EQ(m.measuredVolumeShare, 0.0);
  EXPECT_NEAR(m.volumeLow / m.figures.volume, 4.0 / 9.0, 1e-9);
  EXPECT_NEAR(m.volumeHigh / m.figures.volume, 2.25, 1e-9);
  EXPECT_EQ(m.verdict.level, Verdict::Level::Uncertain);
  EXPECT_NE(m.verdictLine().find("pipe model"), std::string::npos) << m.verdictLine();
}

TEST(TreeModel, TheMeasuredNoiseIsReportedInMetres) {
  const geom::PointCloud cloud = stemScan(0.1);
  MeasureOptions o;
  o.unitMetres = 0.001;  // a cloud in millimetres
  EXPECT_FALSE(std::isfinite(measure(stem(100, true), cloud, o).noiseMetres));  // not measured: not reported
  o.noise = 3.5;
  const ModelMeasures m = measure(stem(100, true), cloud, o);
  EXPECT_DOUBLE_EQ(m.noiseMetres, 0.0035);
  EXPECT_NE(m.summary().find("scan noise 3.5 mm"), std::string::npos) << m.summary();
  EXPECT_DOUBLE_EQ(reportJson(m, nlohmann::json::object())["model"]["noiseM"].get<double>(), 0.0035);
}

TEST(TreeModel, ASparseCloudIsNamed) {
  geom::PointCloud few;
  for (int i = 0; i < 40; ++i) few.positions.emplace_back(0.1 * std::cos(i), 0.1 * std::sin(i), 0.1 * i);
  const ModelMeasures m = measure(stem(0.1, true), few);
  EXPECT_NE(m.verdictLine().find("points per metre"), std::string::npos) << m.verdictLine();
}

}  // namespace
}  // namespace treesketch::model
