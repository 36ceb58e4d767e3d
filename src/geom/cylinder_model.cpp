// Cylinder models: piece volume and bounds, and the frustums of a node model.
#include "treesketch/geom/cylinder_model.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "treesketch/util/error.h"

namespace treesketch::geom {

double ModelCylinder::volume() const {
  const double r0 = startRadius, r1 = endRadius;
  return std::numbers::pi * length() * (r0 * r0 + r0 * r1 + r1 * r1) / 3.0;
}

BBox ModelCylinder::bounds() const {
  BBox box;
  const Vec3 d = end - start;
  const double len = d.norm();
  // An end disc of radius r with unit normal u reaches r·sqrt(1 - u_k²) along axis k; a
  // zero-length piece has no direction, so its disc is bounded by a ball.
  Vec3 reach = Vec3::Ones();
  if (len > 0) {
    const Vec3 u = d / len;
    for (int k = 0; k < 3; ++k) reach[k] = std::sqrt(std::max(0.0, 1.0 - u[k] * u[k]));
  }
  box.add(start - startRadius * reach);
  box.add(start + startRadius * reach);
  box.add(end - endRadius * reach);
  box.add(end + endRadius * reach);
  return box;
}

CylinderModel cylinderModelFromNodes(const std::vector<ModelNode>& nodes) {
  CylinderModel model;
  const auto n = static_cast<std::int64_t>(nodes.size());
  std::vector<std::int64_t> piece(nodes.size(), -1);  // node → its piece
  for (std::int64_t i = 0; i < n; ++i) {
    const std::int64_t p = nodes[i].parent;
    if (p < -1 || p >= n || p == i)
      throw OptionsError("cylinder model: node " + std::to_string(i) + " has parent " + std::to_string(p) + " of " +
                         std::to_string(n) + " nodes");
    if (p < 0) continue;
    piece[i] = static_cast<std::int64_t>(model.cylinders.size());
    model.cylinders.emplace_back();
  }
  for (std::int64_t i = 0; i < n; ++i) {
    if (piece[i] < 0) continue;
    const ModelNode& a = nodes[nodes[i].parent];
    ModelCylinder& c = model.cylinders[piece[i]];
    c.start = a.position;
    c.end = nodes[i].position;
    c.startRadius = a.radius;
    c.endRadius = nodes[i].radius;
    c.parent = piece[nodes[i].parent];
    c.branchOrder = nodes[i].branchOrder;
  }
  return model;
}

}  // namespace treesketch::geom
