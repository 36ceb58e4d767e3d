// Tests of the thesis's sphere scanner: ray counts, origin spread, hits on the surface, misses,
// determinism across thread counts and seeds, mesh ids, bad options.
#include "treesketch/scan/sphere_scan.h"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <cmath>
#include <set>
#include <tuple>

#include "scan/scan_test_meshes.h"
#include "treesketch/util/error.h"

namespace {

using namespace treesketch;
using geom::TriMesh;
using geom::Vec3;
namespace tt = treesketch::test;

scan::SphereScanOptions withSubdiv(int k) {
  scan::SphereScanOptions o;
  o.subdivisions = k;
  return o;
}

TEST(SphereScan, RayCountsMatchTheThesis) {
  // Thesis §4.2: 6 to 8 subdivisions gave 73,728 to 1,179,648 points.
  EXPECT_EQ(scan::sphereRayCount(withSubdiv(6)), 73728u);
  EXPECT_EQ(scan::sphereRayCount(withSubdiv(7)), 294912u);
  EXPECT_EQ(scan::sphereRayCount(withSubdiv(8)), 1179648u);
  EXPECT_EQ(scan::sphereRayCount(withSubdiv(1)), 72u);
  scan::SphereScanOptions byRays;
  for (std::uint64_t want : {1ull, 8ull, 9ull, 1000ull, 100000ull, 1179648ull}) {
    byRays.rays = want;
    const std::uint64_t n = scan::sphereGridSize(byRays), got = scan::sphereRayCount(byRays);
    EXPECT_EQ(got, 8 * n * n);
    EXPECT_GE(got, want);
    EXPECT_LT(8 * (n - 1) * (n - 1), want);  // smallest such grid
  }
  EXPECT_THROW(scan::sphereRayCount(withSubdiv(0)), OptionsError);
  EXPECT_THROW(scan::sphereRayCount(withSubdiv(13)), OptionsError);
}

TEST(SphereScan, OriginsAreDistinctUnitVectorsSpreadOverTheSphere) {
  const std::uint64_t n = 6;  // 288 origins
  std::vector<Vec3> dirs;
  Vec3 sum = Vec3::Zero();
  for (std::uint64_t i = 0; i < 8 * n * n; ++i) {
    const Vec3 d = scan::sphereGridDirection(n, i);
    EXPECT_NEAR(d.norm(), 1.0, 1e-12);
    dirs.push_back(d);
    sum += d;
  }
  EXPECT_NEAR(sum.norm(), 0.0, 1e-9);  // symmetric
  // Nearest-neighbour angles: none coincide, and the spread is within ~2.5x.
  double minNn = 10, maxNn = 0;
  for (std::size_t i = 0; i < dirs.size(); ++i) {
    double nn = 10;
    for (std::size_t j = 0; j < dirs.size(); ++j)
      if (i != j) nn = std::min(nn, std::acos(std::clamp(dirs[i].dot(dirs[j]), -1.0, 1.0)));
    minNn = std::min(minNn, nn);
    maxNn = std::max(maxNn, nn);
  }
  EXPECT_GT(minNn, 0.01);
  EXPECT_LT(maxNn / minNn, 2.5);
}

TEST(SphereScan, HitsLieOnTheSurface) {
  std::vector<TriMesh> meshes = {tt::makeTube(Vec3(0, 0, 0), 0.2, 3.0, 20),
                                 tt::makeTube(Vec3(0.3, 0, 1), 0.1, 1.5, 10)};
  scan::SphereScanOptions o = withSubdiv(4);  // 4608 rays
  o.jitterDeg = 10.0;
  o.recordMesh = true;
  const scan::ScanResult r = scan::sphereScan(meshes, o);
  ASSERT_GT(r.cloud.size(), 100u);
  EXPECT_EQ(r.stats.raysCast, 4608u);
  EXPECT_EQ(r.stats.hits, r.cloud.size());
  geom::BBox box = meshes[0].bounds();
  box.add(meshes[1].bounds());
  const double tol = 1e-6 * box.diagonal();
  std::uint64_t perMesh[2] = {0, 0};
  for (std::size_t i = 0; i < r.cloud.size(); ++i) {
    const int m = r.cloud.meshId[i];
    ASSERT_TRUE(m == 0 || m == 1);
    ++perMesh[m];
    EXPECT_LE(tt::pointMeshDistance(r.cloud.positions[i], meshes[m]), tol) << i;
  }
  EXPECT_EQ(r.stats.hitsPerMesh[0], perMesh[0]);
  EXPECT_EQ(r.stats.hitsPerMesh[1], perMesh[1]);
  EXPECT_GT(perMesh[1], 0u);
}

TEST(SphereScan, RaysThatMissAddNoPoint) {
  // Centre-aimed rays all pass through the hole of a holed square: every ray misses.
  const std::vector<TriMesh> holed = {tt::makeSquare(1.0, 0.5)};
  scan::SphereScanOptions o = withSubdiv(3);  // 1152 rays
  o.jitterDeg = 0.0;
  const scan::ScanResult none = scan::sphereScan(holed, o);
  EXPECT_EQ(none.stats.raysCast, 1152u);
  EXPECT_EQ(none.cloud.size(), 0u);
  // The same rays on a full square all hit (no origin lies in the square's plane).
  const scan::ScanResult all = scan::sphereScan(std::vector<TriMesh>{tt::makeSquare(1.0)}, o);
  EXPECT_EQ(all.cloud.size(), 1152u);
  // With jitter some rays hit the ring, and only there.
  o.jitterDeg = 30.0;
  const scan::ScanResult some = scan::sphereScan(holed, o);
  EXPECT_GT(some.cloud.size(), 0u);
  EXPECT_LT(some.cloud.size(), 1152u);
  for (const Vec3& p : some.cloud.positions) {
    EXPECT_NEAR(p.z(), 0.0, 1e-12);
    EXPECT_GE(std::max(std::abs(p.x()), std::abs(p.y())), 0.5 - 1e-9);
    EXPECT_LE(std::max(std::abs(p.x()), std::abs(p.y())), 1.0 + 1e-9);
  }
}

TEST(SphereScan, SameSeedSameCloudWithOneOrTwoThreads) {
  const std::vector<TriMesh> meshes = {tt::makeTube(Vec3(0, 0, 0), 0.3, 2.0, 16)};
  scan::SphereScanOptions o = withSubdiv(4);
  o.jitterDeg = 15.0;
  o.rangeNoise = 0.01;
  o.seed = 99;
  o.recordMesh = true;
  scan::ScanResult one, two;
  {
    tbb::global_control gc(tbb::global_control::max_allowed_parallelism, 1);
    one = scan::sphereScan(meshes, o);
  }
  {
    tbb::global_control gc(tbb::global_control::max_allowed_parallelism, 2);
    two = scan::sphereScan(meshes, o);
  }
  ASSERT_GT(one.cloud.size(), 0u);
  ASSERT_EQ(one.cloud.size(), two.cloud.size());
  EXPECT_EQ(one.cloud.positions, two.cloud.positions);
  EXPECT_EQ(one.cloud.meshId, two.cloud.meshId);
  // A different seed changes the cloud.
  o.seed = 100;
  const scan::ScanResult other = scan::sphereScan(meshes, o);
  EXPECT_FALSE(other.cloud.size() == one.cloud.size() && other.cloud.positions == one.cloud.positions);
}

TEST(SphereScan, RadiusAndCentre) {
  // With no jitter each hit lies on the line from its origin to the box centre, so hits on a
  // box centred at c are symmetric about c.
  const Vec3 c(10, -20, 30);
  const std::vector<TriMesh> meshes = {tt::makeBox(c - Vec3(1, 2, 3), c + Vec3(1, 2, 3))};
  scan::SphereScanOptions o = withSubdiv(2);
  o.jitterDeg = 0.0;
  o.radius = 50.0;
  const scan::ScanResult r = scan::sphereScan(meshes, o);
  ASSERT_EQ(r.cloud.size(), 288u);
  Vec3 mean = Vec3::Zero();
  for (const Vec3& p : r.cloud.positions) mean += p;
  EXPECT_NEAR((mean / 288.0 - c).norm(), 0.0, 1e-9);
}

TEST(SphereScan, RaysAreJitteredWithinTheCapAndAimedAtTheCentre) {
  geom::BBox box;
  box.add(Vec3(-1, 0, -1));
  box.add(Vec3(1, 4, 1));
  scan::SphereScanOptions o = withSubdiv(3);
  o.jitterDeg = 5.0;
  double maxAngle = 0.0, sumCos = 0.0;
  const std::uint64_t count = scan::sphereRayCount(o);
  for (std::uint64_t i = 0; i < count; ++i) {
    const accel::Ray r = scan::sphereScanRay(o, box, i);
    EXPECT_NEAR((r.origin - box.centre()).norm(), box.diagonal(), 1e-9);  // radiusFactor 1
    EXPECT_NEAR(r.dir.norm(), 1.0, 1e-12);
    const double c = std::clamp(r.dir.dot((box.centre() - r.origin).normalized()), -1.0, 1.0);
    maxAngle = std::max(maxAngle, std::acos(c));
    sumCos += c;
  }
  EXPECT_LE(maxAngle, 5.0 * M_PI / 180.0 + 1e-9);
  EXPECT_GT(maxAngle, 4.5 * M_PI / 180.0);
  // Uniform over the cap: the mean cosine is the cap's middle, (1 + cos 5 deg) / 2.
  // Tolerance: 4.5 standard errors; a jitter uniform in angle (not area) would be 6e-4 off.
  EXPECT_NEAR(sumCos / count, 0.5 * (1.0 + std::cos(5.0 * M_PI / 180.0)), 1.5e-4);
  EXPECT_THROW(scan::sphereScanRay(o, box, count), OptionsError);
  EXPECT_THROW(scan::sphereScanRay(o, geom::BBox{}, 0), OptionsError);
}

TEST(SphereScan, BadOptionsAndEmptyScene) {
  const std::vector<TriMesh> meshes = {tt::makeBox(Vec3(-1, -1, -1), Vec3(1, 1, 1))};
  scan::SphereScanOptions o = withSubdiv(1);
  o.jitterDeg = -1.0;
  EXPECT_THROW(scan::sphereScan(meshes, o), OptionsError);
  o.jitterDeg = 91.0;
  EXPECT_THROW(scan::sphereScan(meshes, o), OptionsError);
  o = withSubdiv(1);
  o.radius = NAN;
  EXPECT_THROW(scan::sphereScan(meshes, o), OptionsError);
  o = withSubdiv(1);
  o.radiusFactor = 0.0;
  EXPECT_THROW(scan::sphereScan(meshes, o), OptionsError);
  o = withSubdiv(1);
  o.rangeNoise = -0.1;
  EXPECT_THROW(scan::sphereScan(meshes, o), OptionsError);
  const scan::ScanResult empty = scan::sphereScan(std::vector<TriMesh>{}, withSubdiv(1));
  EXPECT_TRUE(empty.cloud.empty());
  EXPECT_EQ(empty.stats.raysCast, 0u);
}

}  // namespace
