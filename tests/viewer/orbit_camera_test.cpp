#include "treesketch/viewer/orbit_camera.h"

#include <gtest/gtest.h>

namespace treesketch::viewer {
namespace {

using geom::Vec2;
using geom::Vec3;

OrbitCamera framed(bool ortho = false) {
  OrbitCamera cam;
  cam.setViewport(geom::Viewport{100, 0, 800, 600});
  geom::BBox box;
  box.add(Vec3(-1, 0, -1));
  box.add(Vec3(1, 6, 1));
  cam.setSceneBounds(box);
  cam.setOrthographic(ortho);
  cam.preset(geom::PresetView::Front, geom::UpAxis::Y);
  return cam;
}

TEST(OrbitCamera, PresetFramesTheWholeBox) {
  for (bool ortho : {false, true}) {
    OrbitCamera cam = framed(ortho);
    geom::Camera c = cam.camera();
    EXPECT_EQ(c.isOrthographic(), ortho);
    EXPECT_NEAR((c.forward() - Vec3(0, 0, -1)).norm(), 0.0, 1e-12);
    for (int i = 0; i < 8; ++i) {
      Vec3 corner((i & 1) ? 1 : -1, (i & 2) ? 6 : 0, (i & 4) ? 1 : -1);
      Vec3 s = c.project(corner);
      EXPECT_GE(s.x(), 100.0);
      EXPECT_LE(s.x(), 900.0);
      EXPECT_GE(s.y(), 0.0);
      EXPECT_LE(s.y(), 600.0);
      EXPECT_GT(s.z(), 0.0);
      EXPECT_LT(s.z(), 1.0);
    }
    // The box is tall: it fills most of the height.
    double top = c.project(Vec3(0, 6, 0)).y(), bottom = c.project(Vec3(0, 0, 0)).y();
    EXPECT_GT(bottom - top, 0.6 * 600);
  }
}

TEST(OrbitCamera, SidePresetLooksAlongMinusXAndTopLooksDown) {
  OrbitCamera cam = framed();
  cam.preset(geom::PresetView::Side, geom::UpAxis::Y);
  EXPECT_NEAR((cam.camera().forward() - Vec3(-1, 0, 0)).norm(), 0.0, 1e-12);
  cam.preset(geom::PresetView::Top, geom::UpAxis::Z);
  EXPECT_NEAR((cam.camera().forward() - Vec3(0, 0, -1)).norm(), 0.0, 1e-12);
}

TEST(OrbitCamera, TrackballKeepsTargetAndDistance) {
  OrbitCamera cam = framed();
  Vec3 target = cam.target();
  double dist = cam.distance();
  Vec3 eyeBefore = cam.camera().eye();
  cam.rotate(Vec2(500, 300), Vec2(600, 300));  // horizontal drag: turn around the screen-up axis
  geom::Camera c = cam.camera();
  EXPECT_NEAR((cam.target() - target).norm(), 0.0, 1e-12);
  EXPECT_NEAR((c.eye() - target).norm(), dist, 1e-9);
  EXPECT_GT((c.eye() - eyeBefore).norm(), 0.1);
  EXPECT_NEAR((c.up() - Vec3(0, 1, 0)).norm(), 0.0, 1e-9);  // a horizontal drag keeps the up axis
  // Dragging to the right turns the scene to the right: a point in front of the target moves right.
  OrbitCamera before = framed();
  Vec3 p(0, 3, 1);
  EXPECT_GT(c.project(p).x(), before.camera().project(p).x());
}

TEST(OrbitCamera, ZeroDragDoesNothing) {
  OrbitCamera cam = framed();
  Eigen::Quaterniond q = cam.orientation();
  cam.rotate(Vec2(300, 200), Vec2(300, 200));
  EXPECT_TRUE(cam.orientation().isApprox(q));
}

TEST(OrbitCamera, PanMovesTheSceneWithTheMouse) {
  OrbitCamera cam = framed();
  Vec3 target = cam.target();
  Vec3 before = cam.camera().project(target);
  cam.pan(Vec2(40, -25));
  Vec3 after = cam.camera().project(target);
  EXPECT_NEAR(after.x() - before.x(), 40.0, 1e-6);
  EXPECT_NEAR(after.y() - before.y(), -25.0, 1e-6);
}

TEST(OrbitCamera, ZoomChangesDistanceWithinLimits) {
  OrbitCamera cam = framed();
  double d = cam.distance();
  cam.zoom(2);
  EXPECT_LT(cam.distance(), d);
  cam.zoom(-4);
  EXPECT_GT(cam.distance(), d);
  cam.zoom(1e6);
  EXPECT_GT(cam.distance(), 0.0);
  EXPECT_TRUE(cam.camera().projection.allFinite());
}

TEST(OrbitCamera, DegenerateInputsAreIgnored) {
  OrbitCamera cam;
  cam.setViewport(geom::Viewport{0, 0, 0, 100});  // ignored
  EXPECT_GT(cam.viewport().width, 0.0);
  cam.setSceneBounds(geom::BBox{});  // ignored
  cam.fit();
  EXPECT_NO_THROW(cam.camera().validate("camera"));
}

}  // namespace
}  // namespace treesketch::viewer
