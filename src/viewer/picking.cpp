#include "treesketch/viewer/picking.h"

#include <cmath>
#include <cstdio>
#include <limits>

#include "treesketch/viewer/attribute_colors.h"

namespace treesketch::viewer {

PickedPoint pickPoint(const geom::PointCloud& cloud, const geom::Camera& camera, const geom::Vec2& screen,
                      double radiusPx) {
  PickedPoint best;
  if (cloud.empty() || !(radiusPx > 0.0) || camera.viewport.width <= 0 || camera.viewport.height <= 0) return best;
  const geom::Mat4 m = camera.projection * camera.view;
  const geom::Viewport& vp = camera.viewport;
  const double r2 = radiusPx * radiusPx;
  double bestDepth = std::numeric_limits<double>::infinity(), bestD2 = 0.0;
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    const geom::Vec3& p = cloud.positions[i];
    Eigen::Vector4d c = m * Eigen::Vector4d(p.x(), p.y(), p.z(), 1.0);
    if (!(c.w() > 0.0)) continue;  // behind a perspective eye
    double sx = vp.x + (c.x() / c.w() + 1.0) * 0.5 * vp.width;
    double sy = vp.y + (1.0 - c.y() / c.w()) * 0.5 * vp.height;
    double dx = sx - screen.x(), dy = sy - screen.y(), d2 = dx * dx + dy * dy;
    if (d2 > r2) continue;
    double depth = 0.5 * (c.z() / c.w() + 1.0);
    if (depth < 0.0 || depth > 1.0) continue;
    if (depth < bestDepth || (depth == bestDepth && d2 < bestD2)) {
      bestDepth = depth;
      bestD2 = d2;
      best.found = true;
      best.index = i;
    }
  }
  if (best.found) {
    best.position = cloud.positions[best.index];
    best.screenDistancePx = std::sqrt(bestD2);
  }
  return best;
}

Measurement measure(const geom::Vec3& a, const geom::Vec3& b, geom::UpAxis up) {
  Measurement m;
  m.a = a;
  m.b = b;
  m.delta = b - a;
  m.distance = m.delta.norm();
  int k = up == geom::UpAxis::Z ? 2 : 1;
  m.vertical = std::abs(m.delta[k]);
  geom::Vec3 across = m.delta;
  across[k] = 0.0;
  m.horizontal = across.norm();
  return m;
}

std::vector<std::string> describePoint(const geom::PointCloud& cloud, std::size_t i) {
  std::vector<std::string> out;
  if (i >= cloud.size()) return out;
  char buf[160];
  const geom::Vec3& p = cloud.positions[i];
  std::snprintf(buf, sizeof buf, "x %.4f  y %.4f  z %.4f", p.x(), p.y(), p.z());
  out.emplace_back(buf);
  if (cloud.intensity.size() == cloud.size()) {
    std::snprintf(buf, sizeof buf, "intensity %g", static_cast<double>(cloud.intensity[i]));
    out.emplace_back(buf);
  }
  if (cloud.color.size() == cloud.size()) {
    std::snprintf(buf, sizeof buf, "RGB %d %d %d", cloud.color[i][0], cloud.color[i][1], cloud.color[i][2]);
    out.emplace_back(buf);
  }
  if (cloud.classification.size() == cloud.size()) {
    int c = cloud.classification[i];
    out.push_back("class " + std::to_string(c) + " (" + asprsClassName(c) + ")");
  }
  if (cloud.station.size() == cloud.size()) out.push_back("station " + std::to_string(cloud.station[i]));
  if (cloud.meshId.size() == cloud.size()) out.push_back("mesh " + std::to_string(cloud.meshId[i]));
  return out;
}

bool PickSession::add(const PickedPoint& p) {
  if (!p.found) return false;
  if (count_ == 2) count_ = 0;
  picks_[count_++] = p;
  return true;
}

}  // namespace treesketch::viewer
