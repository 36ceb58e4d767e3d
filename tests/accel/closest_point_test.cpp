#include "treesketch/accel/closest_point.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <set>

#include "treesketch/util/error.h"

namespace treesketch::accel {
namespace {

using geom::Vec3;

const Vec3 kA(0, 0, 0), kB(1, 0, 0), kC(0, 1, 0);

void expectRegion(const Vec3& p, const Vec3& expected, TriangleRegion expectedRegion) {
  TriangleRegion region{};
  Vec3 c = closestPointOnTriangle(p, kA, kB, kC, &region);
  EXPECT_NEAR((c - expected).norm(), 0.0, 1e-15) << "p=" << p.transpose() << " got " << c.transpose();
  EXPECT_EQ(region, expectedRegion) << "p=" << p.transpose();
}

TEST(ClosestPointOnTriangle, EachVoronoiRegionExact) {
  expectRegion({0.25, 0.25, 0.5}, {0.25, 0.25, 0}, TriangleRegion::Face);
  expectRegion({0.25, 0.25, -3}, {0.25, 0.25, 0}, TriangleRegion::Face);
  expectRegion({0.5, -1, 0.3}, {0.5, 0, 0}, TriangleRegion::EdgeAB);
  expectRegion({1, 1, 0.2}, {0.5, 0.5, 0}, TriangleRegion::EdgeBC);
  expectRegion({-1, 0.5, 0}, {0, 0.5, 0}, TriangleRegion::EdgeCA);
  expectRegion({-1, -1, 1}, kA, TriangleRegion::VertexA);
  expectRegion({2, -0.5, 0}, kB, TriangleRegion::VertexB);
  expectRegion({-0.5, 2, 0}, kC, TriangleRegion::VertexC);
}

TEST(ClosestPointOnTriangle, PointOnTriangleIsItsOwnClosestPoint) {
  Vec3 p(0.2, 0.3, 0);
  EXPECT_NEAR((closestPointOnTriangle(p, kA, kB, kC) - p).norm(), 0.0, 1e-16);
  EXPECT_NEAR((closestPointOnTriangle(kB, kA, kB, kC) - kB).norm(), 0.0, 1e-16);
}

TEST(ClosestPointOnTriangle, DegenerateTriangles) {
  // Collinear corners: the closest point of the segment they span.
  Vec3 c = closestPointOnTriangle({1.5, 1, 0}, {0, 0, 0}, {1, 0, 0}, {2, 0, 0});
  EXPECT_NEAR((c - Vec3(1.5, 0, 0)).norm(), 0.0, 1e-15);
  c = closestPointOnTriangle({3, 1, 0}, {0, 0, 0}, {2, 0, 0}, {1, 0, 0});
  EXPECT_NEAR((c - Vec3(2, 0, 0)).norm(), 0.0, 1e-15);
  // Two coincident corners.
  c = closestPointOnTriangle({0.5, 1, 0}, {0, 0, 0}, {0, 0, 0}, {1, 0, 0});
  EXPECT_NEAR((c - Vec3(0.5, 0, 0)).norm(), 0.0, 1e-15);
  // All three coincident.
  c = closestPointOnTriangle({4, 5, 6}, {1, 1, 1}, {1, 1, 1}, {1, 1, 1});
  EXPECT_TRUE(c.allFinite());
  EXPECT_NEAR((c - Vec3(1, 1, 1)).norm(), 0.0, 1e-15);
}

// A random mesh: a soup of small triangles in a unit box plus a few big ones, so queries meet
// every kind of region and box overlap.
geom::TriMesh randomMesh(std::mt19937_64& rng, int triangles) {
  std::uniform_real_distribution<double> u(-1, 1), small(-0.08, 0.08);
  geom::TriMesh m;
  for (int i = 0; i < triangles; ++i) {
    Vec3 c(u(rng), u(rng), u(rng));
    auto base = static_cast<std::uint32_t>(m.vertices.size());
    double s = i % 97 == 0 ? 10.0 : 1.0;
    for (int k = 0; k < 3; ++k) m.vertices.push_back(c + s * Vec3(small(rng), small(rng), small(rng)));
    m.triangles.push_back({base, base + 1, base + 2});
  }
  return m;
}

double bruteForce(const geom::TriMesh& m, const Vec3& q) {
  double best = std::numeric_limits<double>::infinity();
  for (const auto& t : m.triangles)
    best = std::min(best, (closestPointOnTriangle(q, m.vertices[t[0]], m.vertices[t[1]], m.vertices[t[2]]) - q).norm());
  return best;
}

std::vector<Vec3> randomQueries(std::mt19937_64& rng, int n, double extent) {
  std::uniform_real_distribution<double> u(-extent, extent);
  std::vector<Vec3> q(n);
  for (auto& p : q) p = Vec3(u(rng), u(rng), u(rng));
  return q;
}

TEST(MeshClosestPoint, MatchesBruteForceOnRandomMeshes) {
  std::mt19937_64 rng(42);
  for (int trial = 0; trial < 3; ++trial) {
    geom::TriMesh mesh = randomMesh(rng, 1500);
    // Shift far from the origin, as projected coordinates would be.
    const Vec3 shift = trial == 2 ? Vec3(5e5, 4e6, 250) : Vec3::Zero();
    for (auto& v : mesh.vertices) v += shift;
    MeshClosestPoint index(mesh);
    EXPECT_EQ(index.triangleCount(), mesh.triangles.size());
    std::vector<Vec3> queries = randomQueries(rng, 400, 1.3);
    for (auto& q : randomQueries(rng, 50, 20.0)) queries.push_back(q);
    for (auto& q : queries) q += shift;
    std::vector<ClosestHit> batch = index.queryAll(queries);
    ASSERT_EQ(batch.size(), queries.size());
    for (std::size_t i = 0; i < queries.size(); ++i) {
      const Vec3& q = queries[i];
      double expected = bruteForce(mesh, q);
      ClosestHit single = index.query(q);
      ASSERT_TRUE(single.found());
      ASSERT_TRUE(batch[i].found());
      EXPECT_NEAR(single.distance, expected, 1e-9 * expected + 1e-12) << "trial " << trial << " query " << i;
      EXPECT_NEAR(batch[i].distance, expected, 1e-9 * expected + 1e-12) << "trial " << trial << " query " << i;
      // The named triangle holds the returned point at the returned distance.
      const auto& t = mesh.triangles[batch[i].index];
      Vec3 c = closestPointOnTriangle(q, mesh.vertices[t[0]], mesh.vertices[t[1]], mesh.vertices[t[2]]);
      EXPECT_NEAR((c - batch[i].point).norm(), 0.0, 1e-9 * (1 + expected));
      EXPECT_NEAR((batch[i].point - q).norm(), batch[i].distance, 1e-9 * (1 + expected));
    }
  }
}

TEST(MeshClosestPoint, OptionsDoNotChangeAnswers) {
  std::mt19937_64 rng(7);
  geom::TriMesh mesh = randomMesh(rng, 800);
  std::vector<Vec3> queries = randomQueries(rng, 300, 1.2);
  MeshClosestPoint reference(mesh);
  std::vector<ClosestHit> expected = reference.queryAll(queries);
  for (int variant = 0; variant < 4; ++variant) {
    ClosestPointOptions o;
    o.leafSize = variant == 0 ? 1 : variant == 1 ? 16 : 4;
    o.mortonOrder = variant != 2;
    o.warmStart = variant != 3;
    o.blockSize = variant == 1 ? 1 : 64;
    MeshClosestPoint index(mesh, o);
    std::vector<ClosestHit> got = index.queryAll(queries);
    for (std::size_t i = 0; i < queries.size(); ++i)
      EXPECT_NEAR(got[i].distance, expected[i].distance, 1e-12) << "variant " << variant << " query " << i;
  }
}

geom::TriMesh unitSquare() {
  geom::TriMesh m;
  m.vertices = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  m.triangles = {{0, 1, 2}, {0, 2, 3}};
  return m;
}

TEST(MeshClosestPoint, MaxDistanceIsInclusiveAndDropsFartherQueries) {
  MeshClosestPoint index(unitSquare());
  ClosestHit hit = index.query({0.5, 0.5, 1.0}, 1.0);
  ASSERT_TRUE(hit.found());
  EXPECT_DOUBLE_EQ(hit.distance, 1.0);
  EXPECT_FALSE(index.query({0.5, 0.5, 1.0}, 0.999).found());
  std::vector<ClosestHit> hits = index.queryAll({{0.5, 0.5, 0.5}, {0.5, 0.5, 2}, {3, 0.5, 0}}, 1.5);
  EXPECT_TRUE(hits[0].found());
  EXPECT_DOUBLE_EQ(hits[0].distance, 0.5);
  EXPECT_FALSE(hits[1].found());
  EXPECT_TRUE(std::isinf(hits[1].distance));
  EXPECT_EQ(hits[1].index, -1);
  EXPECT_FALSE(hits[2].found());
}

// Queries so far away that squared distances overflow float (`compare` with points at
// 1e30 once never returned): the empty lanes of the 4-wide nodes lead back to the root and were skipped
// only by their infinite distance, which an infinite limit let through. Both ways round, one
// triangle (three empty lanes) and a mesh of several leaves; answers as the exact test gives them.
TEST(MeshClosestPoint, QueriesFarBeyondFloatRangeReturn) {
  const geom::TriMesh square = unitSquare();
  for (const double far : {1e20, 1e30, 1e100}) {
    geom::TriMesh one;
    one.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    one.triangles = {{0, 1, 2}};
    for (const geom::TriMesh* mesh : std::vector<const geom::TriMesh*>{&one, &square}) {
      MeshClosestPoint index(*mesh);
      const Vec3 q(far, far, far);
      const ClosestHit hit = index.query(q);
      ASSERT_TRUE(hit.found()) << far;
      const auto& t = mesh->triangles[hit.index];
      const Vec3 c = closestPointOnTriangle(q, mesh->vertices[t[0]], mesh->vertices[t[1]], mesh->vertices[t[2]]);
      EXPECT_NEAR(hit.distance, (c - q).norm(), 1e-9 * far);
      EXPECT_EQ(index.queryAll({q, -q}).size(), 2u);
    }
    // A mesh far away, queried from near the origin.
    geom::TriMesh moved = square;
    for (auto& v : moved.vertices) v += Vec3::Constant(far);
    MeshClosestPoint index(moved);
    const ClosestHit hit = index.query(Vec3::Zero());
    ASSERT_TRUE(hit.found()) << far;
    EXPECT_NEAR(hit.distance, Vec3::Constant(far).norm(), 1e-6 * far);
  }
}

TEST(MeshClosestPoint, EmptyAndBadInput) {
  MeshClosestPoint empty{geom::TriMesh{}};
  EXPECT_FALSE(empty.query({0, 0, 0}).found());
  EXPECT_TRUE(empty.queryAll({{0, 0, 0}, {1, 1, 1}})[1].index == -1);
  EXPECT_TRUE(empty.queryAll({}).empty());

  geom::TriMesh bad = unitSquare();
  bad.triangles.push_back({0, 1, 9});
  EXPECT_THROW(MeshClosestPoint{bad}, OptionsError);
  geom::TriMesh nan = unitSquare();
  nan.vertices[2].x() = std::nan("");
  EXPECT_THROW(MeshClosestPoint{nan}, OptionsError);
  ClosestPointOptions o;
  o.leafSize = 0;
  EXPECT_THROW(MeshClosestPoint(unitSquare(), o), OptionsError);

  MeshClosestPoint square(unitSquare());
  EXPECT_FALSE(square.query({std::nan(""), 0, 0}).found());
  EXPECT_FALSE(square.query({0, 0, 0}, -1.0).found());
}

TEST(MortonOrder, IsAPermutationThatGroupsNeighbours) {
  std::mt19937_64 rng(3);
  std::vector<Vec3> pts = randomQueries(rng, 2000, 1.0);
  std::vector<std::uint32_t> order = mortonOrder(pts);
  ASSERT_EQ(order.size(), pts.size());
  std::set<std::uint32_t> seen(order.begin(), order.end());
  EXPECT_EQ(seen.size(), pts.size());
  // Consecutive points in Morton order are much closer on average than in input order.
  double sortedStep = 0, inputStep = 0;
  for (std::size_t i = 1; i < pts.size(); ++i) {
    sortedStep += (pts[order[i]] - pts[order[i - 1]]).norm();
    inputStep += (pts[i] - pts[i - 1]).norm();
  }
  EXPECT_LT(sortedStep, 0.25 * inputStep);
  EXPECT_TRUE(mortonOrder({}).empty());
}

// Found by fuzz/closest_point_fuzz.cpp (fuzz/regressions/closest_point/morton_extent_overflows.bin):
// points spread near ±DBL_MAX made the box's extent inf, the cell scale 0 and inf × 0 a NaN cell
// index (undefined behaviour), so every code was the same and nothing was ordered.
TEST(MortonOrder, OrdersPointsSpreadAcrossTheWholeDoubleRange) {
  const double big = 1.5e308;
  const std::vector<Vec3> pts = {Vec3(big, big, big), Vec3(0, 0, 0), Vec3(-big, -big, -big)};
  EXPECT_EQ(mortonOrder(pts), (std::vector<std::uint32_t>{2, 1, 0}));
  const double tiny = 1e-310;  // subnormal extents: a permutation still
  std::vector<std::uint32_t> order = mortonOrder({Vec3(tiny, 0, 0), Vec3(0, 0, 0), Vec3(-tiny, 0, 0)});
  EXPECT_EQ(std::set<std::uint32_t>(order.begin(), order.end()).size(), 3u);
}

TEST(CloudClosestPoint, MatchesBruteForce) {
  std::mt19937_64 rng(11);
  geom::PointCloud cloud;
  cloud.positions = randomQueries(rng, 3000, 1.0);
  CloudClosestPoint index(cloud);
  EXPECT_EQ(index.pointCount(), 3000u);
  std::vector<Vec3> queries = randomQueries(rng, 300, 1.5);
  std::vector<ClosestHit> hits = index.queryAll(queries);
  for (std::size_t i = 0; i < queries.size(); ++i) {
    double best = std::numeric_limits<double>::infinity();
    for (const auto& p : cloud.positions) best = std::min(best, (p - queries[i]).norm());
    ASSERT_TRUE(hits[i].found());
    EXPECT_NEAR(hits[i].distance, best, 1e-12);
    EXPECT_NEAR((cloud.positions[hits[i].index] - queries[i]).norm(), best, 1e-12);
    EXPECT_NEAR(index.query(queries[i]).distance, best, 1e-12);
  }
}

TEST(CloudClosestPoint, MaxDistanceEmptyAndBadInput) {
  geom::PointCloud cloud;
  cloud.positions = {{0, 0, 0}, {10, 0, 0}};
  CloudClosestPoint index(cloud);
  EXPECT_TRUE(index.query({0, 0, 2}, 2.0).found());
  EXPECT_FALSE(index.query({0, 0, 2}, 1.9).found());
  EXPECT_FALSE(CloudClosestPoint(geom::PointCloud{}).query({0, 0, 0}).found());
  cloud.positions.push_back({std::nan(""), 0, 0});
  EXPECT_THROW(CloudClosestPoint{cloud}, OptionsError);
}

}  // namespace
}  // namespace treesketch::accel
