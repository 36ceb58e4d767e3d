// Meshes with known geometry for the comparison tests: icospheres, planar grids, random soups.
#pragma once

#include <algorithm>
#include <cmath>
#include <map>
#include <random>
#include <utility>

#include "treesketch/geom/tri_mesh.h"

namespace treesketch::compare::testing {

using geom::TriMesh;
using geom::Vec3;

/// An icosahedron subdivided `levels` times (each triangle into four), vertices on the sphere of
/// `radius` around `centre`. Faces counter-clockwise seen from outside.
inline TriMesh icosphere(double radius, int levels, const Vec3& centre = Vec3::Zero()) {
  const double t = (1 + std::sqrt(5.0)) / 2;
  TriMesh m;
  m.vertices = {{-1, t, 0},  {1, t, 0},  {-1, -t, 0}, {1, -t, 0}, {0, -1, t},  {0, 1, t},
                {0, -1, -t}, {0, 1, -t}, {t, 0, -1},  {t, 0, 1},  {-t, 0, -1}, {-t, 0, 1}};
  m.triangles = {{0, 11, 5},  {0, 5, 1},  {0, 1, 7},  {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
                 {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
                 {3, 8, 9},   {4, 9, 5},  {2, 4, 11}, {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
  for (auto& v : m.vertices) v.normalize();
  for (int l = 0; l < levels; ++l) {
    std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> mid;
    auto midpoint = [&](std::uint32_t a, std::uint32_t b) {
      auto key = std::make_pair(std::min(a, b), std::max(a, b));
      auto it = mid.find(key);
      if (it != mid.end()) return it->second;
      m.vertices.push_back((m.vertices[a] + m.vertices[b]).normalized());
      auto idx = static_cast<std::uint32_t>(m.vertices.size() - 1);
      mid[key] = idx;
      return idx;
    };
    std::vector<std::array<std::uint32_t, 3>> next;
    for (const auto& f : m.triangles) {
      std::uint32_t ab = midpoint(f[0], f[1]), bc = midpoint(f[1], f[2]), ca = midpoint(f[2], f[0]);
      next.push_back({f[0], ab, ca});
      next.push_back({f[1], bc, ab});
      next.push_back({f[2], ca, bc});
      next.push_back({ab, bc, ca});
    }
    m.triangles = std::move(next);
  }
  for (auto& v : m.vertices) v = centre + radius * v;
  return m;
}

/// Smallest distance from `centre` to any triangle's plane: the mesh lies between this radius and
/// the sphere's (the faceting error of an icosphere is radius minus this).
inline double innerRadius(const TriMesh& m, const Vec3& centre = Vec3::Zero()) {
  double r = std::numeric_limits<double>::infinity();
  for (const auto& f : m.triangles) {
    const Vec3 &a = m.vertices[f[0]], &b = m.vertices[f[1]], &c = m.vertices[f[2]];
    Vec3 n = (b - a).cross(c - a).normalized();
    r = std::min(r, std::abs(n.dot(a - centre)));
  }
  return r;
}

/// An n × n grid of squares over [0, size]² at height z (2 n² triangles).
inline TriMesh grid(int n, double size, double z) {
  TriMesh m;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) m.vertices.push_back({size * i / n, size * j / n, z});
  auto id = [n](int i, int j) { return static_cast<std::uint32_t>(j * (n + 1) + i); };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      m.triangles.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      m.triangles.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  return m;
}

/// A soup of `count` random triangles (sides up to ~0.3) in the unit cube.
inline TriMesh randomSoup(std::uint64_t seed, int count) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0, 1), s(-0.15, 0.15);
  TriMesh m;
  for (int i = 0; i < count; ++i) {
    Vec3 c(u(rng), u(rng), u(rng));
    auto base = static_cast<std::uint32_t>(m.vertices.size());
    for (int k = 0; k < 3; ++k) m.vertices.push_back(c + Vec3(s(rng), s(rng), s(rng)));
    m.triangles.push_back({base, base + 1, base + 2});
  }
  return m;
}

}  // namespace treesketch::compare::testing
