// Tests of accel::RayScene: nearest hits against known geometry and a brute-force ray caster,
// misses, several meshes, large coordinates, the batch call, bad input.
#include "treesketch/accel/ray_scene.h"

#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <random>

#include "scan/scan_test_meshes.h"
#include "treesketch/util/error.h"

namespace {

using treesketch::OptionsError;
using treesketch::accel::Ray;
using treesketch::accel::RayHit;
using treesketch::accel::RayScene;
using treesketch::geom::TriMesh;
using treesketch::geom::Vec3;
namespace tt = treesketch::test;

TEST(RayScene, HitsSingleTriangleAtKnownPoint) {
  TriMesh m;
  m.vertices = {Vec3(0, 0, 0), Vec3(2, 0, 0), Vec3(0, 2, 0)};
  m.triangles = {{0, 1, 2}};
  const RayScene scene(m);
  const RayHit h = scene.intersect(Vec3(0.5, 0.25, 3), Vec3(0, 0, -2));
  ASSERT_TRUE(h.hit());
  EXPECT_EQ(h.meshIndex, 0);
  EXPECT_EQ(h.primId, 0u);
  EXPECT_NEAR(h.t, 1.5, 1e-12);  // t in units of |dir| = 2
  EXPECT_NEAR((h.point - Vec3(0.5, 0.25, 0)).norm(), 0.0, 1e-12);
  EXPECT_EQ(scene.meshCount(), 1u);
  EXPECT_EQ(scene.triangleCount(), 1u);
}

TEST(RayScene, MissesAndRangeLimits) {
  const RayScene scene(tt::makeBox(Vec3(-1, -1, -1), Vec3(1, 1, 1)));
  EXPECT_FALSE(scene.intersect(Vec3(0, 0, 5), Vec3(0, 0, 1)).hit());             // pointing away
  EXPECT_FALSE(scene.intersect(Vec3(3, 0, 5), Vec3(0, 0, -1)).hit());            // passes beside
  EXPECT_FALSE(scene.intersect(Vec3(0, 0, 5), Vec3(0, 0, -1), 0.0, 3.9).hit());  // tfar short of the box
  const RayHit far = scene.intersect(Vec3(0, 0, 5), Vec3(0, 0, -1), 4.5);        // tnear skips the top face
  ASSERT_TRUE(far.hit());
  EXPECT_NEAR(far.point.z(), -1.0, 1e-12);
  // Degenerate rays miss rather than throw.
  EXPECT_FALSE(scene.intersect(Vec3(0, 0, 5), Vec3::Zero()).hit());
  EXPECT_FALSE(scene.intersect(Vec3(NAN, 0, 5), Vec3(0, 0, -1)).hit());
  EXPECT_FALSE(scene.intersect(Vec3(0, 0, 5), Vec3(0, 0, -1), 2.0, 1.0).hit());
}

TEST(RayScene, NearestOfSeveralMeshesWithEmptyMeshKeepingIndices) {
  std::vector<TriMesh> meshes;
  meshes.push_back(tt::makeBox(Vec3(-1, -1, -1), Vec3(1, 1, 1)));
  meshes.push_back(TriMesh{});  // empty: never hit, index kept
  meshes.push_back(tt::makeBox(Vec3(-1, -1, 3), Vec3(1, 1, 4)));
  const RayScene scene(meshes);
  EXPECT_EQ(scene.meshCount(), 3u);
  EXPECT_EQ(scene.triangleCount(), 24u);
  const RayHit fromTop = scene.intersect(Vec3(0.1, 0.2, 10), Vec3(0, 0, -1));
  ASSERT_TRUE(fromTop.hit());
  EXPECT_EQ(fromTop.meshIndex, 2);
  EXPECT_NEAR(fromTop.point.z(), 4.0, 1e-12);
  const RayHit fromBelow = scene.intersect(Vec3(0.1, 0.2, -10), Vec3(0, 0, 1));
  ASSERT_TRUE(fromBelow.hit());
  EXPECT_EQ(fromBelow.meshIndex, 0);
  EXPECT_NEAR(fromBelow.point.z(), -1.0, 1e-12);
  // The primitive index refers to the hit mesh's own triangles.
  const auto& tri = meshes[0].triangles[fromBelow.primId];
  EXPECT_NEAR(tt::pointTriangleDistance(fromBelow.point, meshes[0].vertices[tri[0]], meshes[0].vertices[tri[1]],
                                        meshes[0].vertices[tri[2]]),
              0.0, 1e-12);
}

TEST(RayScene, AgreesWithBruteForceOnRandomRays) {
  TriMesh m = tt::makeTube(Vec3(0, 0, 0), 0.3, 2.0, 24);
  m.append(tt::makeTube(Vec3(0.5, 0.1, 0.5), 0.15, 1.0, 12));
  const RayScene scene(m);
  const double diag = m.bounds().diagonal();
  std::mt19937_64 rng(42);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  int hits = 0, agree = 0, total = 2000;
  for (int i = 0; i < total; ++i) {
    const Vec3 o(3 * u(rng), 3 * u(rng), 1 + 3 * u(rng));
    const Vec3 target(0.4 * u(rng), 0.4 * u(rng), 1 + 1.2 * u(rng));
    const Vec3 d = target - o;
    const RayHit h = scene.intersect(o, d);
    const double tb = tt::bruteForceRay(o, d, m);
    if (h.hit() == std::isfinite(tb) && (!h.hit() || std::abs(h.t - tb) < 1e-9 * d.norm() + 1e-9)) ++agree;
    if (h.hit()) {
      ++hits;
      EXPECT_LE(tt::pointMeshDistance(h.point, m), 1e-6 * diag);
      EXPECT_NEAR((h.point - (o + h.t * d)).norm(), 0.0, 1e-12 * diag);
    }
  }
  EXPECT_GT(hits, total / 4);
  EXPECT_LT(hits, total);
  // Rays grazing an edge may legitimately disagree (float vs double); allow a handful.
  EXPECT_GE(agree, total - 5);
}

TEST(RayScene, KeepsPrecisionAtLargeCoordinates) {
  const Vec3 offset(512345.678, 5234567.891, 250.0);  // UTM-like
  TriMesh m = tt::makeBox(offset + Vec3(-1, -1, -1), offset + Vec3(1, 1, 1));
  const RayScene scene(m);
  const RayHit h = scene.intersect(offset + Vec3(0.123456, -0.654321, 20), Vec3(0, 0, -1));
  ASSERT_TRUE(h.hit());
  EXPECT_NEAR(h.point.x(), offset.x() + 0.123456, 1e-9);
  EXPECT_NEAR(h.point.y(), offset.y() - 0.654321, 1e-9);
  EXPECT_NEAR(h.point.z(), offset.z() + 1.0, 1e-9);
}

TEST(RayScene, BatchMatchesSingleRaysInOrder) {
  const TriMesh m = tt::makeTube(Vec3(0, 0, 0), 0.5, 2.0, 16);
  const RayScene scene(m);
  std::vector<Ray> rays;
  for (int i = 0; i < 5000; ++i) {
    Ray r;
    const double a = 0.01 * i;
    r.origin = Vec3(3 * std::cos(a), 3 * std::sin(a), 0.0004 * i - 0.5);
    r.dir = Vec3(0, 0, 0.0004 * i - 0.5) - r.origin + Vec3(0, 0, 1);
    rays.push_back(r);
  }
  std::atomic<std::uint64_t> lastDone{0}, lastTotal{0};
  const std::vector<RayHit> hits = scene.intersectAll(rays, [&](std::uint64_t done, std::uint64_t total) {
    std::uint64_t prev = lastDone.load();
    while (done > prev && !lastDone.compare_exchange_weak(prev, done)) {
    }
    lastTotal = total;
  });
  ASSERT_EQ(hits.size(), rays.size());
  int nHit = 0;
  for (std::size_t i = 0; i < rays.size(); ++i) {
    const RayHit one = scene.intersect(rays[i]);
    ASSERT_EQ(one.hit(), hits[i].hit()) << i;
    if (one.hit()) {
      ++nHit;
      EXPECT_EQ(one.point, hits[i].point);
    }
  }
  EXPECT_GT(nHit, 0);
  EXPECT_LT(nHit, static_cast<int>(rays.size()));
  EXPECT_EQ(lastDone.load(), rays.size());
  EXPECT_EQ(lastTotal.load(), rays.size());
  EXPECT_TRUE(scene.intersectAll({}).empty());
}

TEST(RayScene, EmptySceneMissesEverything) {
  const RayScene none(std::vector<TriMesh>{});
  EXPECT_EQ(none.meshCount(), 0u);
  EXPECT_TRUE(none.bounds().empty());
  EXPECT_FALSE(none.intersect(Vec3(0, 0, 0), Vec3(1, 0, 0)).hit());
  const RayScene emptyMesh(TriMesh{});
  EXPECT_EQ(emptyMesh.meshCount(), 1u);
  EXPECT_FALSE(emptyMesh.intersect(Vec3(0, 0, 0), Vec3(1, 0, 0)).hit());
}

TEST(RayScene, RejectsBadMeshes) {
  TriMesh badIndex;
  badIndex.vertices = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)};
  badIndex.triangles = {{0, 1, 3}};
  EXPECT_THROW(RayScene{badIndex}, OptionsError);
  TriMesh nan = badIndex;
  nan.triangles = {{0, 1, 2}};
  nan.vertices[1].x() = NAN;
  EXPECT_THROW(RayScene{nan}, OptionsError);
  TriMesh inf = badIndex;
  inf.triangles = {{0, 1, 2}};
  inf.vertices[2].z() = INFINITY;
  EXPECT_THROW(RayScene(std::vector<TriMesh>{TriMesh{}, inf}), OptionsError);
}

TEST(RayScene, BuildQualitiesGiveTheSameHits) {
  const TriMesh m = tt::makeTube(Vec3(0, 0, 0), 0.5, 2.0, 32);
  for (auto q : {treesketch::accel::BuildQuality::Low, treesketch::accel::BuildQuality::Medium,
                 treesketch::accel::BuildQuality::High}) {
    const RayScene scene(m, {q});
    const RayHit h = scene.intersect(Vec3(5, 0.01, 1.0), Vec3(-1, 0, 0));
    ASSERT_TRUE(h.hit());
    EXPECT_NEAR(h.point.z(), 1.0, 1e-12);
    EXPECT_LE(tt::pointMeshDistance(h.point, m), 1e-9);
  }
}

}  // namespace
