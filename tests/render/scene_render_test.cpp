#include "treesketch/render/scene_render.h"

#include <gtest/gtest.h>

#include <cmath>

#include "treesketch/util/error.h"

namespace treesketch::render {
namespace {

using geom::Vec3;

geom::BBox treeBox(geom::UpAxis up) {
  geom::BBox b;
  b.add(Vec3(-1, -0.5, 0));
  b.add(up == geom::UpAxis::Z ? Vec3(1.5, 0.5, 6) : Vec3(1.5, 6, 0.5));
  return b;
}

std::array<Vec3, 8> cornersOf(const geom::BBox& b) {
  std::array<Vec3, 8> c;
  for (int i = 0; i < 8; ++i)
    c[i] = Vec3(i & 1 ? b.max.x() : b.min.x(), i & 2 ? b.max.y() : b.min.y(), i & 4 ? b.max.z() : b.min.z());
  return c;
}

std::size_t countNot(const Image& img, Rgb bg) {
  std::size_t n = 0;
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) n += !(img.at(x, y) == bg);
  return n;
}

TEST(SceneRender, ParsesViewNames) {
  EXPECT_EQ(parseRenderView("front"), RenderView::Front);
  EXPECT_EQ(parseRenderView("Side"), RenderView::Side);
  EXPECT_EQ(parseRenderView("top"), RenderView::Top);
  EXPECT_EQ(parseRenderView("ISO"), RenderView::Iso);
  EXPECT_THROW(parseRenderView("diagonal"), OptionsError);
}

TEST(SceneRender, FitCameraKeepsEveryBoxCornerInThePicture) {
  for (geom::UpAxis up : {geom::UpAxis::Y, geom::UpAxis::Z}) {
    for (RenderView v : {RenderView::Front, RenderView::Side, RenderView::Top, RenderView::Iso}) {
      geom::BBox box = treeBox(up);
      geom::Camera cam = fitCamera(box, v, up, 300, 200);
      double xMin = 1e9, xMax = -1e9, yMin = 1e9, yMax = -1e9;
      for (const Vec3& c : cornersOf(box)) {
        Vec3 s = cam.project(c);
        EXPECT_GT(s.z(), 0.0);
        EXPECT_LT(s.z(), 1.0);
        xMin = std::min(xMin, s.x());
        xMax = std::max(xMax, s.x());
        yMin = std::min(yMin, s.y());
        yMax = std::max(yMax, s.y());
      }
      SCOPED_TRACE(static_cast<int>(v));
      EXPECT_GE(xMin, 0.0);
      EXPECT_LE(xMax, 300.0);
      EXPECT_GE(yMin, 0.0);
      EXPECT_LE(yMax, 200.0);
      EXPECT_GT(std::max((xMax - xMin) / 300.0, (yMax - yMin) / 200.0), 0.85);  // and fills it
    }
  }
}

TEST(SceneRender, IsoViewIsPerspectiveFrom45DegreesAzimuth30Elevation) {
  for (geom::UpAxis up : {geom::UpAxis::Y, geom::UpAxis::Z}) {
    geom::Camera cam = fitCamera(treeBox(up), RenderView::Iso, up, 400, 400);
    EXPECT_FALSE(cam.isOrthographic());
    Vec3 toEye = -cam.forward();
    EXPECT_NEAR(toEye.dot(geom::upVector(up)), 0.5, 1e-9);  // sin 30°
    Vec3 frontEye = up == geom::UpAxis::Y ? Vec3(0, 0, 1) : Vec3(0, -1, 0);
    EXPECT_NEAR(toEye.dot(frontEye), toEye.dot(Vec3(1, 0, 0)), 1e-9);  // halfway between front and side
    EXPECT_GT(toEye.dot(Vec3(1, 0, 0)), 0.5);
    EXPECT_GT(cam.up().dot(geom::upVector(up)), 0.8);
  }
}

TEST(SceneRender, FitCameraBadInput) {
  EXPECT_THROW(fitCamera(geom::BBox{}, RenderView::Iso, geom::UpAxis::Z, 100, 100), OptionsError);
  EXPECT_THROW(fitCamera(treeBox(geom::UpAxis::Z), RenderView::Front, geom::UpAxis::Z, 0, 100), OptionsError);
  geom::BBox point;
  point.add(Vec3(1, 2, 3));
  for (RenderView v : {RenderView::Front, RenderView::Iso}) {
    geom::Camera cam = fitCamera(point, v, geom::UpAxis::Z, 100, 100);
    Vec3 s = cam.project(Vec3(1, 2, 3));
    EXPECT_NEAR(s.x(), 50, 1.0);
    EXPECT_NEAR(s.y(), 50, 10.0);  // iso: the padded cube is centred, its centre projects a little off
  }
}

TEST(SceneRender, TightenCameraFillsThePictureWithTheDrawnPoints) {
  geom::Camera cam = fitCamera(treeBox(geom::UpAxis::Z), RenderView::Iso, geom::UpAxis::Z, 200, 100);
  std::vector<Vec3> pts = {Vec3(0, 0, 1), Vec3(0.2, 0, 1.5), Vec3(0, 0.1, 2)};  // a small cluster
  geom::Camera t = tightenCamera(cam, pts, 0.1);
  EXPECT_TRUE(t.forward().isApprox(cam.forward()));
  double xMin = 1e9, xMax = -1e9, yMin = 1e9, yMax = -1e9;
  for (const Vec3& p : pts) {
    Vec3 s = t.project(p);
    xMin = std::min(xMin, s.x());
    xMax = std::max(xMax, s.x());
    yMin = std::min(yMin, s.y());
    yMax = std::max(yMax, s.y());
  }
  EXPECT_NEAR(0.5 * (xMin + xMax), 100, 1e-6);
  EXPECT_NEAR(0.5 * (yMin + yMax), 50, 1e-6);
  EXPECT_NEAR(std::max((xMax - xMin) / 200, (yMax - yMin) / 100), 0.8, 1e-6);
  geom::Camera same = tightenCamera(cam, {Vec3(0, 0, 1)});
  EXPECT_TRUE(same.projection.isApprox(cam.projection));
}

TEST(SceneRender, DrawsCloudMeshAndLinesOnTop) {
  RenderScene scene;
  for (int i = 0; i < 50; ++i) scene.cloud.push_back(Vec3(0.1 * std::sin(i), 0.1 * std::cos(i), 0.1 * i));
  geom::TriMesh quad;
  quad.vertices = {Vec3(-1, 0.5, 0), Vec3(1, 0.5, 0), Vec3(1, 0.5, 5), Vec3(-1, 0.5, 5)};
  quad.triangles = {{0, 1, 2}, {0, 2, 3}};
  scene.meshes.push_back(quad);
  scene.meshColors = {{0, 0, 200}};
  scene.meshStyle.lambert = false;
  scene.polylines.push_back({{Vec3(-2, 1.5, 2.5), Vec3(2, 1.5, 2.5)}, {255, 0, 0}});  // behind the quad
  geom::Camera cam = fitCamera(scene.bounds(), RenderView::Front, geom::UpAxis::Z, 120, 120);
  Image img = renderScene(scene, cam, 120, 120);
  EXPECT_GT(countNot(img, scene.background), 500u);
  Vec3 c = cam.project(Vec3(0.5, 0.5, 1));
  EXPECT_EQ(img.at(int(c.x()), int(c.y())), (Rgb{0, 0, 200}));
  Vec3 l = cam.project(Vec3(0.5, 1.5, 2.5));
  EXPECT_EQ(img.at(int(l.x()), int(l.y())), (Rgb{255, 0, 0}));  // on top although behind the quad
  scene.linesOnTop = false;
  Image hidden = renderScene(scene, cam, 120, 120);
  EXPECT_EQ(hidden.at(int(l.x()), int(l.y())), (Rgb{0, 0, 200}));
  Vec3 p = cam.project(scene.cloud[10]);  // a cloud point in front of the quad
  EXPECT_EQ(img.at(int(p.x()), int(p.y())), scene.cloudColor);
  scene.cloudBehindMeshes = true;
  Image backdrop = renderScene(scene, cam, 120, 120);
  EXPECT_EQ(backdrop.at(int(p.x()), int(p.y())), (Rgb{0, 0, 200}));
  Vec3 outside = cam.project(Vec3(1.8, 0, 2.5));  // off the quad: the line still draws there
  EXPECT_EQ(backdrop.at(int(outside.x()), int(outside.y())), (Rgb{255, 0, 0}));
}

TEST(SceneRender, EmptySceneAndBadColours) {
  RenderScene scene;
  geom::Camera cam = fitCamera(treeBox(geom::UpAxis::Z), RenderView::Front, geom::UpAxis::Z, 40, 30);
  Image img = renderScene(scene, cam, 40, 30);
  EXPECT_EQ(countNot(img, scene.background), 0u);
  scene.cloud = {Vec3(0, 0, 1), Vec3(0, 0, 2)};
  scene.cloudColors = {{1, 2, 3}};
  EXPECT_THROW(renderScene(scene, cam, 40, 30), OptionsError);
  scene.cloudColors.clear();
  EXPECT_THROW(renderScene(scene, cam, 40, 0), OptionsError);
}

TEST(SceneRender, AddSketchPlacesPointAndScreenNodes) {
  sketch::Sketch sk;
  sk.up = geom::UpAxis::Z;
  sketch::NodeId root = sk.addPointNode(sketch::kNoNode, Vec3(0, 0, 0), Vec3(0, 0, 1));
  sketch::NodeId mid = sk.addPointNode(root, Vec3(0, 0, 1), Vec3(0, 0, 1));
  geom::Camera cam;
  cam.view = geom::lookAt(Vec3(0, -10, 1.5), Vec3(0, 0, 1.5), Vec3(0, 0, 1));
  cam.projection = geom::perspective(40, 1.0, 0.1, 100);
  cam.viewport = {0, 0, 200, 200};
  int ci = sk.addCamera(cam);
  const Vec3 target(0.3, 0.0, 2.0);
  sk.addScreenNode(mid, ci, cam.project(target).head<2>());
  RenderScene scene;
  EXPECT_EQ(addSketch(scene, sk, Vec3(0, 0, 1), {1, 2, 3}), 3u);
  ASSERT_EQ(scene.dots.size(), 3u);
  ASSERT_EQ(scene.polylines.size(), 2u);
  EXPECT_TRUE(scene.dots[0].position.isApprox(Vec3(0, 0, 0)));
  // The point of the view ray (eye -> target) closest to the focus.
  const Vec3 eye(0, -10, 1.5), focus(0, 0, 1), d = target - eye;
  const Vec3 expected = eye + d * ((focus - eye).dot(d) / d.squaredNorm());
  EXPECT_NEAR((scene.dots[2].position - expected).norm(), 0.0, 1e-6);
  EXPECT_TRUE(scene.polylines[1].points[0].isApprox(Vec3(0, 0, 1)));
  EXPECT_EQ(scene.dots[2].color, (Rgb{1, 2, 3}));
}

}  // namespace
}  // namespace treesketch::render
