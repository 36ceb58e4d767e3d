#include "treesketch/geom/tri_mesh.h"

#include "treesketch/util/error.h"

namespace treesketch::geom {

BBox TriMesh::bounds() const {
  BBox b;
  for (const auto& v : vertices) b.add(v);
  return b;
}

double TriMesh::area() const {
  double a = 0;
  for (const auto& t : triangles) {
    a += 0.5 * (vertices[t[1]] - vertices[t[0]]).cross(vertices[t[2]] - vertices[t[0]]).norm();
  }
  return a;
}

void TriMesh::append(const TriMesh& other) {
  bool keepColors = colors.size() == vertices.size() && other.colors.size() == other.vertices.size();
  bool keepQuality = quality.size() == vertices.size() && other.quality.size() == other.vertices.size();
  auto base = static_cast<std::uint32_t>(vertices.size());
  vertices.insert(vertices.end(), other.vertices.begin(), other.vertices.end());
  for (auto t : other.triangles) triangles.push_back({t[0] + base, t[1] + base, t[2] + base});
  if (keepColors) colors.insert(colors.end(), other.colors.begin(), other.colors.end());
  else colors.clear();
  if (keepQuality) quality.insert(quality.end(), other.quality.begin(), other.quality.end());
  else quality.clear();
}

void TriMesh::checkConsistent() const {
  for (std::size_t i = 0; i < triangles.size(); ++i) {
    for (auto idx : triangles[i]) {
      if (idx >= vertices.size())
        throw OptionsError("mesh: triangle " + std::to_string(i) + " references vertex " + std::to_string(idx) +
                           " of " + std::to_string(vertices.size()));
    }
  }
  if (!colors.empty() && colors.size() != vertices.size()) throw OptionsError("mesh: colour array size mismatch");
  if (!quality.empty() && quality.size() != vertices.size()) throw OptionsError("mesh: quality array size mismatch");
}

}  // namespace treesketch::geom
