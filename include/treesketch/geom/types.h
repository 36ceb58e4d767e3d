// Basic geometry: vectors (Eigen, double precision), axis-aligned boxes, the up-axis convention.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <limits>
#include <string>
#include <vector>

namespace treesketch::geom {

using Vec2 = Eigen::Vector2d;
using Vec3 = Eigen::Vector3d;
using Vec3f = Eigen::Vector3f;
using Mat3 = Eigen::Matrix3d;
using Mat4 = Eigen::Matrix4d;

/// Axis-aligned bounding box. Empty (min > max) until a point is added.
struct BBox {
  Vec3 min = Vec3::Constant(std::numeric_limits<double>::infinity());
  Vec3 max = Vec3::Constant(-std::numeric_limits<double>::infinity());

  bool empty() const { return (min.array() > max.array()).any(); }
  void add(const Vec3& p) {
    min = min.cwiseMin(p);
    max = max.cwiseMax(p);
  }
  void add(const BBox& b) {
    if (b.empty()) return;
    add(b.min);
    add(b.max);
  }
  Vec3 centre() const { return 0.5 * (min + max); }
  Vec3 extent() const { return empty() ? Vec3::Zero() : Vec3(max - min); }
  /// Length of the diagonal; 0 for an empty box.
  double diagonal() const { return empty() ? 0.0 : (max - min).norm(); }
};

/// Which world axis points up. Real LIDAR is Z-up; many meshes (and the third-party trees) are
/// Y-up. The library never rotates data: algorithms that need "up" take this vector.
enum class UpAxis { Y, Z };

inline Vec3 upVector(UpAxis up) { return up == UpAxis::Y ? Vec3(0, 1, 0) : Vec3(0, 0, 1); }
/// Height of a point along the up axis.
inline double height(const Vec3& p, UpAxis up) { return up == UpAxis::Y ? p.y() : p.z(); }
/// Parses "y" or "z" (case-insensitive); throws OptionsError otherwise.
UpAxis parseUpAxis(const std::string& s);
inline const char* toString(UpAxis up) { return up == UpAxis::Y ? "y" : "z"; }

/// Any unit vector perpendicular to `n` (n need not be normalized, must be non-zero).
Vec3 anyPerpendicular(const Vec3& n);

}  // namespace treesketch::geom
