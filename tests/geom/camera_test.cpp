#include "treesketch/geom/camera.h"

#include <gtest/gtest.h>

#include "treesketch/util/error.h"

namespace treesketch::geom {
namespace {

TEST(Camera, ProjectUnprojectRoundTripPerspective) {
  BBox box;
  box.add(Vec3(-1, 0, -1));
  box.add(Vec3(1, 5, 1));
  Camera cam = presetCamera(PresetView::Front, box, UpAxis::Y, Viewport{0, 0, 800, 600}, false);
  EXPECT_FALSE(cam.isOrthographic());
  Vec3 p(0.3, 2.0, -0.2);
  Vec3 s = cam.project(p);
  Vec3 back = cam.unproject(s.head<2>(), s.z());
  EXPECT_NEAR((back - p).norm(), 0.0, 1e-6);
  EXPECT_GT(s.z(), 0.0);
  EXPECT_LT(s.z(), 1.0);
}

TEST(Camera, OrthographicFrontViewMapsUpToScreenUp) {
  BBox box;
  box.add(Vec3(-1, 0, -1));
  box.add(Vec3(1, 10, 1));
  Camera cam = presetCamera(PresetView::Front, box, UpAxis::Y, Viewport{0, 0, 400, 400}, true);
  EXPECT_TRUE(cam.isOrthographic());
  Vec3 top = cam.project(Vec3(0, 10, 0));
  Vec3 bottom = cam.project(Vec3(0, 0, 0));
  EXPECT_LT(top.y(), bottom.y());  // screen y points down
  EXPECT_NEAR(top.x(), 200.0, 1e-9);
  EXPECT_NEAR((cam.forward() - Vec3(0, 0, -1)).norm(), 0.0, 1e-12);
}

TEST(Camera, ZUpFrontLooksAlongY) {
  BBox box;
  box.add(Vec3(-1, -1, 0));
  box.add(Vec3(1, 1, 4));
  Camera cam = presetCamera(PresetView::Front, box, UpAxis::Z, Viewport{}, true);
  EXPECT_NEAR((cam.up() - Vec3(0, 0, 1)).norm(), 0.0, 1e-12);
}

TEST(Camera, ValidateRejectsDegenerate) {
  Camera cam;
  cam.viewport.width = 0;
  EXPECT_THROW(cam.validate("node 3"), OptionsError);
  Camera nanCam;
  nanCam.view(0, 0) = std::nan("");
  EXPECT_THROW(nanCam.validate("node 3"), OptionsError);
  Camera singular;
  singular.projection = Mat4::Zero();
  EXPECT_THROW(singular.validate("node 3"), OptionsError);
}

}  // namespace
}  // namespace treesketch::geom
