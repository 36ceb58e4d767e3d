// Scene pictures: draw order cloud -> meshes -> lines and dots, and camera framing. The iso view
// (45° azimuth, 30° elevation, perspective) is solved for the camera distance that keeps every
// bounding-box corner inside the frustum.
#include "treesketch/render/scene_render.h"

#include <algorithm>
#include <cmath>
#include <map>

#include "treesketch/render/color_map.h"
#include "treesketch/util/error.h"
#include "treesketch/util/text.h"

namespace treesketch::render {

using geom::Vec3;

namespace {

constexpr double kIsoAzimuthDeg = 45.0;
constexpr double kIsoElevationDeg = 30.0;
constexpr double kIsoFovYDeg = 30.0;
constexpr double kFrameFill = 0.95;  // the box fills 95 % of the half-extent (5 % margin)

void checkSize(int width, int height) {
  if (width < 1 || height < 1 || width > 16384 || height > 16384)
    throw OptionsError("render: picture size " + std::to_string(width) + " x " + std::to_string(height) +
                       " is outside 1..16384 pixels");
}

std::array<Vec3, 8> corners(const geom::BBox& b) {
  std::array<Vec3, 8> c;
  for (int i = 0; i < 8; ++i)
    c[i] = Vec3(i & 1 ? b.max.x() : b.min.x(), i & 2 ? b.max.y() : b.min.y(), i & 4 ? b.max.z() : b.min.z());
  return c;
}

geom::Camera isoCamera(const geom::BBox& box, geom::UpAxis up, int width, int height) {
  const Vec3 upV = geom::upVector(up);
  const Vec3 frontEye = up == geom::UpAxis::Y ? Vec3(0, 0, 1) : Vec3(0, -1, 0);  // presetCamera front looks back at it
  const Vec3 sideEye(1, 0, 0);
  const double az = kIsoAzimuthDeg * M_PI / 180.0, el = kIsoElevationDeg * M_PI / 180.0;
  const Vec3 horizontal = (std::cos(az) * frontEye + std::sin(az) * sideEye).normalized();
  const Vec3 toEye = std::cos(el) * horizontal + std::sin(el) * upV;
  const double aspect = static_cast<double>(width) / height;
  const double tanV = std::tan(0.5 * kIsoFovYDeg * M_PI / 180.0) * kFrameFill, tanH = tanV * aspect;
  const double radius = 0.5 * box.diagonal();

  Vec3 target = box.centre();
  double dist = 0;
  for (int pass = 0; pass < 3; ++pass) {  // solve the distance, then re-centre the picture on the box
    geom::Mat4 rot = geom::lookAt(target + toEye, target, upV);
    dist = 0;
    for (const Vec3& c : corners(box)) {
      Eigen::Vector4d r = rot * Eigen::Vector4d(c.x(), c.y(), c.z(), 1.0);  // eye frame with the eye at distance 1
      double z = r.z() + 1.0;                                               // relative to the target
      dist = std::max({dist, z + std::abs(r.x()) / tanH, z + std::abs(r.y()) / tanV, z + 1e-6 * radius});
    }
    double xMin = HUGE_VAL, xMax = -HUGE_VAL, yMin = HUGE_VAL, yMax = -HUGE_VAL;
    for (const Vec3& c : corners(box)) {
      Eigen::Vector4d r = rot * Eigen::Vector4d(c.x(), c.y(), c.z(), 1.0);
      double depth = dist - (r.z() + 1.0);
      xMin = std::min(xMin, r.x() / depth);
      xMax = std::max(xMax, r.x() / depth);
      yMin = std::min(yMin, r.y() / depth);
      yMax = std::max(yMax, r.y() / depth);
    }
    Vec3 right = rot.block<1, 3>(0, 0).transpose(), camUp = rot.block<1, 3>(1, 0).transpose();
    target += dist * (0.5 * (xMin + xMax) * right + 0.5 * (yMin + yMax) * camUp);
  }
  geom::Camera cam;
  cam.viewport = {0, 0, static_cast<double>(width), static_cast<double>(height)};
  cam.view = geom::lookAt(target + dist * toEye, target, upV);
  const double zNear = std::max(dist - 2.0 * radius, 1e-3 * dist);
  cam.projection = geom::perspective(kIsoFovYDeg, aspect, zNear, dist + 2.0 * radius);
  return cam;
}

}  // namespace

geom::BBox RenderScene::bounds() const {
  geom::BBox b;
  for (const auto& p : cloud) b.add(p);
  for (const auto& m : meshes) b.add(m.bounds());
  for (const auto& l : polylines)
    for (const auto& p : l.points) b.add(p);
  for (const auto& d : dots) b.add(d.position);
  return b;
}

Image renderScene(const RenderScene& scene, const geom::Camera& camera, int width, int height) {
  checkSize(width, height);
  if (!scene.cloudColors.empty() && scene.cloudColors.size() != scene.cloud.size())
    throw OptionsError("render: " + std::to_string(scene.cloudColors.size()) + " point colours for " +
                       std::to_string(scene.cloud.size()) + " points");
  geom::Camera cam = camera;
  cam.viewport = {0, 0, static_cast<double>(width), static_cast<double>(height)};
  Rasterizer r(cam, scene.background);
  auto drawCloud = [&](PointDepth mode) {
    for (std::size_t i = 0; i < scene.cloud.size(); ++i)
      r.drawPoint(scene.cloud[i], scene.cloudColors.empty() ? scene.cloudColor : scene.cloudColors[i], scene.pointSize,
                  mode);
  };
  if (!scene.cloudBehindMeshes) drawCloud(PointDepth::Test);
  for (std::size_t i = 0; i < scene.meshes.size(); ++i)
    r.drawMesh(scene.meshes[i], i < scene.meshColors.size() ? scene.meshColors[i] : distinctColor(static_cast<int>(i)),
               scene.meshStyle);
  if (scene.cloudBehindMeshes) drawCloud(PointDepth::EmptyOnly);
  LineStyle line;
  line.widthPx = scene.lineWidth;
  line.depthTest = !scene.linesOnTop;
  for (const auto& l : scene.polylines)
    for (std::size_t k = 0; k + 1 < l.points.size(); ++k) r.drawLine(l.points[k], l.points[k + 1], l.color, line);
  for (const auto& d : scene.dots)
    r.drawPoint(d.position, d.color, scene.dotSize, scene.linesOnTop ? PointDepth::Ignore : PointDepth::Test);
  return r.takeImage();
}

RenderView parseRenderView(const std::string& name) {
  const std::string s = lowercase(name);
  if (s == "front") return RenderView::Front;
  if (s == "side") return RenderView::Side;
  if (s == "top") return RenderView::Top;
  if (s == "iso") return RenderView::Iso;
  throw OptionsError("render: unknown view '" + name + "' (expected front, side, top or iso)");
}

geom::Camera fitCamera(const geom::BBox& box, RenderView view, geom::UpAxis up, int width, int height) {
  checkSize(width, height);
  if (box.empty()) throw OptionsError("render: nothing to frame (empty bounding box)");
  if (!box.min.allFinite() || !box.max.allFinite()) throw OptionsError("render: bounding box has NaN or Inf");
  geom::BBox b = box;
  if (b.diagonal() < 1e-9) {  // a single point: frame a small cube around it
    double pad = 1e-3 * std::max(1.0, b.centre().norm());
    b.add(Vec3(b.min.array() - pad));
    b.add(Vec3(b.max.array() + pad));
  }
  if (view == RenderView::Iso) return isoCamera(b, up, width, height);
  geom::PresetView preset = view == RenderView::Front  ? geom::PresetView::Front
                            : view == RenderView::Side ? geom::PresetView::Side
                                                       : geom::PresetView::Top;
  return geom::presetCamera(preset, b, up, {0, 0, static_cast<double>(width), static_cast<double>(height)}, true);
}

geom::Camera tightenCamera(const geom::Camera& camera, const std::vector<Vec3>& points, double margin) {
  const geom::Mat4 viewProj = camera.projection * camera.view;
  double xMin = HUGE_VAL, xMax = -HUGE_VAL, yMin = HUGE_VAL, yMax = -HUGE_VAL;
  std::size_t used = 0;
  for (const Vec3& p : points) {
    Eigen::Vector4d c = viewProj * Eigen::Vector4d(p.x(), p.y(), p.z(), 1.0);
    if (!c.allFinite() || c.z() + c.w() < 0 || c.w() <= 0) continue;
    double x = c.x() / c.w(), y = c.y() / c.w();
    xMin = std::min(xMin, x);
    xMax = std::max(xMax, x);
    yMin = std::min(yMin, y);
    yMax = std::max(yMax, y);
    ++used;
  }
  const double span = std::max(xMax - xMin, yMax - yMin);
  if (used < 2 || !(span > 1e-12) || !std::isfinite(span)) return camera;
  const double fill = 2.0 * (1.0 - 2.0 * std::clamp(margin, 0.0, 0.45));
  const double scale = std::min(fill / std::max(xMax - xMin, 1e-12), fill / std::max(yMax - yMin, 1e-12));
  // In clip space x' = s (x - cx w), y' = s (y - cy w), z and w unchanged: in NDC a shift of the
  // box centre to 0 and a uniform scale, so depth and the near/far planes stay as they were.
  const double cx = 0.5 * (xMin + xMax), cy = 0.5 * (yMin + yMax);
  geom::Mat4 m = geom::Mat4::Identity();
  m.row(0) = scale * Eigen::RowVector4d(1, 0, 0, -cx);
  m.row(1) = scale * Eigen::RowVector4d(0, 1, 0, -cy);
  geom::Camera out = camera;
  out.projection = m * camera.projection;
  return out;
}

std::size_t addSketch(RenderScene& scene, const sketch::Sketch& sketch, const Vec3& focus, Rgb color) {
  std::map<sketch::NodeId, Vec3> placed;
  for (sketch::NodeId id : sketch.topologicalOrder()) {
    const sketch::Node& n = sketch.node(id);
    Vec3 p = n.point;
    if (n.isScreenNode()) {
      sketch::NodeGeometry g = sketch.geometry(id);
      double len2 = g.lineDir.squaredNorm();
      if (!g.hasLine || !(len2 > 0) || !g.linePoint.allFinite()) continue;
      p = g.linePoint + g.lineDir * ((focus - g.linePoint).dot(g.lineDir) / len2);
    }
    if (!p.allFinite()) continue;
    placed[id] = p;
    scene.dots.push_back({p, color});
    auto parent = placed.find(n.parent);
    if (parent != placed.end()) scene.polylines.push_back({{parent->second, p}, color});
  }
  return placed.size();
}

}  // namespace treesketch::render
