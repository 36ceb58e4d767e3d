#include "treesketch/util/non_increasing_fit.h"

#include <gtest/gtest.h>

namespace treesketch::util {
namespace {

TEST(NonIncreasingFit, ARiseIsPooledIntoItsWeightedMean) {
  std::vector<double> v = {5, 3, 4, 1};
  nonIncreasingFit(v, {1, 1, 3, 1});
  // 3 and 4 rise: pooled to (3·1 + 4·3) / 4 = 3.75.
  EXPECT_EQ(v, (std::vector<double>{5, 3.75, 3.75, 1}));
}

TEST(NonIncreasingFit, ANonIncreasingSequenceIsLeftAsItIs) {
  std::vector<double> v = {4, 4, 2, 0.5};
  nonIncreasingFit(v, {1, 2, 1, 1});
  EXPECT_EQ(v, (std::vector<double>{4, 4, 2, 0.5}));
  std::vector<double> empty;
  nonIncreasingFit(empty, {});
  EXPECT_TRUE(empty.empty());
}

TEST(NonIncreasingFit, AWideValueAtTheTipLowersWhatPrecedesIt) {
  std::vector<double> v = {1, 1, 4};
  nonIncreasingFit(v, {1, 1, 1});
  EXPECT_EQ(v, (std::vector<double>{2, 2, 2}));
}

}  // namespace
}  // namespace treesketch::util
