// Triangle meshes with optional per-vertex colour and quality (used for error maps).
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "treesketch/geom/types.h"

namespace treesketch::geom {

struct TriMesh {
  std::vector<Vec3> vertices;
  std::vector<std::array<std::uint32_t, 3>> triangles;
  /// Optional per-vertex RGB colour; empty or one per vertex.
  std::vector<std::array<std::uint8_t, 3>> colors;
  /// Optional per-vertex scalar (MeshLab's "quality"); empty or one per vertex.
  std::vector<double> quality;

  bool empty() const { return triangles.empty(); }
  BBox bounds() const;
  /// Total surface area.
  double area() const;
  /// Appends `other`, offsetting its indices. Attributes are kept only if both meshes have them.
  void append(const TriMesh& other);
  /// Throws OptionsError when an index is out of range or an attribute array has the wrong size.
  void checkConsistent() const;
};

}  // namespace treesketch::geom
