#include "treesketch/util/non_increasing_fit.h"

#include <gtest/gtest.h>

namespace treesketch::util {
namespace {

TEST(NonIncreasingFit, ARiseIsPooledAtItsWeightedMedian) {
  std::vector<double> v = {5, 3, 4, 1};
  nonIncreasingFit(v, {1, 1, 3, 1});
  // 3 and 4 rise: pooled at their weighted median, 4 (weight 3 of 4; the mean would be 3.75).
  EXPECT_EQ(v, (std::vector<double>{5, 4, 4, 1}));
}

TEST(NonIncreasingFit, ANonIncreasingSequenceIsLeftAsItIs) {
  std::vector<double> v = {4, 4, 2, 0.5};
  nonIncreasingFit(v, {1, 2, 1, 1});
  EXPECT_EQ(v, (std::vector<double>{4, 4, 2, 0.5}));
  std::vector<double> empty;
  nonIncreasingFit(empty, {});
  EXPECT_TRUE(empty.empty());
}

TEST(NonIncreasingFit, AWideValueAtTheTipIsOutvoted) {
  std::vector<double> v = {1, 1, 4};
  nonIncreasingFit(v, {1, 1, 1});
  EXPECT_EQ(v, (std::vector<double>{1, 1, 1}));  // the mean would have raised all three to 2
}

}  // namespace
}  // namespace treesketch::util
