#include "treesketch/render/rasterizer.h"

#include <gtest/gtest.h>

#include <cmath>

#include "treesketch/util/error.h"

namespace treesketch::render {
namespace {

using geom::Vec3;

const Rgb kWhite{255, 255, 255};
const Rgb kRed{255, 0, 0};
const Rgb kBlue{0, 0, 255};

geom::Camera testCamera(bool ortho = false) {
  geom::Camera cam;
  cam.view = geom::lookAt(Vec3(0, 0, 5), Vec3(0, 0, 0), Vec3(0, 1, 0));
  cam.projection = ortho ? geom::orthographic(-2, 2, -2, 2, 0.1, 100) : geom::perspective(60, 1.0, 0.1, 100);
  cam.viewport = {0, 0, 64, 48};
  cam.projection(0, 0) *= 48.0 / 64.0;  // keep square pixels for the 64 x 48 viewport
  return cam;
}

TriangleStyle flat() {
  TriangleStyle s;
  s.lambert = false;
  return s;
}

TEST(Rasterizer, ImageMatchesViewportAndStartsAsBackground) {
  Rasterizer r(testCamera(), {10, 20, 30});
  EXPECT_EQ(r.image().width, 64);
  EXPECT_EQ(r.image().height, 48);
  EXPECT_EQ(r.image().at(5, 5), (Rgb{10, 20, 30}));
  EXPECT_EQ(r.depthAt(5, 5), 1.0f);
}

TEST(Rasterizer, TriangleCoveringCentreColoursCentreNotCorner) {
  for (bool ortho : {false, true}) {
    Rasterizer r(testCamera(ortho));
    ASSERT_TRUE(r.drawTriangle({Vec3(-0.5, -0.5, 0), Vec3(0.5, -0.5, 0), Vec3(0, 0.5, 0)}, {kRed, kRed, kRed}, flat()));
    EXPECT_EQ(r.image().at(32, 24), kRed);
    EXPECT_EQ(r.image().at(0, 0), kWhite);
    EXPECT_EQ(r.image().at(63, 47), kWhite);
    EXPECT_LT(r.depthAt(32, 24), 1.0f);
  }
}

TEST(Rasterizer, WindingDoesNotMatterAndLambertDarkensObliqueFaces) {
  Rasterizer r(testCamera());
  r.drawTriangle({Vec3(0, 0.5, 0), Vec3(0.5, -0.5, 0), Vec3(-0.5, -0.5, 0)}, {kRed, kRed, kRed});
  EXPECT_EQ(r.image().at(32, 24), kRed);  // facing the headlight: full colour
  Rasterizer oblique(testCamera());
  // The same triangle tilted 60° about the X axis.
  const double c = std::cos(M_PI / 3), s = std::sin(M_PI / 3);
  oblique.drawTriangle({Vec3(-0.5, -0.5 * c, -0.5 * s), Vec3(0.5, -0.5 * c, -0.5 * s), Vec3(0, 0.5 * c, 0.5 * s)},
                       {kRed, kRed, kRed});
  Rgb got = oblique.image().at(32, 24);
  EXPECT_LT(got.r, 255);
  EXPECT_GT(got.r, 120);
  EXPECT_EQ(got.g, 0);
}

TEST(Rasterizer, DepthBufferKeepsTheNearerTriangleInEitherOrder) {
  const std::array<Vec3, 3> nearTri = {Vec3(-1, -1, 1), Vec3(1, -1, 1), Vec3(0, 1, 1)};
  const std::array<Vec3, 3> farTri = {Vec3(-1, -1, -1), Vec3(1, -1, -1), Vec3(0, 1, -1)};
  Rasterizer a(testCamera());
  a.drawTriangle(nearTri, {kRed, kRed, kRed}, flat());
  a.drawTriangle(farTri, {kBlue, kBlue, kBlue}, flat());
  EXPECT_EQ(a.image().at(32, 24), kRed);
  Rasterizer b(testCamera());
  b.drawTriangle(farTri, {kBlue, kBlue, kBlue}, flat());
  b.drawTriangle(nearTri, {kRed, kRed, kRed}, flat());
  EXPECT_EQ(b.image().at(32, 24), kRed);
  EXPECT_LT(b.depthAt(32, 24), 1.0f);
}

TEST(Rasterizer, VertexColoursAreInterpolated) {
  Rasterizer r(testCamera());
  r.drawTriangle({Vec3(-2, -2, 0), Vec3(2, -2, 0), Vec3(0, 2, 0)}, {kRed, kRed, kBlue}, flat());
  Rgb top = r.image().at(32, 8), bottom = r.image().at(32, 40);
  EXPECT_GT(top.b, bottom.b);
  EXPECT_LT(top.r, bottom.r);
}

TEST(Rasterizer, PointsBehindOrBeyondTheCameraDrawNothing) {
  Rasterizer r(testCamera());
  EXPECT_FALSE(r.drawPoint(Vec3(0, 0, 6), kRed, 3));     // behind the eye
  EXPECT_FALSE(r.drawPoint(Vec3(0, 0, 4.95), kRed, 3));  // between the eye and the near plane
  EXPECT_FALSE(r.drawPoint(Vec3(0, 0, -200), kRed, 3));  // beyond the far plane
  EXPECT_FALSE(r.drawPoint(Vec3(0, 0, NAN), kRed, 3));
  for (int y = 0; y < 48; ++y)
    for (int x = 0; x < 64; ++x) ASSERT_EQ(r.image().at(x, y), kWhite);
  EXPECT_TRUE(r.drawPoint(Vec3(0, 0, 0), kRed, 3));
  EXPECT_EQ(r.image().at(32, 24), kRed);
}

TEST(Rasterizer, PointSplatIsDepthTested) {
  Rasterizer r(testCamera());
  r.drawTriangle({Vec3(-1, -1, 1), Vec3(1, -1, 1), Vec3(0, 1, 1)}, {kBlue, kBlue, kBlue}, flat());
  r.drawPoint(Vec3(0, 0, 0), kRed, 4);  // hidden behind the triangle
  EXPECT_EQ(r.image().at(32, 24), kBlue);
  r.drawPoint(Vec3(0, 0, 0), kRed, 4, PointDepth::EmptyOnly);  // only where nothing is drawn
  EXPECT_EQ(r.image().at(32, 24), kBlue);
  r.drawPoint(Vec3(0, 0, 0), kRed, 4, PointDepth::Ignore);  // drawn over
  EXPECT_EQ(r.image().at(32, 24), kRed);
  Rasterizer empty(testCamera());
  empty.drawPoint(Vec3(0, 0, 0), kRed, 4, PointDepth::EmptyOnly);
  EXPECT_EQ(empty.image().at(32, 24), kRed);
}

TEST(Rasterizer, LineEndpointsLandWhereCameraProjectSays) {
  geom::Camera cam = testCamera();
  Rasterizer r(cam);
  const Vec3 a(-1.2, 0.7, 0.3), b(0.9, -0.8, -0.6);
  ASSERT_TRUE(r.drawLine(a, b, kRed));
  for (const Vec3& p : {a, b}) {
    Vec3 s = cam.project(p);
    EXPECT_EQ(r.image().at(static_cast<int>(std::floor(s.x())), static_cast<int>(std::floor(s.y()))), kRed);
  }
  Vec3 mid = cam.project(0.5 * (a + b));  // depth is not linear, but the midpoint lies on the drawn line
  int covered = 0;
  for (int dy = -1; dy <= 1; ++dy)
    for (int dx = -1; dx <= 1; ++dx)
      covered += r.image().at(int(std::floor(mid.x())) + dx, int(std::floor(mid.y())) + dy) == kRed;
  EXPECT_GT(covered, 0);
}

TEST(Rasterizer, LineCrossingTheNearPlaneIsClippedAndBehindIsSkipped) {
  geom::Camera cam = testCamera();
  Rasterizer r(cam);
  EXPECT_FALSE(r.drawLine(Vec3(0, 0, 6), Vec3(1, 0, 7), kRed));
  const Vec3 inFront(0.3, 0.2, 0), behind(0.3, 0.2, 9);
  EXPECT_TRUE(r.drawLine(inFront, behind, kRed));
  Vec3 s = cam.project(inFront);
  EXPECT_EQ(r.image().at(int(std::floor(s.x())), int(std::floor(s.y()))), kRed);
}

TEST(Rasterizer, VeryLongLinesAndHugeTrianglesStayContinuousAndSafe) {
  geom::Camera cam = testCamera(true);
  Rasterizer r(cam);
  EXPECT_TRUE(r.drawLine(Vec3(-1e7, 0.01, 0), Vec3(1e7, 0.01, 0), kRed));
  int row = static_cast<int>(std::floor(cam.project(Vec3(0, 0.01, 0)).y()));
  for (int x = 0; x < 64; ++x) EXPECT_EQ(r.image().at(x, row), kRed) << "column " << x;
  EXPECT_TRUE(r.drawLine(Vec3(-1e7, 50, 0), Vec3(1e7, 50, 0), kRed));  // off screen: nothing drawn
  Rasterizer p(testCamera());
  // A vertex just past the near plane projects hundreds of thousands of pixels away.
  EXPECT_TRUE(p.drawTriangle({Vec3(0, 0, 4.8999), Vec3(-1, -1, 0), Vec3(1, -1, 0)}, {kRed, kRed, kRed}, flat()));
}

TEST(Rasterizer, DegenerateAndCulledTrianglesAreSkipped) {
  Rasterizer r(testCamera());
  EXPECT_FALSE(r.drawTriangle({Vec3(0, 0, 0), Vec3(1, 1, 0), Vec3(2, 2, 0)}, {kRed, kRed, kRed}));
  EXPECT_FALSE(r.drawTriangle({Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 8)}, {kRed, kRed, kRed}));
  EXPECT_FALSE(r.drawTriangle({Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, NAN, 0)}, {kRed, kRed, kRed}));
  EXPECT_EQ(r.image().at(32, 24), kWhite);
}

TEST(Rasterizer, MeshWithWireframeAndBadIndices) {
  geom::TriMesh mesh;
  mesh.vertices = {Vec3(-1, -1, 0), Vec3(1, -1, 0), Vec3(1, 1, 0), Vec3(-1, 1, 0)};
  mesh.triangles = {{0, 1, 2}, {0, 2, 3}};
  TriangleStyle style = flat();
  style.wireframe = true;
  style.wireColor = kBlue;
  Rasterizer r(testCamera());
  EXPECT_EQ(r.drawMesh(mesh, kRed, style), 2u);
  EXPECT_EQ(r.image().at(38, 18), kRed);  // inside a face, off the diagonal
  geom::Camera cam = testCamera();
  Vec3 corner = cam.project(Vec3(1, -1, 0));
  EXPECT_EQ(r.image().at(int(std::floor(corner.x())), int(std::floor(corner.y()))), kBlue);
  mesh.triangles.push_back({0, 1, 9});
  EXPECT_THROW(r.drawMesh(mesh, kRed), OptionsError);
}

TEST(Rasterizer, RejectsDegenerateCameras) {
  geom::Camera cam = testCamera();
  cam.viewport.width = 0;
  EXPECT_THROW(Rasterizer{cam}, OptionsError);
  cam = testCamera();
  cam.viewport.width = 100000;
  EXPECT_THROW(Rasterizer{cam}, OptionsError);
  cam = testCamera();
  cam.projection = geom::Mat4::Zero();
  EXPECT_THROW(Rasterizer{cam}, OptionsError);
}

}  // namespace
}  // namespace treesketch::render
