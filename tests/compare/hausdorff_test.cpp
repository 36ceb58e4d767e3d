#include "treesketch/compare/hausdorff.h"

#include <gtest/gtest.h>

#include <cmath>

#include "test_meshes.h"
#include "treesketch/accel/closest_point.h"
#include "treesketch/util/error.h"

namespace treesketch::compare {
namespace {

using testing::grid;
using testing::icosphere;
using testing::innerRadius;
using testing::randomSoup;

TEST(Hausdorff, MeshAgainstItselfIsZero) {
  geom::TriMesh m = icosphere(3.0, 3);
  CompareOptions o;
  o.keepSamples = true;
  DistanceReport r = compareMeshes(m, m, o);
  EXPECT_EQ(r.samplesUsed, 3 * m.vertices.size());
  EXPECT_EQ(r.samplesDropped, 0u);
  EXPECT_LT(r.max, 1e-12);
  EXPECT_LT(r.rms, 1e-12);
  EXPECT_DOUBLE_EQ(r.diagonal, m.bounds().diagonal());
  for (double d : r.distances) EXPECT_LT(d, 1e-12);
}

TEST(Hausdorff, ConcentricSpheresGiveTheRadiusDifferenceWithinTheFacetingError) {
  const double r1 = 1.0, r2 = 1.25;
  geom::TriMesh inner = icosphere(r1, 4), outer = icosphere(r2, 4);
  // Each mesh lies between its inscribed radius (nearest triangle plane) and its sphere.
  const double e1 = r1 - innerRadius(inner), e2 = r2 - innerRadius(outer);
  ASSERT_LT(e1, 0.005);
  ASSERT_LT(e2, 0.005);
  CompareOptions o;
  o.keepSamples = true;
  BothReport both = compareBoth(inner, outer, o);
  // A point at radius r in [r1 - e1, r1] is at least (r2 - e2) - r1 and at most r2 - (r1 - e1)
  // from the outer mesh (which lies in the shell [r2 - e2, r2] and meets every ray from the centre).
  const double lo = r2 - e2 - r1, hi = r2 - r1 + e1;
  for (double d : both.forward.distances) {
    EXPECT_GE(d, lo - 1e-12);
    EXPECT_LE(d, hi + 1e-12);
  }
  for (double d : both.backward.distances) {
    EXPECT_GE(d, lo - 1e-12);
    EXPECT_LE(d, hi + 1e-12);
  }
  EXPECT_NEAR(both.forward.mean, r2 - r1, e1 + e2);
  EXPECT_NEAR(both.backward.rms, r2 - r1, e1 + e2);
  EXPECT_DOUBLE_EQ(both.hausdorff, std::max(both.forward.max, both.backward.max));
  EXPECT_DOUBLE_EQ(both.hausdorffPercent, 100 * both.hausdorff / inner.bounds().diagonal());
  // Vertex samples of the outer sphere lie exactly at r2; the inner mesh is within [r1 - e1, r1].
  for (std::size_t i = 0; i < both.backward.distances.size(); ++i)
    if (both.backward.sampleKinds[i] == SampleKind::Vertex) {
      EXPECT_GE(both.backward.distances[i], r2 - r1 - 1e-12);
      EXPECT_LE(both.backward.distances[i], r2 - r1 + e1 + 1e-12);
    }
}

TEST(Hausdorff, ParallelPlanesGiveTheExactOffset) {
  geom::TriMesh a = grid(6, 2.0, 0.0), b = grid(3, 2.0, 0.375);
  CompareOptions o;
  o.sampling.count = 500;
  BothReport both = compareBoth(a, b, o);
  for (const DistanceReport* r : {&both.forward, &both.backward}) {
    EXPECT_EQ(r->samplesDropped, 0u);
    EXPECT_NEAR(r->min, 0.375, 1e-12);
    EXPECT_NEAR(r->max, 0.375, 1e-12);
    EXPECT_NEAR(r->mean, 0.375, 1e-12);
    EXPECT_NEAR(r->rms, 0.375, 1e-12);
  }
  EXPECT_NEAR(both.hausdorff, 0.375, 1e-12);
  EXPECT_NEAR(both.forward.percent(both.forward.max), 100 * 0.375 / std::sqrt(8.0), 1e-9);
  EXPECT_EQ(both.forward.vertexSamples, 49u);
  EXPECT_EQ(both.forward.edgeSamples, 500u);
  EXPECT_EQ(both.forward.faceSamples, 500u);
}

TEST(Hausdorff, EverySampleMatchesBruteForce) {
  geom::TriMesh a = randomSoup(1, 60), b = randomSoup(2, 300);
  CompareOptions o;
  o.keepSamples = true;
  o.sampling.count = 200;
  DistanceReport r = compareMeshes(a, b, o);
  SurfaceSamples s = sampleSurface(a, o.sampling);
  ASSERT_EQ(r.distances.size(), s.size());
  for (std::size_t i = 0; i < s.size(); ++i) {
    double best = std::numeric_limits<double>::infinity();
    for (const auto& t : b.triangles)
      best = std::min(
          best, (accel::closestPointOnTriangle(s.points[i], b.vertices[t[0]], b.vertices[t[1]], b.vertices[t[2]]) -
                 s.points[i])
                    .norm());
    EXPECT_NEAR(r.distances[i], best, 1e-9 * best + 1e-15) << i;
  }
}

TEST(Hausdorff, SameSeedSameReport) {
  geom::TriMesh a = randomSoup(3, 200), b = randomSoup(4, 200);
  CompareOptions o;
  o.keepSamples = true;
  o.sampling.seed = 77;
  nlohmann::json first = toJson(compareBoth(a, b, o)), second = toJson(compareBoth(a, b, o));
  EXPECT_EQ(first.dump(), second.dump());
  o.sampling.seed = 78;
  EXPECT_NE(toJson(compareBoth(a, b, o)).dump(), first.dump());
}

TEST(Hausdorff, SamplesBeyondTheSearchDistanceAreDroppedAndCounted) {
  // Target: unit square at z = 0. Sampled: a square at z = 0.1 above it and one at z = 3 beside.
  geom::TriMesh target = grid(2, 1.0, 0.0);
  geom::TriMesh sampled = grid(2, 1.0, 0.1), far = grid(2, 1.0, 3.0);
  sampled.append(far);
  CompareOptions o;
  o.maxDistance = 0.5;
  o.keepSamples = true;
  DistanceReport r = compareMeshes(sampled, target, o);
  SurfaceSamples s = sampleSurface(sampled, o.sampling);
  std::uint64_t high = 0;
  for (const auto& p : s.points) high += p.z() > 1 ? 1 : 0;
  ASSERT_GT(high, 0u);
  EXPECT_EQ(r.samplesDropped, high);
  EXPECT_EQ(r.samplesUsed, s.size() - high);
  EXPECT_NEAR(r.max, 0.1, 1e-12);
  EXPECT_DOUBLE_EQ(r.maxDistance, 0.5);
  for (std::size_t i = 0; i < s.size(); ++i) EXPECT_EQ(std::isinf(r.distances[i]), s.points[i].z() > 1);

  // As a fraction of the sampled diagonal: 0.01 * diag < 0.1, so everything is dropped.
  CompareOptions f;
  f.maxDistanceFraction = 0.01;
  DistanceReport none = compareMeshes(sampled, target, f);
  EXPECT_EQ(none.samplesUsed, 0u);
  EXPECT_NEAR(none.maxDistance, 0.01 * sampled.bounds().diagonal(), 1e-15);
  EXPECT_TRUE(std::isnan(none.max));
}

TEST(Hausdorff, PointCloudTargetsAndSources) {
  // Cloud: a dense grid of points at z = 0.2 (spacing 0.01): a mesh sample at z = 0 is between
  // 0.2 and sqrt(0.2² + 2 · 0.005²) from it.
  geom::PointCloud cloud;
  for (int j = 0; j <= 100; ++j)
    for (int i = 0; i <= 100; ++i) cloud.positions.push_back({i * 0.01, j * 0.01, 0.2});
  geom::TriMesh plane = grid(4, 1.0, 0.0);
  DistanceReport toCloud = compareMeshToCloud(plane, cloud, {});
  EXPECT_GE(toCloud.min, 0.2 - 1e-12);
  EXPECT_LE(toCloud.max, std::sqrt(0.04 + 2 * 0.005 * 0.005) + 1e-12);
  // The cloud's points against the plane: exactly 0.2 each.
  DistanceReport fromCloud = compareCloudToMesh(cloud, plane, {});
  EXPECT_EQ(fromCloud.samplesUsed, cloud.size());
  EXPECT_EQ(fromCloud.vertexSamples, cloud.size());
  EXPECT_NEAR(fromCloud.min, 0.2, 1e-12);
  EXPECT_NEAR(fromCloud.max, 0.2, 1e-12);
}

TEST(Hausdorff, BadInputThrows) {
  geom::TriMesh m = grid(2, 1.0, 0.0);
  EXPECT_THROW(compareMeshes(geom::TriMesh{}, m, {}), OptionsError);
  EXPECT_THROW(compareMeshes(m, geom::TriMesh{}, {}), OptionsError);
  geom::TriMesh nan = m;
  nan.vertices[3].y() = std::nan("");
  EXPECT_THROW(compareMeshes(nan, m, {}), OptionsError);
  EXPECT_THROW(compareMeshes(m, nan, {}), OptionsError);
  geom::TriMesh badIndex = m;
  badIndex.triangles.push_back({0, 1, 99});
  EXPECT_THROW(compareMeshes(badIndex, m, {}), OptionsError);
  CompareOptions o;
  o.sampling.vertices = o.sampling.edges = o.sampling.faces = false;
  EXPECT_THROW(compareMeshes(m, m, o), OptionsError);
  o = {};
  o.maxDistance = -1;
  EXPECT_THROW(compareMeshes(m, m, o), OptionsError);
  o = {};
  o.histogramBins = 0;
  EXPECT_THROW(compareMeshes(m, m, o), OptionsError);
  EXPECT_THROW(compareMeshToCloud(m, geom::PointCloud{}, {}), OptionsError);
  EXPECT_THROW(compareCloudToMesh(geom::PointCloud{}, m, {}), OptionsError);
}

TEST(Hausdorff, VertexDistancesFromReportsAndQueries) {
  geom::TriMesh a = grid(3, 1.0, 0.25), b = grid(2, 1.0, 0.0);
  CompareOptions o;
  o.keepSamples = true;
  o.sampling.count = 5;  // a subset of the 16 vertices
  DistanceReport r = compareMeshes(a, b, o);
  std::vector<double> d = vertexDistancesFromReport(r, a.vertices.size());
  int known = 0;
  for (double x : d) known += std::isnan(x) ? 0 : 1;
  EXPECT_EQ(known, 5);
  fillVertexDistances(a, b, std::numeric_limits<double>::infinity(), d);
  ASSERT_EQ(d.size(), a.vertices.size());
  for (double x : d) EXPECT_NEAR(x, 0.25, 1e-12);
  std::vector<double> limited;
  fillVertexDistances(a, b, 0.1, limited);
  for (double x : limited) EXPECT_TRUE(std::isinf(x));
  geom::PointCloud cloud;
  cloud.positions = b.vertices;
  std::vector<double> toCloud;
  fillVertexDistances(a, cloud, std::numeric_limits<double>::infinity(), toCloud);
  for (double x : toCloud) EXPECT_GE(x, 0.25 - 1e-12);
}

TEST(Hausdorff, BothReportJson) {
  BothReport both = compareBoth(grid(2, 1.0, 0.0), grid(2, 1.0, 0.5), {});
  nlohmann::json j = toJson(both);
  EXPECT_TRUE(j.contains("forward"));
  EXPECT_TRUE(j.contains("backward"));
  EXPECT_NEAR(j["hausdorff"].get<double>(), 0.5, 1e-12);
  EXPECT_NEAR(j["forward"]["rms"].get<double>(), 0.5, 1e-12);
}

}  // namespace
}  // namespace treesketch::compare
