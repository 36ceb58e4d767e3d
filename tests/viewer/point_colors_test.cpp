#include "treesketch/viewer/point_colors.h"

#include <gtest/gtest.h>

#include <cmath>

#include "treesketch/gen/random.h"
#include "treesketch/viewer/point_lod.h"
#include "treesketch/render/color_map.h"

namespace treesketch::viewer {
namespace {

using geom::Vec3;
using render::viridis;

TEST(PointColors, DistanceToCircleKnownValues) {
  Circle3 c{Vec3(1, 2, 3), Vec3(0, 1, 0), 2.0};
  EXPECT_NEAR(distanceToCircle(Vec3(3, 2, 3), c), 0.0, 1e-12);                   // on the curve
  EXPECT_NEAR(distanceToCircle(Vec3(1, 2, 3), c), 2.0, 1e-12);                   // the centre
  EXPECT_NEAR(distanceToCircle(Vec3(1, 5, 3), c), std::sqrt(9.0 + 4.0), 1e-12);  // on the axis
  EXPECT_NEAR(distanceToCircle(Vec3(6, 2, 3), c), 3.0, 1e-12);                   // outside in the plane
  EXPECT_NEAR(distanceToCircle(Vec3(3, 3, 3), c), 1.0, 1e-12);                   // above the curve
}

TEST(PointColors, CircleDistanceColorsUseTheNearestCircle) {
  geom::PointCloud cloud;
  cloud.positions = {Vec3(1, 0, 0), Vec3(0, 10, 1), Vec3(50, 50, 50), Vec3(0.5, 0, 0)};
  std::vector<Circle3> circles = {{Vec3(0, 0, 0), Vec3(0, 1, 0), 1.0}, {Vec3(0, 10, 0), Vec3(0, 1, 0), 1.0}};
  auto colors = circleDistanceColors(cloud, circles, 1.0);
  EXPECT_EQ(colors[0], viridis(0.0));
  EXPECT_EQ(colors[1], viridis(0.0));
  EXPECT_EQ(colors[2], viridis(1.0));
  EXPECT_EQ(colors[3], viridis(0.5));
  auto none = circleDistanceColors(cloud, {}, 1.0);
  EXPECT_EQ(none[0], viridis(1.0));
  EXPECT_EQ(plainColors(cloud, Rgb{1, 2, 3}).size(), 4u);
}

}  // namespace
}  // namespace treesketch::viewer

namespace treesketch::viewer {
namespace {

// The grid gives exactly circleDistanceColors' colours, call after call (its scratch is reset).
TEST(DistanceColorGrid, SameColoursAsTheDirectComputation) {
  gen::Rng rng(17);
  geom::PointCloud cloud;
  for (int i = 0; i < 20000; ++i)
    cloud.positions.emplace_back(rng.uniform(-1, 1), rng.uniform(0, 4), rng.uniform(-1, 1));
  std::vector<Circle3> circles = {{geom::Vec3(0, 1, 0), geom::Vec3(0, 1, 0), 0.2},
                                  {geom::Vec3(0.3, 2.5, 0.1), geom::Vec3(0.6, 0.8, 0).normalized(), 0.1},
                                  {geom::Vec3(5, 9, 5), geom::Vec3(0, 0, 1), 0.3}};  // outside the cloud
  DistanceColorGrid grid;
  grid.build(cloud, 0.15);
  ASSERT_TRUE(grid.builtFor(cloud, 0.15));
  EXPECT_FALSE(grid.builtFor(cloud, 0.2));
  std::vector<Rgb> fast;
  for (int pass = 0; pass < 2; ++pass) {
    grid.colors(circles, fast);
    std::vector<Rgb> direct = circleDistanceColors(cloud, circles, 0.15);
    ASSERT_EQ(fast.size(), direct.size());
    std::size_t differ = 0, near = 0;
    for (std::size_t i = 0; i < fast.size(); ++i) {
      differ += !(fast[i] == direct[i]);
      near += !(direct[i] == render::viridis(1.0));
    }
    EXPECT_EQ(differ, 0u) << "pass " << pass;
    EXPECT_GT(near, 100u);  // the check sees points near the circles, not only far ones
    circles.pop_back();
  }
  grid.colors({}, fast);
  EXPECT_EQ(fast, std::vector<Rgb>(cloud.size(), render::viridis(1.0)));
}

}  // namespace
}  // namespace treesketch::viewer

namespace treesketch::viewer {
namespace {

geom::ModelCylinder piece(const geom::Vec3& a, const geom::Vec3& b, double r0, double r1, std::int64_t parent) {
  geom::ModelCylinder c{a, b, r0, r1};
  c.parent = parent;
  return c;
}

std::size_t differing(const std::vector<Rgb>& a, const std::vector<Rgb>& b) {
  std::size_t n = a.size() == b.size() ? 0 : std::max(a.size(), b.size());
  for (std::size_t i = 0; i < std::min(a.size(), b.size()); ++i) n += !(a[i] == b[i]);
  return n;
}

// A grid keeping its colours between models measures only near the pieces that changed, and
// gives exactly the colours measured from scratch, edit after edit: a joint moved (two pieces
// change), a radius changed, a piece removed, a limb added, a joint broken (the caps there close),
// an empty model, the model back, and more pieces changed at once than it tests each point against.
TEST(DistanceColorGrid, KeptSurfaceColoursEqualTheFullMeasureAfterEdits) {
  gen::Rng rng(23);
  geom::PointCloud cloud;
  for (int i = 0; i < 30000; ++i) {  // a trunk's surface with noise, and points all around it
    const double a = rng.uniform(0, 2 * M_PI), r = 0.2 + rng.uniform(-0.08, 0.08);
    cloud.positions.emplace_back(r * std::cos(a), rng.uniform(0, 4), r * std::sin(a));
    cloud.positions.emplace_back(rng.uniform(-1.5, 1.5), rng.uniform(0, 4), rng.uniform(-1.5, 1.5));
  }
  const double scale = 0.15;
  geom::CylinderModel model;
  model.cylinders = {piece(geom::Vec3(0, 0, 0), geom::Vec3(0, 1, 0), 0.22, 0.2, -1),
                     piece(geom::Vec3(0, 1, 0), geom::Vec3(0, 2, 0), 0.2, 0.18, 0),
                     piece(geom::Vec3(0, 2, 0), geom::Vec3(0, 3, 0), 0.18, 0.15, 1),
                     piece(geom::Vec3(0, 3, 0), geom::Vec3(0, 4, 0), 0.15, 0.1, 2)};
  DistanceColorGrid grid;
  grid.build(cloud, scale);
  std::vector<Rgb> kept;
  auto check = [&](const char* what) {
    grid.surfaceColors(model, kept);
    const std::vector<Rgb> full = surfaceDistanceColors(cloud, model, scale);
    EXPECT_EQ(differing(kept, full), 0u) << what;
  };
  check("first model");
  const std::size_t first = grid.lastPointsMeasured();
  EXPECT_GT(first, 10000u);

  model.cylinders[1].end = model.cylinders[2].start = geom::Vec3(0.05, 2.1, 0.02);  // a joint dragged
  check("joint moved");
  EXPECT_GT(grid.lastPointsMeasured(), 100u);
  EXPECT_LT(grid.lastPointsMeasured(), first);  // not the whole model again
  model.cylinders[3].startRadius = 0.25;
  check("radius changed");
  grid.surfaceColors(model, kept);
  EXPECT_EQ(grid.lastPointsMeasured(), 0u) << "the same model again measures nothing";
  model.cylinders.pop_back();
  check("top piece removed");
  model.cylinders.push_back(piece(geom::Vec3(0, 2.1, 0), geom::Vec3(0.9, 3.0, 0.3), 0.08, 0.05, 1));
  check("limb added");
  model.cylinders[2].parent = -1;  // the joint at 2.1 m no longer joins: the caps there close
  check("joint broken");
  const geom::CylinderModel kept4 = model;
  model.cylinders.clear();
  check("empty model");
  model = kept4;
  check("model back");
  for (int i = 0; i < 20; ++i)  // twigs all over: more changed pieces than the per-point test takes
    model.cylinders.push_back(piece(geom::Vec3(0, 0.2 * i, 0), geom::Vec3(0.8, 0.2 * i + 0.3, 0.1 * (i % 5)), 0.03,
                                    0.02, 0));
  check("twenty twigs added");
  grid.forgetSurface();
  check("after forgetSurface");
  EXPECT_GT(grid.lastPointsMeasured(), first);
}

}  // namespace
}  // namespace treesketch::viewer

namespace treesketch::viewer {
namespace {

// The kept upload-order colours equal the full gather after each change of a few points, after
// a change of every point, and after a rebuild of the order.
TEST(PointLod, KeptColoursEqualTheFullGather) {
  gen::Rng rng(5);
  std::vector<Rgb> colors(5000);
  for (Rgb& c : colors) c = viridis(rng.uniform(0, 1));
  PointLod lod;
  lod.build(colors.size());
  std::vector<std::uint8_t> gathered;
  for (int round = 0; round < 4; ++round) {
    if (round == 2)
      for (Rgb& c : colors) c = Rgb{1, 2, 3};
    else
      for (int k = 0; k < 40; ++k) colors[static_cast<std::size_t>(rng.uniform(0, 4999.9))] = viridis(rng.uniform(0, 1));
    if (round == 3) lod.build(colors.size(), 99);
    lod.colors(colors, gathered);
    EXPECT_EQ(lod.keptColors(colors), gathered) << "round " << round;
  }
}

}  // namespace
}  // namespace treesketch::viewer
