// Small meshes with known geometry and a brute-force point-triangle distance, shared by the
// accel/ray_scene and scan tests.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

#include "treesketch/geom/tri_mesh.h"

namespace treesketch::test {

using geom::TriMesh;
using geom::Vec3;

/// Axis-aligned box [lo, hi] as 12 triangles. `skipFace` (0..5 = -x,+x,-y,+y,-z,+z) leaves a
/// face out (an open box); -1 keeps all.
inline TriMesh makeBox(const Vec3& lo, const Vec3& hi, int skipFace = -1) {
  TriMesh m;
  for (int i = 0; i < 8; ++i)
    m.vertices.emplace_back((i & 1) ? hi.x() : lo.x(), (i & 2) ? hi.y() : lo.y(), (i & 4) ? hi.z() : lo.z());
  const std::uint32_t faces[6][4] = {{0, 4, 6, 2}, {1, 3, 7, 5}, {0, 1, 5, 4},
                                     {2, 6, 7, 3}, {0, 2, 3, 1}, {4, 5, 7, 6}};
  for (int f = 0; f < 6; ++f) {
    if (f == skipFace) continue;
    m.triangles.push_back({faces[f][0], faces[f][1], faces[f][2]});
    m.triangles.push_back({faces[f][0], faces[f][2], faces[f][3]});
  }
  return m;
}

/// Square [-h, h]^2 in the plane z = z0 with a square hole [-hole, hole]^2 (hole = 0: no hole).
inline TriMesh makeSquare(double h, double hole = 0.0, double z0 = 0.0) {
  TriMesh m;
  auto quad = [&](double x0, double y0, double x1, double y1) {
    const auto b = static_cast<std::uint32_t>(m.vertices.size());
    m.vertices.emplace_back(x0, y0, z0);
    m.vertices.emplace_back(x1, y0, z0);
    m.vertices.emplace_back(x1, y1, z0);
    m.vertices.emplace_back(x0, y1, z0);
    m.triangles.push_back({b, b + 1, b + 2});
    m.triangles.push_back({b, b + 2, b + 3});
  };
  if (hole <= 0.0) {
    quad(-h, -h, h, h);
  } else {
    quad(-h, -h, h, -hole);
    quad(-h, hole, h, h);
    quad(-h, -hole, -hole, hole);
    quad(hole, -hole, h, hole);
  }
  return m;
}

/// A closed tube (cylinder with caps) along z: radius r, from z0 to z1, `sides` around.
inline TriMesh makeTube(const Vec3& base, double r, double length, int sides) {
  TriMesh m;
  for (int k = 0; k < 2; ++k)
    for (int i = 0; i < sides; ++i) {
      const double a = 2.0 * M_PI * i / sides;
      m.vertices.push_back(base + Vec3(r * std::cos(a), r * std::sin(a), k * length));
    }
  const auto s = static_cast<std::uint32_t>(sides);
  for (std::uint32_t i = 0; i < s; ++i) {
    const std::uint32_t j = (i + 1) % s;
    m.triangles.push_back({i, j, s + j});
    m.triangles.push_back({i, s + j, s + i});
  }
  const auto c0 = static_cast<std::uint32_t>(m.vertices.size());
  m.vertices.push_back(base);
  m.vertices.push_back(base + Vec3(0, 0, length));
  for (std::uint32_t i = 0; i < s; ++i) {
    const std::uint32_t j = (i + 1) % s;
    m.triangles.push_back({c0, j, i});
    m.triangles.push_back({c0 + 1, s + i, s + j});
  }
  return m;
}

/// Distance from p to triangle abc (exact, by regions; after Ericson, Real-Time Collision Detection).
inline double pointTriangleDistance(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return (p - a).norm();
  const Vec3 bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return (p - b).norm();
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return (p - (a + ab * (d1 / (d1 - d3)))).norm();
  const Vec3 cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return (p - c).norm();
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return (p - (a + ac * (d2 / (d2 - d6)))).norm();
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0)
    return (p - (b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6))))).norm();
  const double denom = 1.0 / (va + vb + vc);
  return (p - (a + ab * (vb * denom) + ac * (vc * denom))).norm();
}

/// Distance from p to the nearest triangle of m (brute force).
inline double pointMeshDistance(const Vec3& p, const TriMesh& m) {
  double best = std::numeric_limits<double>::infinity();
  for (const auto& t : m.triangles)
    best = std::min(best, pointTriangleDistance(p, m.vertices[t[0]], m.vertices[t[1]], m.vertices[t[2]]));
  return best;
}

/// Nearest ray-triangle hit parameter in double (Moller-Trumbore), or +inf.
inline double bruteForceRay(const Vec3& o, const Vec3& d, const TriMesh& m) {
  double best = std::numeric_limits<double>::infinity();
  for (const auto& t : m.triangles) {
    const Vec3 a = m.vertices[t[0]], e1 = m.vertices[t[1]] - a, e2 = m.vertices[t[2]] - a;
    const Vec3 pv = d.cross(e2);
    const double det = e1.dot(pv);
    if (std::abs(det) < 1e-300) continue;
    const Vec3 tv = o - a;
    const double u = tv.dot(pv) / det;
    if (u < 0 || u > 1) continue;
    const Vec3 qv = tv.cross(e1);
    const double v = d.dot(qv) / det;
    if (v < 0 || u + v > 1) continue;
    const double tt = e2.dot(qv) / det;
    if (tt >= 0 && tt < best) best = tt;
  }
  return best;
}

}  // namespace treesketch::test
