// Tests of scan::castPattern and the counter-based random numbers it relies on.
#include "treesketch/scan/pattern_cast.h"

#include <gtest/gtest.h>

#include <atomic>
#include <cmath>

#include "scan/scan_test_meshes.h"
#include "treesketch/scan/counter_rng.h"
#include "treesketch/util/error.h"

namespace {

using namespace treesketch;
using geom::Vec3;
namespace tt = treesketch::test;

TEST(CounterRng, UniformAndGaussianMoments) {
  const int n = 200000;
  double su = 0, sg = 0, sg2 = 0;
  for (int i = 0; i < n; ++i) {
    const double u = scan::counterUniform(7, i, 0);
    ASSERT_GE(u, 0.0);
    ASSERT_LT(u, 1.0);
    su += u;
    const double g = scan::counterGaussian(7, i, 2);
    sg += g;
    sg2 += g * g;
  }
  EXPECT_NEAR(su / n, 0.5, 0.005);
  EXPECT_NEAR(sg / n, 0.0, 0.01);
  EXPECT_NEAR(std::sqrt(sg2 / n), 1.0, 0.01);
  // Pure functions of (seed, index, stream), and each argument matters.
  EXPECT_EQ(scan::counterHash(1, 2, 3), scan::counterHash(1, 2, 3));
  EXPECT_NE(scan::counterHash(1, 2, 3), scan::counterHash(2, 2, 3));
  EXPECT_NE(scan::counterHash(1, 2, 3), scan::counterHash(1, 3, 3));
  EXPECT_NE(scan::counterHash(1, 2, 3), scan::counterHash(1, 2, 4));
}

// Rays along -z through a grid over [-2, 2]^2; the scene is the unit square at z = 0.
scan::ScanRay gridRay(std::uint64_t i) {
  scan::ScanRay r;
  const double x = -2.0 + 4.0 * static_cast<double>(i % 40) / 39.0 + 1e-3;
  const double y = -2.0 + 4.0 * static_cast<double>(i / 40) / 39.0 + 1e-3;
  r.ray.origin = Vec3(x, y, 5.0);
  r.ray.dir = Vec3(0, 0, -2.0);  // not unit: noise must still be in scene units
  r.station = static_cast<std::int32_t>(i % 3);
  return r;
}

TEST(CastPattern, MissesAddNothingAndOrderIsRayOrder) {
  const accel::RayScene scene(tt::makeSquare(1.0));
  scan::CastOptions opt;
  opt.recordMesh = true;
  opt.recordStation = true;
  std::atomic<std::uint64_t> maxDone{0};
  const scan::ScanResult r = scan::castPattern(scene, 1600, gridRay, opt, [&](std::uint64_t done, std::uint64_t total) {
    EXPECT_EQ(total, 1600u);
    std::uint64_t prev = maxDone.load();
    while (done > prev && !maxDone.compare_exchange_weak(prev, done)) {
    }
  });
  EXPECT_EQ(maxDone.load(), 1600u);
  // Expected hits: the grid points inside the unit square, in index order.
  std::vector<std::uint64_t> expected;
  for (std::uint64_t i = 0; i < 1600; ++i) {
    const Vec3 o = gridRay(i).ray.origin;
    if (std::abs(o.x()) < 1.0 && std::abs(o.y()) < 1.0) expected.push_back(i);
  }
  ASSERT_GT(expected.size(), 100u);
  ASSERT_EQ(r.cloud.size(), expected.size());
  ASSERT_EQ(r.cloud.meshId.size(), expected.size());
  ASSERT_EQ(r.cloud.station.size(), expected.size());
  EXPECT_EQ(r.stats.raysCast, 1600u);
  EXPECT_EQ(r.stats.hits, expected.size());
  ASSERT_EQ(r.stats.hitsPerMesh.size(), 1u);
  EXPECT_EQ(r.stats.hitsPerMesh[0], expected.size());
  EXPECT_DOUBLE_EQ(r.stats.fraction(0), 1.0);
  for (std::size_t k = 0; k < expected.size(); ++k) {
    const Vec3 o = gridRay(expected[k]).ray.origin;
    EXPECT_NEAR((r.cloud.positions[k] - Vec3(o.x(), o.y(), 0.0)).norm(), 0.0, 1e-12);
    EXPECT_EQ(r.cloud.station[k], static_cast<std::int32_t>(expected[k] % 3));
    EXPECT_EQ(r.cloud.meshId[k], 0);
  }
  EXPECT_NO_THROW(r.cloud.checkConsistent());
}

TEST(CastPattern, RangeNoiseIsInSceneUnitsAlongTheRay) {
  const accel::RayScene scene(tt::makeSquare(3.0));
  scan::CastOptions opt;
  opt.rangeNoise = 0.05;
  const scan::ScanResult r = scan::castPattern(scene, 1600, gridRay, opt);
  ASSERT_EQ(r.cloud.size(), 1600u);
  EXPECT_TRUE(r.cloud.meshId.empty());
  EXPECT_TRUE(r.cloud.station.empty());
  double s = 0, s2 = 0;
  for (std::size_t i = 0; i < r.cloud.size(); ++i) {
    const Vec3 o = gridRay(i).ray.origin;
    EXPECT_NEAR(r.cloud.positions[i].x(), o.x(), 1e-12);  // noise only along the ray (z)
    const double z = r.cloud.positions[i].z();
    s += z;
    s2 += z * z;
  }
  const double mean = s / 1600, sd = std::sqrt(s2 / 1600 - mean * mean);
  EXPECT_NEAR(mean, 0.0, 0.005);
  EXPECT_NEAR(sd, 0.05, 0.005);
}

TEST(CastPattern, EmptyAndBadInput) {
  const accel::RayScene scene(tt::makeSquare(1.0));
  const scan::ScanResult none = scan::castPattern(scene, 0, gridRay);
  EXPECT_TRUE(none.cloud.empty());
  EXPECT_EQ(none.stats.raysCast, 0u);
  scan::CastOptions bad;
  bad.rangeNoise = -1.0;
  EXPECT_THROW(scan::castPattern(scene, 10, gridRay, bad), OptionsError);
  bad.rangeNoise = NAN;
  EXPECT_THROW(scan::castPattern(scene, 10, gridRay, bad), OptionsError);
  // Degenerate rays from a generator just miss.
  const scan::ScanResult degenerate = scan::castPattern(scene, 10, [](std::uint64_t) {
    scan::ScanRay r;
    r.ray.origin = Vec3(0, 0, 1);
    r.ray.dir = Vec3::Zero();
    return r;
  });
  EXPECT_TRUE(degenerate.cloud.empty());
  EXPECT_EQ(degenerate.stats.raysCast, 10u);
}

}  // namespace
