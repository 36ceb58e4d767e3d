#include "treesketch/compare/surface_sampling.h"

#include <gtest/gtest.h>

#include <cmath>
#include <set>

#include "test_meshes.h"
#include "treesketch/accel/closest_point.h"
#include "treesketch/util/error.h"

namespace treesketch::compare {
namespace {

using testing::grid;
using testing::icosphere;

TEST(SurfaceSampling, DefaultCountIsTheVertexCountPerKind) {
  geom::TriMesh m = grid(4, 1.0, 0.0);  // 25 vertices, 32 triangles
  SurfaceSamples s = sampleSurface(m, SamplingOptions{});
  EXPECT_EQ(s.vertexSamples, 25u);
  EXPECT_EQ(s.edgeSamples, 25u);
  EXPECT_EQ(s.faceSamples, 25u);
  EXPECT_EQ(s.size(), 75u);
  ASSERT_EQ(s.kinds.size(), s.size());
  ASSERT_EQ(s.vertex.size(), s.size());
  // Order: vertex, edge, face samples.
  for (std::size_t i = 0; i < s.size(); ++i) {
    SampleKind expected = i < 25 ? SampleKind::Vertex : i < 50 ? SampleKind::Edge : SampleKind::Face;
    EXPECT_EQ(s.kinds[i], expected) << i;
  }
}

TEST(SurfaceSampling, KindsAndCountsAreSwitchable) {
  geom::TriMesh m = grid(4, 1.0, 0.0);
  SamplingOptions o;
  o.count = 10;
  o.edges = false;
  SurfaceSamples s = sampleSurface(m, o);
  EXPECT_EQ(s.vertexSamples, 10u);
  EXPECT_EQ(s.edgeSamples, 0u);
  EXPECT_EQ(s.faceSamples, 10u);
  o.count = 1000;  // more than the vertices: all 25 of them, but 1000 of the others
  o.edges = true;
  o.faces = false;
  s = sampleSurface(m, o);
  EXPECT_EQ(s.vertexSamples, 25u);
  EXPECT_EQ(s.edgeSamples, 1000u);
  EXPECT_EQ(s.faceSamples, 0u);
  o.vertices = false;
  o.faces = true;
  s = sampleSurface(m, o);
  EXPECT_EQ(s.vertexSamples, 0u);
  EXPECT_EQ(s.size(), 2000u);
}

TEST(SurfaceSampling, VertexSamplesAreVerticesWithTheirIndex) {
  geom::TriMesh m = icosphere(2.0, 2);
  m.vertices.push_back({100, 100, 100});  // unused by any triangle: never sampled
  SamplingOptions o;
  o.edges = o.faces = false;
  SurfaceSamples all = sampleSurface(m, o);
  EXPECT_EQ(all.vertexSamples, m.vertices.size() - 1);
  for (std::size_t i = 0; i < all.size(); ++i) {
    ASSERT_GE(all.vertex[i], 0);
    EXPECT_EQ(all.points[i], m.vertices[all.vertex[i]]);
  }
  o.count = 50;
  SurfaceSamples subset = sampleSurface(m, o);
  ASSERT_EQ(subset.vertexSamples, 50u);
  std::set<std::int64_t> distinct(subset.vertex.begin(), subset.vertex.end());
  EXPECT_EQ(distinct.size(), 50u);
  for (std::size_t i = 0; i < subset.size(); ++i) EXPECT_EQ(subset.points[i], m.vertices[subset.vertex[i]]);
}

TEST(SurfaceSampling, EdgeSamplesAreEvenlySpacedAndAvoidVertices) {
  // One right triangle with sides 3, 4, 5: total 12; 12 samples -> one per unit of length, at
  // half-units from the edge starts: 3, 4 and 5 samples on the sides.
  geom::TriMesh m;
  m.vertices = {{0, 0, 0}, {3, 0, 0}, {0, 4, 0}};
  m.triangles = {{0, 1, 2}};
  SamplingOptions o;
  o.vertices = o.faces = false;
  o.count = 12;
  SurfaceSamples s = sampleSurface(m, o);
  ASSERT_EQ(s.edgeSamples, 12u);
  int onX = 0, onY = 0, onHyp = 0;
  for (const auto& p : s.points) {
    EXPECT_EQ(p.z(), 0.0);
    for (const auto& v : m.vertices) EXPECT_GE((p - v).norm(), 0.5 - 1e-12);
    if (std::abs(p.y()) < 1e-12)
      ++onX;
    else if (std::abs(p.x()) < 1e-12)
      ++onY;
    else {
      EXPECT_NEAR(p.x() / 3 + p.y() / 4, 1.0, 1e-12);
      ++onHyp;
    }
  }
  EXPECT_EQ(onX, 3);
  EXPECT_EQ(onY, 4);
  EXPECT_EQ(onHyp, 5);
  for (std::size_t i = 1; i < s.size(); ++i) EXPECT_EQ(s.vertex[i], -1);
}

TEST(SurfaceSampling, SharedEdgesAreSampledOnce) {
  // Two triangles sharing the diagonal of a unit square: 5 unique edges, total 4 + sqrt 2.
  geom::TriMesh m = grid(1, 1.0, 0.0);
  SamplingOptions o;
  o.vertices = o.faces = false;
  o.count = 1000;
  SurfaceSamples s = sampleSurface(m, o);
  int onDiagonal = 0;
  for (const auto& p : s.points)
    if (std::abs(p.x() - p.y()) < 1e-12) ++onDiagonal;
  const double expected = 1000 * std::sqrt(2.0) / (4 + std::sqrt(2.0));
  EXPECT_NEAR(onDiagonal, expected, 1.0);
}

TEST(SurfaceSampling, FaceSamplesAreOnTheSurfaceAndAreaWeighted) {
  // Triangle areas 0.5 and 1.5.
  geom::TriMesh m;
  m.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {10, 0, 0}, {13, 0, 0}, {10, 1, 0}};
  m.triangles = {{0, 1, 2}, {3, 4, 5}};
  SamplingOptions o;
  o.vertices = o.edges = false;
  o.count = 20000;
  SurfaceSamples s = sampleSurface(m, o);
  ASSERT_EQ(s.faceSamples, 20000u);
  accel::MeshClosestPoint index(m);
  int onSmall = 0;
  for (const auto& p : s.points) {
    ASSERT_LT(index.query(p).distance, 1e-12);
    if (p.x() < 5) ++onSmall;
  }
  EXPECT_NEAR(onSmall / 20000.0, 0.25, 0.015);
}

TEST(SurfaceSampling, SameSeedSameSamplesAndKindsUseSeparateStreams) {
  geom::TriMesh m = icosphere(1.0, 2);
  SamplingOptions o;
  o.count = 30;
  o.seed = 9;
  SurfaceSamples a = sampleSurface(m, o), b = sampleSurface(m, o);
  EXPECT_EQ(a.points, b.points);
  o.seed = 10;
  SurfaceSamples c = sampleSurface(m, o);
  EXPECT_NE(a.points, c.points);
  // Switching edges off leaves the vertex and face samples as they were.
  o.seed = 9;
  o.edges = false;
  SurfaceSamples d = sampleSurface(m, o);
  ASSERT_EQ(d.size(), 60u);
  for (int i = 0; i < 30; ++i) EXPECT_EQ(d.points[i], a.points[i]);
  for (int i = 0; i < 30; ++i) EXPECT_EQ(d.points[30 + i], a.points[60 + i]);
}

TEST(SurfaceSampling, EmptyDegenerateAndBadMeshes) {
  EXPECT_EQ(sampleSurface(geom::TriMesh{}, {}).size(), 0u);
  geom::TriMesh flat;  // all three corners at one point: no edge or face samples
  flat.vertices = {{1, 1, 1}, {1, 1, 1}, {1, 1, 1}};
  flat.triangles = {{0, 1, 2}};
  SurfaceSamples s = sampleSurface(flat, {});
  EXPECT_EQ(s.vertexSamples, 3u);
  EXPECT_EQ(s.edgeSamples, 0u);
  EXPECT_EQ(s.faceSamples, 0u);
  geom::TriMesh bad = grid(1, 1.0, 0.0);
  bad.triangles.push_back({0, 1, 7});
  EXPECT_THROW(sampleSurface(bad, {}), OptionsError);
}

TEST(SurfaceSampling, CloudSamplesAllPointsOrASubset) {
  geom::PointCloud cloud;
  for (int i = 0; i < 100; ++i) cloud.positions.push_back({double(i), 0, 0});
  SurfaceSamples all = sampleCloud(cloud, {});
  EXPECT_EQ(all.vertexSamples, 100u);
  SamplingOptions o;
  o.count = 10;
  SurfaceSamples sub = sampleCloud(cloud, o);
  ASSERT_EQ(sub.size(), 10u);
  for (std::size_t i = 0; i < sub.size(); ++i) EXPECT_EQ(sub.points[i].x(), double(sub.vertex[i]));
  EXPECT_EQ(sampleCloud(geom::PointCloud{}, {}).size(), 0u);
}

}  // namespace
}  // namespace treesketch::compare
