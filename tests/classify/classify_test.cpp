// The whole stage with the built-in model, on a leaf-on scan of a tree from the project's own
// generator (not the ez-tree trees the model was trained on): the scanner's labels are the truth.
#include "treesketch/classify/classify.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "leaf_on_scan.h"
#include "treesketch/accel/ray_scene.h"
#include "treesketch/gen/tree_generator.h"
#include "treesketch/scan/sphere_scan.h"
#include "treesketch/util/error.h"

namespace treesketch::classify {
namespace {

using test::leafOnScan;

TEST(Classify, BuiltInModelSeparatesWoodFromLeavesOnAnotherGeneratorsTree) {
  const BoostedTrees& m = trainedModel();
  ASSERT_FALSE(m.empty());
  EXPECT_EQ(m.featureNames, featureNames(FeatureOptions{}));
  const geom::PointCloud cloud = leafOnScan();
  const Classification c = classifyWood(cloud, geom::UpAxis::Y);
  ASSERT_EQ(c.wood.size(), cloud.size());
  ASSERT_EQ(c.woodProbability.size(), cloud.size());
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    ASSERT_GE(c.woodProbability[i], 0.0f);
    ASSERT_LE(c.woodProbability[i], 1.0f);
  }
  const test::WoodCounts n = test::woodCounts(cloud, c.wood);
  const std::size_t tp = n.truePositives, fp = n.falsePositives, fn = n.falseNegatives;
  const double f1 = 2.0 * tp / (2.0 * tp + fp + fn);
  EXPECT_GT(f1, 0.8) << "tp " << tp << " fp " << fp << " fn " << fn;
  EXPECT_EQ(c.woodPoints, tp + fp);
  // The graph step only demotes: wood after it is a subset of the classifier's wood.
  for (std::size_t i = 0; i < cloud.size(); ++i)
    if (c.wood[i]) ASSERT_GE(c.woodProbability[i], c.threshold);
  const std::vector<std::uint8_t> codes = classCodes(c);
  for (std::size_t i = 0; i < cloud.size(); ++i) ASSERT_EQ(codes[i], c.wood[i] ? kWoodClass : kLeafClass);
}

TEST(Classify, BlockedPredictionGivesEveryRowsOwnProbability) {
  // predictWood walks the trees over blocks of rows; each row must get exactly what the model
  // gives it alone. 700 points: blocks of 256 and a partial block.
  geom::PointCloud cloud;
  for (int i = 0; i < 700; ++i)
    cloud.positions.emplace_back(0.3 * std::sin(0.05 * i) + 0.001 * (i % 3), 0.01 * i, 0.3 * std::cos(0.07 * i));
  const BoostedTrees& m = trainedModel();
  FeatureOptions o = featureOptionsFor(m);
  o.coreSpacings = 0;
  const FeatureTable f = computeFeatures(cloud, geom::UpAxis::Y, o);
  const std::vector<float> p = predictWood(f, m);
  ASSERT_EQ(p.size(), f.points());
  float lo = 1, hi = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    ASSERT_EQ(p[i], static_cast<float>(m.probability(f.row(i)))) << "row " << i;
    lo = std::min(lo, p[i]);
    hi = std::max(hi, p[i]);
  }
  EXPECT_LT(lo, hi);  // the rows differ, so a row given another's answer would show
}

TEST(Classify, AModelTrainedWithoutTheNormalsTurnIsStillRead) {
  // A model trained with --no-normal-features (or before they existed) names no normal_fan_*
  // column: the stage computes the features it was trained on, and the prediction runs.
  FeatureOptions without;
  without.normalFeatures = false;
  BoostedTrees m;
  m.featureNames = featureNames(without);
  m.trees = {{TreeNode{}}};
  const FeatureOptions chosen = featureOptionsFor(m);
  EXPECT_FALSE(chosen.normalFeatures);
  EXPECT_TRUE(chosen.graphFeatures);
  EXPECT_TRUE(chosen.positionFeatures);
  EXPECT_TRUE(featureOptionsFor(trainedModel()).normalFeatures);
  geom::PointCloud cloud;
  for (int i = 0; i < 200; ++i) cloud.positions.emplace_back(0.01 * i, 0.02 * (i % 7), 0.001 * (i % 5));
  const Classification c = classifyWood(cloud, geom::UpAxis::Y, {}, &m);
  EXPECT_EQ(c.wood.size(), cloud.size());
}

TEST(Classify, ModelOfOtherFeaturesIsRefused) {
  BoostedTrees other;
  other.featureNames = {"a"};
  other.trees = {{TreeNode{}}};
  geom::PointCloud cloud;
  for (int i = 0; i < 200; ++i) cloud.positions.emplace_back(0.01 * i, 0.02 * (i % 7), 0.0);
  EXPECT_THROW(classifyWood(cloud, geom::UpAxis::Y, {}, &other), OptionsError);
}

}  // namespace
}  // namespace treesketch::classify
