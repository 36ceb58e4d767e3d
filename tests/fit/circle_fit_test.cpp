#include "treesketch/fit/circle_fit.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "fit/synthetic_cylinder.h"
#include "treesketch/util/error.h"

namespace treesketch::fit {
namespace {

using geom::Vec2;
using test::noisyCircle;

TEST(CircleFrom3, ExactCircleAndCollinear) {
  Vec2 c;
  double r;
  ASSERT_TRUE(circleFrom3(Vec2(3, 2), Vec2(1, 4), Vec2(-1, 2), &c, &r));
  EXPECT_NEAR(c.x(), 1.0, 1e-12);
  EXPECT_NEAR(c.y(), 2.0, 1e-12);
  EXPECT_NEAR(r, 2.0, 1e-12);
  EXPECT_FALSE(circleFrom3(Vec2(0, 0), Vec2(1, 1), Vec2(2, 2), &c, &r));
  EXPECT_FALSE(circleFrom3(Vec2(1, 1), Vec2(1, 1), Vec2(2, 0), &c, &r));
}

// Full circles with noise and 30 % outliers: centre and radius within 2 % of the radius, for
// several radii and seeds.
TEST(FitCircleRansac, NoisyCircleWithThirtyPercentOutliers) {
  for (double radius : {0.1, 0.5, 2.0}) {
    for (std::uint64_t seed : {1u, 2u, 3u, 4u, 5u}) {
      Vec2 centre(0.7 * radius + 1.0, -3.0);
      auto pts = noisyCircle(centre, radius, 700, 300, 0.003, 0.0, 2 * M_PI, seed);
      CircleFitOptions opt;
      opt.seed = seed;
      CircleFitResult r = fitCircleRansac(pts, opt);
      ASSERT_TRUE(r.ok) << r.reason << " radius " << radius << " seed " << seed;
      EXPECT_LT((r.centre - centre).norm(), 0.02 * radius) << "radius " << radius << " seed " << seed;
      EXPECT_LT(std::abs(r.radius - radius), 0.02 * radius) << "radius " << radius << " seed " << seed;
      EXPECT_GE(r.inliers.size(), 650u);
      EXPECT_TRUE(std::is_sorted(r.inliers.begin(), r.inliers.end()));
      EXPECT_LT(r.rms, 0.01);
    }
  }
}

// A scan sees one side of a branch: arcs of 120° and 180° must still fit.
TEST(FitCircleRansac, PartialArcs) {
  for (double span : {2 * M_PI / 3, M_PI}) {
    for (double radius : {0.15, 0.6}) {
      for (std::uint64_t seed : {7u, 8u, 9u}) {
        Vec2 centre(-2.0, 5.0);
        auto pts = noisyCircle(centre, radius, 500, 215, 0.002, 0.3 * seed, span, seed);
        CircleFitOptions opt;
        opt.seed = seed;
        CircleFitResult r = fitCircleRansac(pts, opt);
        ASSERT_TRUE(r.ok) << r.reason;
        EXPECT_LT((r.centre - centre).norm(), 0.02 * radius) << "span " << span << " radius " << radius;
        EXPECT_LT(std::abs(r.radius - radius), 0.02 * radius) << "span " << span << " radius " << radius;
      }
    }
  }
}

TEST(FitCircleRansac, DeterministicForAFixedSeed) {
  auto pts = noisyCircle(Vec2(1, 1), 0.4, 400, 170, 0.004, 0.0, 2 * M_PI, 11);
  CircleFitOptions opt;
  opt.seed = 42;
  CircleFitResult a = fitCircleRansac(pts, opt), b = fitCircleRansac(pts, opt);
  ASSERT_TRUE(a.ok);
  EXPECT_EQ(a.centre, b.centre);
  EXPECT_EQ(a.radius, b.radius);
  EXPECT_EQ(a.inliers, b.inliers);
  EXPECT_EQ(a.iterations, b.iterations);
}

TEST(FitCircleRansac, AdaptiveIterationCount) {
  CircleFitOptions opt;
  auto clean = noisyCircle(Vec2(0, 0), 1.0, 500, 0, 0.001, 0.0, 2 * M_PI, 3);
  auto dirty = noisyCircle(Vec2(0, 0), 1.0, 300, 700, 0.001, 0.0, 2 * M_PI, 3);
  CircleFitResult c = fitCircleRansac(clean, opt), d = fitCircleRansac(dirty, opt);
  ASSERT_TRUE(c.ok);
  ASSERT_TRUE(d.ok) << d.reason;
  // w ≈ 1: N = log(0.001)/log(1 − w³) is tiny, only the floor applies.
  EXPECT_LE(c.iterations, 2 * opt.minIterations);
  // w ≈ 0.3 (+ outliers in the band): N ≈ log(0.001)/log(1 − 0.03) ≈ 250.
  EXPECT_GT(d.iterations, 100);
  EXPECT_LT(d.iterations, opt.maxIterations);
}

TEST(FitCircleRansac, DegenerateInputsReturnAReason) {
  CircleFitOptions opt;
  CircleFitResult r = fitCircleRansac({}, opt);
  EXPECT_FALSE(r.ok);
  EXPECT_NE(r.reason.find("fewer than 3"), std::string::npos);
  r = fitCircleRansac({Vec2(0, 0), Vec2(1, 0)}, opt);
  EXPECT_FALSE(r.ok);
  std::vector<Vec2> line;
  for (int i = 0; i < 50; ++i) line.emplace_back(0.1 * i, 0.2 * i);
  r = fitCircleRansac(line, opt);
  EXPECT_FALSE(r.ok);
  EXPECT_FALSE(r.reason.empty());
  std::vector<Vec2> same(30, Vec2(1, 1));
  EXPECT_FALSE(fitCircleRansac(same, opt).ok);
}

TEST(FitCircleRansac, NonFinitePointsAreNeverInliers) {
  auto pts = noisyCircle(Vec2(0, 0), 0.5, 200, 0, 0.001, 0.0, 2 * M_PI, 5);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  pts.emplace_back(nan, 0.0);
  pts.emplace_back(0.5, std::numeric_limits<double>::infinity());
  CircleFitResult r = fitCircleRansac(pts, {});
  ASSERT_TRUE(r.ok);
  EXPECT_NEAR(r.radius, 0.5, 0.01);
  EXPECT_LT(r.inliers.back(), 200u);
}

TEST(FitCircleRansac, RadiusBoundsAndCentreRegionAreRespected) {
  auto pts = noisyCircle(Vec2(0, 0), 0.5, 300, 0, 0.001, 0.0, 2 * M_PI, 6);
  CircleFitOptions opt;
  opt.maxRadius = 0.3;
  EXPECT_FALSE(fitCircleRansac(pts, opt).ok);
  opt = {};
  opt.centreRegion.active = true;
  opt.centreRegion.hasLine = true;
  opt.centreRegion.origin = Vec2(0, 2);
  opt.centreRegion.dir = Vec2(1, 0);
  opt.centreRegion.maxDistance = 1.0;  // the circle's centre is 2 from the line y = 2
  EXPECT_FALSE(fitCircleRansac(pts, opt).ok);
  opt.centreRegion.maxDistance = 2.5;
  CircleFitResult r = fitCircleRansac(pts, opt);
  ASSERT_TRUE(r.ok);
  EXPECT_LT(r.centre.norm(), 0.01);
}

TEST(FitCircleRansac, MinimumSupport) {
  // Two concentric-free circles: 60 points on one, 940 scattered: 60 < 10 % of 1000.
  auto pts = noisyCircle(Vec2(0, 0), 0.5, 60, 940, 0.001, 0.0, 2 * M_PI, 9);
  CircleFitOptions opt;
  CircleFitResult r = fitCircleRansac(pts, opt);
  EXPECT_FALSE(r.ok);
  EXPECT_NE(r.reason.find("too few inliers"), std::string::npos) << r.reason;
  opt.minInlierFraction = 0.05;
  opt.maxIterations = 50000;  // w ≈ 0.075: N ≈ 16,000 samples for p = 0.999
  r = fitCircleRansac(pts, opt);
  ASSERT_TRUE(r.ok) << r.reason;
  EXPECT_NEAR(r.radius, 0.5, 0.01);
}

TEST(FitCircleRansac, InvalidOptionsThrow) {
  std::vector<Vec2> pts = {Vec2(1, 0), Vec2(0, 1), Vec2(-1, 0), Vec2(0, -1)};
  CircleFitOptions opt;
  opt.probability = 1.0;
  EXPECT_THROW(fitCircleRansac(pts, opt), OptionsError);
  opt = {};
  opt.inlierThreshold = -1;
  EXPECT_THROW(fitCircleRansac(pts, opt), OptionsError);
  opt = {};
  opt.inlierThreshold = 0;
  opt.inlierThresholdRelative = 0;
  EXPECT_THROW(fitCircleRansac(pts, opt), OptionsError);
  opt = {};
  opt.minRadius = 2;
  opt.maxRadius = 1;
  EXPECT_THROW(fitCircleRansac(pts, opt), OptionsError);
}

TEST(FitCircleLeastSquares, RecoversAnArcWithoutOutliers) {
  auto pts = noisyCircle(Vec2(3, -1), 0.8, 200, 0, 0.0, 0.2, M_PI / 2, 4);
  std::vector<std::uint32_t> idx(pts.size());
  for (std::uint32_t i = 0; i < idx.size(); ++i) idx[i] = i;
  Vec2 c;
  double r = 0;
  ASSERT_TRUE(fitCircleLeastSquares(pts, idx, 20, &c, &r));
  EXPECT_NEAR((c - Vec2(3, -1)).norm(), 0.0, 1e-9);
  EXPECT_NEAR(r, 0.8, 1e-9);
  EXPECT_FALSE(fitCircleLeastSquares(pts, {0, 1}, 20, &c, &r));
}

}  // namespace
}  // namespace treesketch::fit
