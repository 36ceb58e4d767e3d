#include "treesketch/fit/cloud_index.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <limits>
#include <random>
#include <thread>

#include "fit/synthetic_cylinder.h"
#include "treesketch/util/error.h"

namespace treesketch::fit {
namespace {

using geom::Vec3;

// Index lists sorted: CloudIndex answers in its storage order, sliceBruteForce in increasing order.
std::vector<std::uint32_t> sorted(std::vector<std::uint32_t> v) {
  std::sort(v.begin(), v.end());
  return v;
}

geom::PointCloud randomCloud(std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  geom::PointCloud cloud;
  test::addOutliers(cloud, 15000, Vec3(-2, 0, -1), Vec3(3, 6, 2), rng);
  test::CylinderSpec c;
  c.base = Vec3(0.5, 0, 0.2);
  c.radius = 0.4;
  c.length = 5;
  c.points = 10000;
  test::addCylinder(cloud, c, rng);
  // Points exactly on cell boundaries and duplicates.
  for (int i = 0; i < 200; ++i) cloud.positions.push_back(Vec3(-2 + 0.025 * i, 0.0, 2.0));
  cloud.positions.push_back(cloud.positions[17]);
  cloud.positions.push_back(Vec3(3, 6, 2));
  return cloud;
}

Vec3 randomUnit(std::mt19937_64& rng) {
  std::normal_distribution<double> nd;
  Vec3 v(nd(rng), nd(rng), nd(rng));
  return v.normalized();
}

// Query q of a random series over randomCloud's box: kinds in turn, every fourth plane
// axis-aligned (the dominant-axis column walk's edge case), lines mostly in the plane (as
// sketches draw them), every fifth not.
SliceRegion randomRegion(int q, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u01(0, 1);
  SliceRegion r;
  r.kind = SliceRegion::Kind(q % 3);
  r.planePoint = Vec3(-2 + 5 * u01(rng), 6 * u01(rng), -1 + 3 * u01(rng));
  r.planeNormal = q % 4 == 0 ? Vec3::Unit(q % 3) : randomUnit(rng);
  r.halfThickness = 0.01 + 0.2 * u01(rng);
  r.linePoint = r.planePoint + 0.3 * u01(rng) * r.planeNormal.cross(randomUnit(rng));
  const Vec3 d = randomUnit(rng);
  r.lineDir = (d - d.dot(r.planeNormal) * r.planeNormal).normalized();
  if (q % 5 == 0) r.lineDir = randomUnit(rng);
  r.radius = 0.05 + 1.5 * u01(rng);
  return r;
}

TEST(CloudIndex, IndexedSlicesEqualBruteForceOnRandomRegions) {
  geom::PointCloud cloud = randomCloud(1);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  cloud.positions.push_back(Vec3(nan, 1, 1));  // never returned
  CloudIndex index(cloud);
  EXPECT_EQ(index.size(), cloud.size() - 1);
  std::mt19937_64 rng(99);
  std::size_t nonEmpty = 0;
  for (int q = 0; q < 120; ++q) {
    const SliceRegion r = randomRegion(q, rng);
    std::vector<Vec3> pos;
    auto fast = index.query(r, &pos);
    auto slow = sliceBruteForce(cloud, r);
    ASSERT_EQ(sorted(fast), slow) << "query " << q;
    std::vector<Vec3> slowPos;
    EXPECT_EQ(index.queryBruteForce(r, &slowPos), fast);  // same list, same order
    EXPECT_EQ(slowPos, pos);
    EXPECT_EQ(index.count(r), slow.size());
    ASSERT_EQ(pos.size(), fast.size());
    for (std::size_t i = 0; i < fast.size(); ++i) EXPECT_EQ(pos[i], cloud.positions[fast[i]]);
    nonEmpty += !slow.empty();
  }
  EXPECT_GT(nonEmpty, 60u);  // the comparison is not vacuous
}

// The eight-wide (AVX2) pre-test and the baseline four-wide one give the same lists, and the
// plane coordinates of a query's hits are the same numbers on both paths, close to the exact ones.
// (On a processor without AVX2 both indexes run the baseline path and the test still holds.)
TEST(CloudIndex, Avx2AndBaselinePreTestsAndProjectedQueryAgree) {
  const geom::PointCloud cloud = randomCloud(7);
  CloudIndexOptions baseline;
  baseline.allowAvx2 = false;
  const CloudIndex wide(cloud), narrow(cloud, baseline);
  std::mt19937_64 rng(5);
  std::size_t hits = 0;
  for (int q = 0; q < 90; ++q) {
    const SliceRegion r = randomRegion(q, rng);
    std::vector<Vec3> pos;
    const auto a = wide.query(r, &pos);
    ASSERT_EQ(narrow.query(r), a) << "query " << q;
    PlaneFrame frame;
    frame.origin = r.planePoint;
    frame.u = geom::anyPerpendicular(r.planeNormal).normalized();
    frame.v = r.planeNormal.cross(frame.u);
    std::vector<geom::Vec2> coords, slowCoords;
    ASSERT_EQ(wide.query(r, nullptr, &frame, &coords), a) << "query " << q;
    ASSERT_EQ(wide.queryBruteForce(r, nullptr, &frame, &slowCoords), a) << "query " << q;
    EXPECT_EQ(slowCoords, coords);  // the same numbers on both paths
    ASSERT_EQ(coords.size(), a.size());
    // From the float copy: within ~1e-7 of the cloud's size (diagonal ~8 here) of the exact ones.
    for (std::size_t i = 0; i < a.size(); ++i) ASSERT_LT((coords[i] - frame(pos[i])).norm(), 1e-5);
    hits += a.size();
  }
  EXPECT_GT(hits, 1000u);  // not vacuous
}

// A small surface scan is not refined to millions of cells (their build time dominated small
// clouds): at most maxCellsPerPoint cells a point, with the same answers as without the bound.
TEST(CloudIndex, SmallCloudsGetAGridSizedToThem) {
  std::mt19937_64 rng(3);
  geom::PointCloud cloud;
  test::CylinderSpec c;
  c.radius = 0.3;
  c.length = 6;
  c.points = 3000;
  test::addCylinder(cloud, c, rng);
  cloud.positions.push_back(Vec3(20, 20, 20));  // a far stray point: a large, mostly empty box
  auto cells = [&](const CloudIndex& index) {
    const Vec3 ext = index.bounds().extent();
    double total = 1;
    for (int a = 0; a < 3; ++a) total *= std::max(1.0, std::ceil(ext[a] / index.cellSize()));
    return total;
  };
  CloudIndexOptions unbounded;
  unbounded.maxCellsPerPoint = 0;
  const CloudIndex bounded(cloud), fine(cloud, unbounded);
  EXPECT_LE(cells(bounded), 16.0 * 3001 * 1.001);
  EXPECT_GT(cells(fine), 2 * cells(bounded));  // the bound did something
  for (int q = 0; q < 60; ++q) {
    SliceRegion r;
    r.kind = SliceRegion::Kind(q % 3);
    r.planePoint = Vec3(0, 0.1 * q, 0);
    r.planeNormal = Vec3(0.1 * (q % 7), 1, 0.05 * (q % 5)).normalized();
    r.halfThickness = 0.02 + 0.002 * q;
    r.linePoint = r.planePoint;
    r.lineDir = Vec3::UnitY();
    r.radius = 0.2 + 0.01 * q;
    ASSERT_EQ(bounded.query(r), bounded.queryBruteForce(r)) << "query " << q;
    ASSERT_EQ(sorted(bounded.query(r)), sorted(fine.query(r))) << "query " << q;
  }
  CloudIndexOptions bad;
  bad.maxCellsPerPoint = -1;
  EXPECT_THROW(CloudIndex(cloud, bad), OptionsError);
}

TEST(CloudIndex, CoarseAndFineGridsGiveTheSameAnswer) {
  geom::PointCloud cloud = randomCloud(2);
  CloudIndexOptions coarse, fine;
  coarse.pointsPerCell = 500;
  fine.pointsPerCell = 0.5;
  CloudIndex a(cloud, coarse), b(cloud, fine);
  EXPECT_GT(a.cellSize(), b.cellSize());
  SliceRegion r;
  r.kind = SliceRegion::Kind::Cylinder;
  r.planePoint = Vec3(0.5, 2, 0.2);
  r.planeNormal = Vec3(0.1, 1, 0.05).normalized();
  r.linePoint = r.planePoint;
  r.lineDir = r.planeNormal.cross(Vec3::UnitX()).normalized();
  r.radius = 0.5;
  EXPECT_EQ(sorted(a.query(r)), sorted(b.query(r)));
  EXPECT_EQ(sorted(a.query(r)), sliceBruteForce(cloud, r));
}

TEST(CloudIndex, EmptyAndFlatClouds) {
  geom::PointCloud empty;
  CloudIndex e(empty);
  SliceRegion r;
  EXPECT_TRUE(e.query(r).empty());
  EXPECT_EQ(e.count(r), 0u);

  geom::PointCloud flat;
  for (int i = 0; i < 50; ++i)
    for (int j = 0; j < 50; ++j) flat.positions.push_back(Vec3(0.02 * i, 0.02 * j, 0.0));
  CloudIndex f(flat);
  r.planePoint = Vec3(0.5, 0, 0);
  r.planeNormal = Vec3::UnitX();
  r.halfThickness = 0.011;
  auto got = f.query(r);
  EXPECT_EQ(sorted(got), sliceBruteForce(flat, r));
  EXPECT_EQ(got.size(), 50u);  // the column x = 0.5 (i = 25)
}

TEST(CloudIndex, RegionCoversCloud) {
  geom::PointCloud cloud;
  cloud.positions = {Vec3(0, 0, 0), Vec3(1, 1, 1)};
  CloudIndex index(cloud);
  SliceRegion r;
  r.kind = SliceRegion::Kind::Ball;
  r.linePoint = Vec3(0.5, 0.5, 0.5);
  r.radius = 0.8;  // half-diagonal is 0.866
  EXPECT_FALSE(index.regionCoversCloud(r));
  r.radius = 0.9;
  EXPECT_TRUE(index.regionCoversCloud(r));
  r.kind = SliceRegion::Kind::Cylinder;
  r.lineDir = Vec3(1, 1, 1).normalized();
  r.radius = 0.01;  // the diagonal itself: all corners... except those off the diagonal
  EXPECT_FALSE(index.regionCoversCloud(r));
  r.kind = SliceRegion::Kind::Slab;
  EXPECT_TRUE(index.regionCoversCloud(r));
}

TEST(CloudIndex, InvalidRegionsThrow) {
  geom::PointCloud cloud;
  cloud.positions = {Vec3(0, 0, 0), Vec3(1, 1, 1)};
  CloudIndex index(cloud);
  SliceRegion r;
  r.halfThickness = 0;
  EXPECT_THROW(index.query(r), OptionsError);
  r = {};
  r.planeNormal = Vec3(0, 2, 0);
  EXPECT_THROW(index.query(r), OptionsError);
  r = {};
  r.kind = SliceRegion::Kind::Cylinder;
  r.lineDir = Vec3::Zero();
  r.radius = 1;
  EXPECT_THROW(sliceBruteForce(cloud, r), OptionsError);
  r = {};
  r.planePoint.x() = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(index.count(r), OptionsError);
  CloudIndexOptions bad;
  bad.pointsPerCell = 0;
  EXPECT_THROW(CloudIndex(cloud, bad), OptionsError);
}

// The index pre-tests points in float (relative to the cloud's centre) and decides points near
// the region's boundary exactly: points placed at the boundary within a few ulps, in a cloud far
// from the origin, must give the brute-force answer; so must regions whose sizes or positions are
// beyond the float pre-test's range (a huge ball centred far away, a plane point far away).
TEST(CloudIndex, BoundaryPointsAndHugeRegionsEqualBruteForce) {
  const Vec3 offset(1e5, -2e5, 3e4);
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-1, 1);
  geom::PointCloud cloud;
  const double h = 0.05, radius = 0.5;
  for (int i = 0; i < 4000; ++i) {
    // Slab normal +y through offset: y on the boundary ± a few ulps, x/z on the ball boundary.
    double y = h * (i % 2 ? 1 : -1);
    y = std::nextafter(y, (i % 4) < 2 ? 1.0 : -1.0);
    double th = 3.0 * u(rng);
    double rr = std::nextafter(std::sqrt(radius * radius - y * y), (i % 3) ? 0.0 : 1.0);
    cloud.positions.push_back(offset + Vec3(rr * std::cos(th), y, rr * std::sin(th)));
    cloud.positions.push_back(offset + Vec3(u(rng), 0.1 * u(rng), u(rng)));
  }
  CloudIndex index(cloud);
  std::vector<SliceRegion> regions;
  SliceRegion r;
  r.kind = SliceRegion::Kind::Ball;
  r.planePoint = offset;
  r.planeNormal = Vec3::UnitY();
  r.halfThickness = h;
  r.linePoint = offset;
  r.radius = radius;
  regions.push_back(r);
  r.kind = SliceRegion::Kind::Cylinder;
  r.lineDir = Vec3::UnitY();
  regions.push_back(r);
  r.kind = SliceRegion::Kind::Slab;
  regions.push_back(r);
  r.kind = SliceRegion::Kind::Ball;  // huge ball centred far away: covers part of the cloud only
  r.linePoint = offset + Vec3(2e15, 0, 0);
  r.radius = 2e15 - 0.2;
  regions.push_back(r);
  r.kind = SliceRegion::Kind::Slab;  // plane point far away along the plane
  r.linePoint = offset;
  r.planePoint = offset + Vec3(1e35, 0, -1e35);
  regions.push_back(r);
  for (const auto& reg : regions) {
    auto slow = sliceBruteForce(cloud, reg);
    EXPECT_EQ(sorted(index.query(reg)), slow) << "kind " << int(reg.kind);
    EXPECT_EQ(index.query(reg), index.queryBruteForce(reg)) << "kind " << int(reg.kind);
    EXPECT_EQ(index.count(reg), slow.size());
  }
  EXPECT_FALSE(sliceBruteForce(cloud, regions[0]).empty());
  EXPECT_LT(sliceBruteForce(cloud, regions[3]).size(), cloud.size());
  EXPECT_FALSE(sliceBruteForce(cloud, regions[3]).empty());
}

// Queries reuse per-thread buffers (grown by big results, released past a size): a mix of huge and
// small results on one thread, and the same from several threads at once.
TEST(CloudIndex, ReusedQueryBuffersGiveBruteForceResults) {
  std::mt19937_64 rng(5);
  geom::PointCloud cloud;
  test::addOutliers(cloud, 150000, Vec3(-2, 0, -2), Vec3(2, 4, 2), rng);
  const CloudIndex index(cloud);
  std::uniform_real_distribution<double> u01(0, 1);
  std::vector<SliceRegion> regions;
  for (int q = 0; q < 12; ++q) {
    SliceRegion r;
    r.kind = q % 3 == 0 ? SliceRegion::Kind::Slab : SliceRegion::Kind::Ball;
    r.planePoint = Vec3(0, 4 * u01(rng), 0);
    r.planeNormal = randomUnit(rng);
    r.halfThickness = q % 3 == 0 ? 1.0 : 0.05;  // slabs: ~100k hits; balls: a few hundred
    r.linePoint = r.planePoint;
    r.radius = 0.3 + 0.5 * u01(rng);
    regions.push_back(r);
  }
  std::vector<std::vector<std::uint32_t>> expected;
  for (const auto& r : regions) {
    expected.push_back(index.queryBruteForce(r));
    ASSERT_EQ(sorted(expected.back()), sliceBruteForce(cloud, r));
  }
  EXPECT_GT(expected[0].size(), 70000u);
  EXPECT_GT(expected[1].size(), 100u);
  auto check = [&](int pass) {
    for (std::size_t i = 0; i < regions.size(); ++i) {
      std::vector<Vec3> pos;
      ASSERT_EQ(index.query(regions[i], &pos), expected[i]) << "pass " << pass << " region " << i;
      ASSERT_EQ(pos.size(), expected[i].size());
      for (std::size_t k = 0; k < pos.size(); k += 97) ASSERT_EQ(pos[k], cloud.positions[expected[i][k]]);
    }
  };
  check(0);
  check(1);
  std::vector<std::thread> threads;
  for (int t = 0; t < 3; ++t) threads.emplace_back(check, 2 + t);
  for (auto& th : threads) th.join();
}

}  // namespace
}  // namespace treesketch::fit
