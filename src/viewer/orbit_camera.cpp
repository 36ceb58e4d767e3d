#include "treesketch/viewer/orbit_camera.h"

#include <algorithm>
#include <cmath>

namespace treesketch::viewer {

using geom::Vec2;
using geom::Vec3;

OrbitCamera::OrbitCamera(const OrbitCameraOptions& options) : options_(options) {}

void OrbitCamera::setViewport(const geom::Viewport& viewport) {
  if (!(viewport.width > 0) || !(viewport.height > 0)) return;
  viewport_ = viewport;
}

void OrbitCamera::setSceneBounds(const geom::BBox& box) {
  if (box.empty()) return;
  scene_ = box;
}

void OrbitCamera::setDistance(double d) {
  double size = std::max(sceneRadius(), 1e-9);
  distance_ = std::clamp(d, 1e-4 * size, 1e4 * size);
}

double OrbitCamera::sceneRadius() const { return scene_.empty() ? 1.0 : std::max(0.5 * scene_.diagonal(), 1e-9); }

void OrbitCamera::fit() {
  double aspect = viewport_.width / viewport_.height;
  double tanHalf = std::tan(options_.fovYDeg * M_PI / 360.0);
  if (scene_.empty()) {
    setDistance(1.0 / tanHalf);
    return;
  }
  target_ = scene_.centre();
  // The box's corners in the eye axes: its half-extents across and along the view.
  geom::Mat3 m = orientation_.toRotationMatrix();
  double halfW = 0, halfH = 0, halfD = 0;
  for (int i = 0; i < 8; ++i) {
    Vec3 corner((i & 1) ? scene_.max.x() : scene_.min.x(), (i & 2) ? scene_.max.y() : scene_.min.y(),
                (i & 4) ? scene_.max.z() : scene_.min.z());
    Vec3 e = m.transpose() * (corner - target_);
    halfW = std::max(halfW, std::abs(e.x()));
    halfH = std::max(halfH, std::abs(e.y()));
    halfD = std::max(halfD, std::abs(e.z()));
  }
  double h = std::max({halfH, halfW / aspect, 1e-9}) * (1.0 + options_.fitMargin);
  // Perspective: the box's front face (halfD nearer than the target) must fit too.
  setDistance(h / tanHalf + (ortho_ ? 0.0 : halfD));
}

void OrbitCamera::preset(geom::PresetView view, geom::UpAxis up) { preset(view, geom::upVector(up)); }

void OrbitCamera::preset(geom::PresetView view, const Vec3& up) {
  Vec3 upV = up.normalized();
  Vec3 front = std::abs(upV.z()) > 0.5 ? Vec3(0, 1, 0) : Vec3(0, 0, -1);
  Vec3 dir, camUp;
  if (view == geom::PresetView::Front) {
    dir = front;
    camUp = upV;
  } else if (view == geom::PresetView::Side) {
    dir = upV.cross(front).normalized();
    camUp = upV;
  } else {
    dir = -upV;
    camUp = front;
  }
  geom::Mat3 m;
  m.col(0) = dir.cross(camUp).normalized();
  m.col(1) = camUp;
  m.col(2) = -dir;
  orientation_ = Eigen::Quaterniond(m).normalized();
  fit();
}

Vec3 OrbitCamera::trackballPoint(const Vec2& screen) const {
  // Bell's trackball: a sphere in the middle blended into a hyperbolic sheet outside, so drags
  // beyond the sphere's rim still rotate smoothly.
  double r = 0.5 * std::min(viewport_.width, viewport_.height);
  double x = (screen.x() - (viewport_.x + 0.5 * viewport_.width)) / r;
  double y = -(screen.y() - (viewport_.y + 0.5 * viewport_.height)) / r;
  double d2 = x * x + y * y;
  double z = d2 <= 0.5 ? std::sqrt(1.0 - d2) : 0.5 / std::sqrt(d2);
  return Vec3(x, y, z).normalized();
}

void OrbitCamera::rotate(const Vec2& from, const Vec2& to) {
  if ((from - to).norm() < 1e-9) return;
  Vec3 a = trackballPoint(from);
  Vec3 b = trackballPoint(to);
  Vec3 axis = a.cross(b);
  double s = axis.norm();
  if (s < 1e-12) return;
  double angle = std::atan2(s, a.dot(b)) * options_.trackballSpeed;
  // The scene turns by R (eye frame); the camera turns by R^-1 around the target.
  Eigen::Quaterniond r(Eigen::AngleAxisd(angle, axis / s));
  orientation_ = (orientation_ * r.inverse()).normalized();
}

double OrbitCamera::worldPerPixel() const {
  return 2.0 * distance_ * std::tan(options_.fovYDeg * M_PI / 360.0) / viewport_.height;
}

void OrbitCamera::pan(const Vec2& delta) {
  geom::Mat3 m = orientation_.toRotationMatrix();
  double k = worldPerPixel();
  target_ += -delta.x() * k * m.col(0) + delta.y() * k * m.col(1);
}

void OrbitCamera::zoom(double steps) { setDistance(distance_ * std::pow(options_.zoomStep, steps)); }

geom::Camera OrbitCamera::camera() const {
  geom::Mat3 m = orientation_.toRotationMatrix();
  Vec3 eye = target_ + distance_ * m.col(2);
  geom::Camera cam;
  cam.viewport = viewport_;
  cam.view = geom::Mat4::Identity();
  cam.view.block<3, 3>(0, 0) = m.transpose();
  cam.view.block<3, 1>(0, 3) = -m.transpose() * eye;
  // Depth range: the scene's bounding sphere as seen along the view axis, with some slack.
  Vec3 centre = scene_.empty() ? target_ : scene_.centre();
  double r = sceneRadius() * 1.1;
  double dc = (centre - eye).dot(-m.col(2));
  double aspect = viewport_.width / viewport_.height;
  double halfH = distance_ * std::tan(options_.fovYDeg * M_PI / 360.0);
  if (ortho_) {
    double zNear = dc - r, zFar = dc + r;
    cam.projection = geom::orthographic(-halfH * aspect, halfH * aspect, -halfH, halfH, zNear, zFar);
  } else {
    double zFar = std::max(dc + r, 1e-3 * r);
    double zNear = std::max(dc - r, zFar * 1e-4);
    cam.projection = geom::perspective(options_.fovYDeg, aspect, zNear, zFar);
  }
  return cam;
}

}  // namespace treesketch::viewer
