#include "treesketch/geom/camera.h"

#include <Eigen/LU>
#include <algorithm>
#include <cmath>

#include "treesketch/util/error.h"

namespace treesketch::geom {

Vec3 Camera::unproject(const Vec2& screen, double depth01) const {
  // Window -> normalized device coordinates (OpenGL: y up, depth in [-1, 1]).
  double ndcX = 2.0 * (screen.x() - viewport.x) / viewport.width - 1.0;
  double ndcY = 1.0 - 2.0 * (screen.y() - viewport.y) / viewport.height;
  double ndcZ = 2.0 * depth01 - 1.0;
  Mat4 inv = (projection * view).inverse();
  Eigen::Vector4d p = inv * Eigen::Vector4d(ndcX, ndcY, ndcZ, 1.0);
  if (p.w() == 0.0 || !std::isfinite(p.w())) throw OptionsError("camera: cannot unproject (singular matrices)");
  return p.head<3>() / p.w();
}

Vec3 Camera::project(const Vec3& world) const {
  Eigen::Vector4d c = projection * view * Eigen::Vector4d(world.x(), world.y(), world.z(), 1.0);
  Vec3 ndc = c.head<3>() / c.w();
  double sx = viewport.x + (ndc.x() + 1.0) * 0.5 * viewport.width;
  double sy = viewport.y + (1.0 - ndc.y()) * 0.5 * viewport.height;
  return Vec3(sx, sy, 0.5 * (ndc.z() + 1.0));
}

Vec3 Camera::eye() const {
  Mat4 inv = view.inverse();
  return inv.block<3, 1>(0, 3);
}

Vec3 Camera::forward() const { return -view.block<1, 3>(2, 0).transpose().normalized(); }
Vec3 Camera::up() const { return view.block<1, 3>(1, 0).transpose().normalized(); }
Vec3 Camera::right() const { return view.block<1, 3>(0, 0).transpose().normalized(); }

void Camera::validate(const std::string& what) const {
  if (!view.allFinite() || !projection.allFinite()) throw OptionsError(what + ": camera matrix has NaN or Inf");
  if (!(viewport.width > 0) || !(viewport.height > 0) || !std::isfinite(viewport.width) ||
      !std::isfinite(viewport.height))
    throw OptionsError(what + ": camera viewport has zero or negative size");
  double det = (projection * view).determinant();
  if (!std::isfinite(det) || std::abs(det) < 1e-300) throw OptionsError(what + ": camera matrices are singular");
}

Mat4 lookAt(const Vec3& eye, const Vec3& target, const Vec3& up) {
  Vec3 f = (target - eye).normalized();
  Vec3 s = f.cross(up).normalized();
  Vec3 u = s.cross(f);
  Mat4 m = Mat4::Identity();
  m.block<1, 3>(0, 0) = s.transpose();
  m.block<1, 3>(1, 0) = u.transpose();
  m.block<1, 3>(2, 0) = -f.transpose();
  m(0, 3) = -s.dot(eye);
  m(1, 3) = -u.dot(eye);
  m(2, 3) = f.dot(eye);
  return m;
}

Mat4 perspective(double fovYDeg, double aspect, double zNear, double zFar) {
  double f = 1.0 / std::tan(fovYDeg * M_PI / 360.0);
  Mat4 m = Mat4::Zero();
  m(0, 0) = f / aspect;
  m(1, 1) = f;
  m(2, 2) = (zFar + zNear) / (zNear - zFar);
  m(2, 3) = 2.0 * zFar * zNear / (zNear - zFar);
  m(3, 2) = -1.0;
  return m;
}

Mat4 orthographic(double left, double right, double bottom, double top, double zNear, double zFar) {
  Mat4 m = Mat4::Identity();
  m(0, 0) = 2.0 / (right - left);
  m(1, 1) = 2.0 / (top - bottom);
  m(2, 2) = -2.0 / (zFar - zNear);
  m(0, 3) = -(right + left) / (right - left);
  m(1, 3) = -(top + bottom) / (top - bottom);
  m(2, 3) = -(zFar + zNear) / (zFar - zNear);
  return m;
}

PresetView parsePresetView(const std::string& s) {
  if (s == "front") return PresetView::Front;
  if (s == "side") return PresetView::Side;
  if (s == "top") return PresetView::Top;
  throw OptionsError("view must be 'front', 'side' or 'top', got '" + s + "'");
}

Camera presetCamera(PresetView view, const BBox& box, UpAxis up, const Viewport& viewport, bool ortho) {
  if (box.empty()) throw OptionsError("preset camera: empty bounding box");
  Vec3 upV = upVector(up);
  Vec3 dir;      // viewing direction
  Vec3 camUp;    // screen up
  Vec3 depthAx;  // unused, for clarity
  if (view == PresetView::Front) {
    dir = up == UpAxis::Y ? Vec3(0, 0, -1) : Vec3(0, 1, 0);
    camUp = upV;
  } else if (view == PresetView::Side) {
    dir = Vec3(-1, 0, 0);
    camUp = upV;
  } else {
    dir = -upV;
    camUp = up == UpAxis::Y ? Vec3(0, 0, -1) : Vec3(0, 1, 0);
  }
  (void)depthAx;
  Vec3 c = box.centre();
  double radius = 0.5 * std::max(box.diagonal(), 1e-9);
  Vec3 right = dir.cross(camUp).normalized();
  Vec3 ext = box.extent();
  double halfW = 0.5 * std::abs(ext.dot(right.cwiseAbs())) * 1.05 + 1e-9;
  double halfH = 0.5 * std::abs(ext.dot(camUp.cwiseAbs())) * 1.05 + 1e-9;
  double aspect = viewport.width / viewport.height;
  if (halfW / halfH > aspect) halfH = halfW / aspect;
  else halfW = halfH * aspect;
  Camera cam;
  cam.viewport = viewport;
  if (ortho) {
    Vec3 eye = c - dir * (2.0 * radius);
    cam.view = lookAt(eye, c, camUp);
    cam.projection = orthographic(-halfW, halfW, -halfH, halfH, 0.01 * radius, 4.0 * radius);
  } else {
    double fov = 30.0;
    double dist = halfH / std::tan(fov * M_PI / 360.0) + radius;
    Vec3 eye = c - dir * dist;
    cam.view = lookAt(eye, c, camUp);
    cam.projection = perspective(fov, aspect, std::max(dist - 2.0 * radius, 0.01 * radius), dist + 2.0 * radius);
  }
  return cam;
}

}  // namespace treesketch::geom
