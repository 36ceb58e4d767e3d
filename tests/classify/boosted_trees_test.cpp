// The boosted-tree learner: it learns a rule no single threshold gives, its JSON gives the same
// answers back, and malformed models and training sets are refused.
#include "treesketch/classify/boosted_trees.h"

#include <gtest/gtest.h>

#include <random>

#include "treesketch/util/error.h"

namespace treesketch::classify {
namespace {

// Label: inside a ring (0.3 < |x| < 0.7), a third feature is noise.
void ringData(std::size_t n, unsigned seed, std::vector<float>& rows, std::vector<std::uint8_t>& labels) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  for (std::size_t i = 0; i < n; ++i) {
    const float x = u(rng), y = u(rng), z = u(rng);
    const float r = std::sqrt(x * x + y * y);
    rows.insert(rows.end(), {x, y, z});
    labels.push_back(r > 0.3f && r < 0.7f);
  }
}

TEST(BoostedTrees, LearnsARingAndRoundTripsThroughJson) {
  std::vector<float> rows, testRows;
  std::vector<std::uint8_t> labels, testLabels;
  ringData(20000, 1, rows, labels);
  ringData(5000, 2, testRows, testLabels);
  BoostOptions o;
  o.rounds = 80;
  o.depth = 4;
  const BoostedTrees m = trainBoostedTrees(rows, {"x", "y", "z"}, labels, {}, o);
  ASSERT_EQ(m.trees.size(), 80u);
  std::size_t right = 0;
  for (std::size_t i = 0; i < testLabels.size(); ++i)
    right += (m.probability(&testRows[3 * i]) >= 0.5) == testLabels[i];
  EXPECT_GT(static_cast<double>(right) / testLabels.size(), 0.9);
  const BoostedTrees back = boostedTreesFromJson(toJson(m), "test");
  EXPECT_EQ(back.featureNames, m.featureNames);
  for (std::size_t i = 0; i < 200; ++i) EXPECT_NEAR(back.logit(&testRows[3 * i]), m.logit(&testRows[3 * i]), 1e-5);
}

TEST(BoostedTrees, WeightsMoveTheBias) {
  std::vector<float> rows;
  std::vector<std::uint8_t> labels;
  ringData(4000, 3, rows, labels);
  BoostOptions o;
  o.rounds = 1;
  std::vector<float> heavy(labels.size());
  for (std::size_t i = 0; i < labels.size(); ++i) heavy[i] = labels[i] ? 10.0f : 1.0f;
  EXPECT_GT(trainBoostedTrees(rows, {"x", "y", "z"}, labels, heavy, o).bias,
            trainBoostedTrees(rows, {"x", "y", "z"}, labels, {}, o).bias + 1.0);
}

TEST(BoostedTrees, BadInputIsRefused) {
  std::vector<float> rows = {0, 1, 2, 3};
  EXPECT_THROW(trainBoostedTrees(rows, {"a"}, {1, 1, 1, 1}, {}), OptionsError);  // one class
  EXPECT_THROW(trainBoostedTrees(rows, {"a"}, {1, 0}, {}), OptionsError);        // sizes
  EXPECT_THROW(boostedTreesFromJson("{", "m.json"), InputError);
  try {
    boostedTreesFromJson(R"({"features":["a"],"bias":0,"threshold":0.5,"trees":[[[0,0.5,0,2],[1.0],[2.0]]]})",
                         "m.json");
    FAIL() << "a node pointing at itself was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("m.json"), std::string::npos) << e.what();
  }
  EXPECT_THROW(
      boostedTreesFromJson(R"({"features":["a"],"bias":0,"threshold":0.5,"trees":[[[3,0.5,1,2],[1.0],[2.0]]]})", "m"),
      InputError);  // feature out of range
}

}  // namespace
}  // namespace treesketch::classify
