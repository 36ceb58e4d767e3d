#include "treesketch/sketch/auto_sketch.h"

#include <gtest/gtest.h>

#include <random>

#include "treesketch/util/error.h"

namespace treesketch::sketch {
namespace {

using geom::Vec2;
using geom::Vec3;

/// A noisy vertical cylinder surface (radius r, height h, Y up) with a crown blob on top.
geom::PointCloud treeCloud(double r = 0.3, double h = 8.0, std::size_t n = 4000) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  geom::PointCloud c;
  for (std::size_t i = 0; i < n; ++i) {
    double a = 2 * M_PI * u(rng), y = h * u(rng);
    c.positions.emplace_back(r * std::cos(a), y, r * std::sin(a));
  }
  for (std::size_t i = 0; i < n / 4; ++i)
    c.positions.emplace_back(3.0 * (u(rng) - 0.5), h + 2.0 * u(rng), 3.0 * (u(rng) - 0.5));
  return c;
}

TEST(DefaultSampling, ScalesWithTheDiagonal) {
  geom::BBox box;
  box.add(Vec3(0, 0, 0));
  box.add(Vec3(3, 4, 12));  // diagonal 13
  SamplingParams p = defaultSamplingFor(box);
  EXPECT_DOUBLE_EQ(p.sliceHalfThickness, 0.004 * 13);
  EXPECT_DOUBLE_EQ(p.lineEpsilon, 0.02 * 13);
  EXPECT_DOUBLE_EQ(p.lineEpsilonStep, 0.02 * 13);
  EXPECT_TRUE(p.enabled);
  SamplingScale s;
  s.lineEpsilonFraction = 0.1;
  EXPECT_DOUBLE_EQ(defaultSamplingFor(box, s).lineEpsilon, 1.3);
  EXPECT_THROW(defaultSamplingFor(geom::BBox{}), OptionsError);
  geom::BBox point;
  point.add(Vec3(1, 1, 1));
  EXPECT_THROW(defaultSamplingFor(point), OptionsError);
  s.sliceHalfThicknessFraction = 0;
  EXPECT_THROW(defaultSamplingFor(box, s), OptionsError);
}

void checkUniform(const geom::PointCloud& cloud, const geom::Camera& cam, int count) {
  Sketch sk = uniformAutoSketch(cloud, cam, count, geom::UpAxis::Y);
  ASSERT_NO_THROW(sk.validate());
  ASSERT_EQ(sk.size(), static_cast<std::size_t>(count));
  ASSERT_EQ(sk.cameras().size(), 1u);
  // Screen extent of the cloud.
  double yMin = 1e300, yMax = -1e300, xMin = 1e300, xMax = -1e300;
  for (const Vec3& p : cloud.positions) {
    Vec3 s = cam.project(p);
    yMin = std::min(yMin, s.y()), yMax = std::max(yMax, s.y());
    xMin = std::min(xMin, s.x()), xMax = std::max(xMax, s.x());
  }
  double band = (yMax - yMin) / count;
  // One chain from the root (bottom, largest y) to the top.
  std::vector<NodeId> order = sk.topologicalOrder();
  ASSERT_EQ(order.size(), static_cast<std::size_t>(count));
  for (std::size_t i = 0; i < order.size(); ++i) {
    const Node& n = sk.node(order[i]);
    EXPECT_LE(n.children.size(), 1u);
    if (i + 1 < order.size()) EXPECT_EQ(n.children.front(), order[i + 1]);
    EXPECT_NEAR(n.screen.x(), 0.5 * (xMin + xMax), 1e-9);
    EXPECT_NEAR(n.screen.y(), yMax - (i + 0.5) * band, 1e-6);
    EXPECT_GT(n.screen.y(), yMin);
    EXPECT_LT(n.screen.y(), yMax);
    EXPECT_GE(n.screen.x(), cam.viewport.x);
    EXPECT_LE(n.screen.x(), cam.viewport.x + cam.viewport.width);
    if (i > 0) EXPECT_LT(n.screen.y(), sk.node(order[i - 1]).screen.y());  // going up the screen
    // Maximal sizes: every point of the slice within lineEpsilon of the line, and not much more.
    NodeGeometry g = sk.geometry(order[i]);
    double far = 0;
    for (const Vec3& p : cloud.positions) {
      Vec3 r = p - g.linePoint;
      if (std::abs(r.dot(g.planeNormal)) > n.params.sliceHalfThickness) continue;
      far = std::max(far, (r - g.lineDir * g.lineDir.dot(r)).norm());
    }
    EXPECT_GT(far, 0.0);
    EXPECT_GE(n.params.lineEpsilon, far);
    EXPECT_LT(n.params.lineEpsilon, far * 1.001);
    EXPECT_EQ(n.params.lineEpsilonStep, n.params.lineEpsilon);
  }
}

TEST(UniformAutoSketch, FrontPerspective) {
  geom::PointCloud cloud = treeCloud();
  geom::Camera cam = geom::presetCamera(geom::PresetView::Front, cloud.bounds(), geom::UpAxis::Y, {0, 0, 800, 600}, false);
  checkUniform(cloud, cam, 18);
}

TEST(UniformAutoSketch, OrthographicSlicesTileTheHeight) {
  geom::PointCloud cloud = treeCloud();
  geom::Camera cam = geom::presetCamera(geom::PresetView::Side, cloud.bounds(), geom::UpAxis::Y, {0, 0, 640, 640}, true);
  checkUniform(cloud, cam, 10);
  Sketch sk = uniformAutoSketch(cloud, cam, 10, geom::UpAxis::Y);
  // Horizontal slices (vertical chain), each 2 × half-thickness = height / 10.
  double height = cloud.bounds().extent().y();
  for (NodeId id : sk.ids()) {
    EXPECT_NEAR(2 * sk.node(id).params.sliceHalfThickness, height / 10, 1e-6 * height);
    EXPECT_NEAR(std::abs(sk.geometry(id).planeNormal.y()), 1.0, 1e-9);
  }
  // Together the slabs cover every point.
  std::vector<NodeGeometry> geoms;
  for (NodeId id : sk.ids()) geoms.push_back(sk.geometry(id));
  for (const Vec3& p : cloud.positions) {
    bool covered = false;
    for (std::size_t k = 0; k < geoms.size(); ++k)
      covered |= std::abs((p - geoms[k].planePoint).dot(geoms[k].planeNormal)) <=
                 sk.node(sk.ids()[k]).params.sliceHalfThickness + 1e-9;
    ASSERT_TRUE(covered) << p.transpose();
  }
}

TEST(UniformAutoSketch, SingleNodeAndBadInput) {
  geom::PointCloud cloud = treeCloud();
  geom::Camera cam = geom::presetCamera(geom::PresetView::Front, cloud.bounds(), geom::UpAxis::Y, {}, true);
  checkUniform(cloud, cam, 1);
  EXPECT_THROW(uniformAutoSketch(cloud, cam, 0, geom::UpAxis::Y), OptionsError);
  EXPECT_THROW(uniformAutoSketch(geom::PointCloud{}, cam, 5, geom::UpAxis::Y), OptionsError);
  geom::Camera bad = cam;
  bad.viewport.height = 0;
  EXPECT_THROW(uniformAutoSketch(cloud, bad, 5, geom::UpAxis::Y), OptionsError);
  // A camera looking away from the cloud sees nothing.
  geom::Camera away = cam;
  away.view = geom::lookAt(Vec3(0, 5, 100), Vec3(0, 5, 200), Vec3(0, 1, 0));
  EXPECT_THROW(uniformAutoSketch(cloud, away, 5, geom::UpAxis::Y), OptionsError);
}

}  // namespace
}  // namespace treesketch::sketch
