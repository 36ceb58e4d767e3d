#include "treesketch/accel/point_index.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

#include "treesketch/util/error.h"

namespace treesketch::accel {
namespace {

using geom::Vec3;

// Clustered points (a few dense blobs and a sparse background, some exact duplicates) so that
// balls hold anything from none to hundreds of points.
std::vector<Vec3> randomPoints(std::mt19937_64& rng, std::size_t n) {
  std::uniform_real_distribution<double> uni(-1.0, 1.0);
  std::normal_distribution<double> gauss(0.0, 0.05);
  std::vector<Vec3> pts;
  const Vec3 centres[3] = {Vec3(0.3, 0.2, -0.1), Vec3(-0.5, 0.4, 0.6), Vec3(0.1, -0.7, 0.2)};
  for (std::size_t i = 0; i < n; ++i) {
    if (i % 4 == 0) {
      pts.emplace_back(uni(rng), uni(rng), uni(rng));
    } else {
      const Vec3& c = centres[i % 3];
      pts.push_back(c + Vec3(gauss(rng), gauss(rng), gauss(rng)));
    }
    if (i % 50 == 0 && !pts.empty()) pts.push_back(pts.front());  // duplicates
  }
  return pts;
}

std::vector<std::uint32_t> bruteBall(const std::vector<Vec3>& pts, const Vec3& c, double r) {
  std::vector<std::uint32_t> out;
  for (std::size_t i = 0; i < pts.size(); ++i)
    if ((pts[i] - c).squaredNorm() < r * r) out.push_back(static_cast<std::uint32_t>(i));
  return out;
}

class PointIndexLeaves : public ::testing::TestWithParam<std::size_t> {};

// Every leaf size: one point a leaf (every node cut by some ball), a few, the default.
INSTANTIATE_TEST_SUITE_P(LeafSizes, PointIndexLeaves, ::testing::Values(1, 3, 16, PointIndexOptions{}.leafSize));

TEST_P(PointIndexLeaves, BallQueriesEqualABruteForceScan) {
  std::mt19937_64 rng(5);
  const auto pts = randomPoints(rng, 3000);
  const PointIndex index(pts, PointIndexOptions{GetParam()});
  ASSERT_EQ(index.size(), pts.size());
  for (std::uint32_t i = 0; i < pts.size(); i += 97) EXPECT_EQ(index.point(i), pts[i]);
  std::uniform_real_distribution<double> uni(-1.1, 1.1), rad(0.0, 0.4);
  std::vector<std::uint32_t> got;
  std::size_t nonEmpty = 0;
  for (int q = 0; q < 300; ++q) {
    // Half the queries centred on a point of the set (its own distance 0 is inside any ball).
    const Vec3 c = q % 2 ? pts[rng() % pts.size()] : Vec3(uni(rng), uni(rng), uni(rng));
    const double r = rad(rng);
    index.withinRadius(c, r, got);
    const auto expected = bruteBall(pts, c, r);
    EXPECT_EQ(got, expected) << "query " << q;  // the same indices, increasing
    nonEmpty += !expected.empty();
  }
  EXPECT_GT(nonEmpty, 200u);  // the test exercises real answers
}

TEST(PointIndex, BallIsOpenAtItsBoundary) {
  // Points exactly at distance 1 from the centre (in binary) are outside the open ball.
  const std::vector<Vec3> pts = {Vec3(1, 0, 0), Vec3(0, -1, 0), Vec3(0.5, 0, 0), Vec3(0, 0, 1.0000001)};
  const PointIndex index(pts);
  EXPECT_EQ(index.withinRadius(Vec3::Zero(), 1.0), (std::vector<std::uint32_t>{2}));
  EXPECT_EQ(index.withinRadius(Vec3::Zero(), std::nextafter(1.0, 2.0)), (std::vector<std::uint32_t>{0, 1, 2}));
  EXPECT_TRUE(index.withinRadius(Vec3::Zero(), 0.0).empty());
}

TEST(PointIndex, BallByDistanceIsSortedNearestFirstWithIndexTies) {
  std::mt19937_64 rng(9);
  auto pts = randomPoints(rng, 1500);
  // Exact ties: the same offset from the query in three directions.
  const Vec3 c(0.05, 0.05, 0.05);
  for (const Vec3& d : {Vec3(0.01, 0, 0), Vec3(0, 0.01, 0), Vec3(0, 0, 0.01)}) pts.push_back(c + d);
  const PointIndex index(pts);
  std::vector<Neighbour> got;
  index.withinRadiusByDistance(c, 0.3, got);
  const auto expected = bruteBall(pts, c, 0.3);
  ASSERT_EQ(got.size(), expected.size());
  std::vector<std::uint32_t> ids;
  for (std::size_t i = 0; i < got.size(); ++i) {
    ids.push_back(got[i].index);
    EXPECT_EQ(got[i].distance2, (pts[got[i].index] - c).squaredNorm());
    if (i > 0) {
      EXPECT_LE(got[i - 1].distance2, got[i].distance2);
      if (got[i - 1].distance2 == got[i].distance2) EXPECT_LT(got[i - 1].index, got[i].index);
    }
  }
  std::sort(ids.begin(), ids.end());
  EXPECT_EQ(ids, expected);
}

TEST_P(PointIndexLeaves, NearestEqualABruteForceScan) {
  std::mt19937_64 rng(7);
  const auto pts = randomPoints(rng, 2000);
  const PointIndex index(pts, PointIndexOptions{GetParam()});
  std::uniform_real_distribution<double> uni(-1.5, 1.5);
  for (int q = 0; q < 200; ++q) {
    const Vec3 c(uni(rng), uni(rng), uni(rng));
    std::vector<double> d2(pts.size());
    for (std::size_t i = 0; i < pts.size(); ++i) d2[i] = (pts[i] - c).squaredNorm();
    std::vector<double> sorted = d2;
    std::sort(sorted.begin(), sorted.end());
    const auto one = index.nearest(c);
    ASSERT_TRUE(one.has_value());
    EXPECT_EQ(one->distance2, sorted[0]);
    EXPECT_EQ(d2[one->index], sorted[0]);
    for (std::size_t k : {std::size_t{1}, std::size_t{5}, std::size_t{40}}) {
      const auto knn = index.nearest(c, k);
      ASSERT_EQ(knn.size(), k);
      for (std::size_t j = 0; j < k; ++j) {
        EXPECT_EQ(knn[j].distance2, sorted[j]) << "query " << q << " k " << k << " rank " << j;
        EXPECT_EQ(knn[j].distance2, d2[knn[j].index]);
      }
    }
  }
}

TEST(PointIndex, EmptyTinyAndInvalidInputs) {
  const PointIndex empty(std::vector<Vec3>{});
  EXPECT_EQ(empty.size(), 0u);
  EXPECT_TRUE(empty.withinRadius(Vec3::Zero(), 10.0).empty());
  EXPECT_FALSE(empty.nearest(Vec3::Zero()).has_value());
  EXPECT_TRUE(empty.nearest(Vec3::Zero(), 3).empty());

  const PointIndex two(std::vector<Vec3>{Vec3(0, 0, 0), Vec3(1, 0, 0)});
  EXPECT_EQ(two.nearest(Vec3(5, 0, 0), 10).size(), 2u);  // k is capped at the point count
  EXPECT_EQ(two.nearest(Vec3(0.9, 0, 0))->index, 1u);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(two.nearest(Vec3(nan, 0, 0)).has_value());
  EXPECT_TRUE(two.withinRadius(Vec3(nan, 0, 0), 1.0).empty());
  EXPECT_TRUE(two.withinRadius(Vec3::Zero(), nan).empty());

  EXPECT_THROW(PointIndex(std::vector<Vec3>{Vec3(0, 0, 0), Vec3(nan, 0, 0)}), OptionsError);
  EXPECT_THROW(PointIndex(std::vector<Vec3>{Vec3(std::numeric_limits<double>::infinity(), 0, 0)}), OptionsError);
  EXPECT_THROW(PointIndex(std::vector<Vec3>{Vec3::Zero()}, PointIndexOptions{0}), OptionsError);
}

}  // namespace
}  // namespace treesketch::accel
