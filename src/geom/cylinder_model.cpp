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
    c.endRadius = nodes[i].radius;
    // A piece that starts a branch (its order above its parent node's) is the branch's own
    // cylinder: a frustum from the parent's radius would flare from the parent's axis out past
    // its surface, a cone of the parent's thickness along the branch (adtree_tree7: 0.5 % of the
    // points deeper than 2 cm inside such cones). The branch starts at the parent's axis with its
    // own radius, as QSM cylinders do.
    const bool startsBranch = nodes[i].branchOrder >= 0 && a.branchOrder >= 0 && nodes[i].branchOrder > a.branchOrder;
    c.startRadius = startsBranch ? std::min(a.radius, nodes[i].radius) : a.radius;
    c.parent = piece[nodes[i].parent];
    c.branchOrder = nodes[i].branchOrder;
  }
  return model;
}

namespace {

/// The child of `p` that continues its branch, or -1.
std::int64_t continuation(const CylinderModel& model, std::int64_t p, const std::vector<std::int64_t>& kids,
                          bool givenOrders) {
  const ModelCylinder& parent = model.cylinders[p];
  const Vec3 d = parent.end - parent.start;
  const double len = d.norm();
  std::int64_t best = -1;
  double bestRadius = -1, bestAlign = -2;
  for (std::int64_t k : kids) {
    const ModelCylinder& c = model.cylinders[k];
    if (givenOrders && c.branchOrder != parent.branchOrder) continue;
    const Vec3 e = c.end - c.start;
    const double align = len > 0 && e.norm() > 0 ? d.dot(e) / (len * e.norm()) : -1;
    if (c.startRadius > bestRadius || (c.startRadius == bestRadius && align > bestAlign)) {
      best = k;
      bestRadius = c.startRadius;
      bestAlign = align;
    }
  }
  return best;
}

}  // namespace

BranchStructure branchStructure(const CylinderModel& model, UpAxis up) {
  const auto n = static_cast<std::int64_t>(model.size());
  BranchStructure b;
  b.order.assign(n, -1);
  b.branch.assign(n, -1);
  b.position.assign(n, 0);
  b.extension.assign(n, -1);
  std::vector<std::vector<std::int64_t>> kids(n);
  std::vector<std::int64_t> roots;
  bool givenOrders = n > 0;
  for (std::int64_t i = 0; i < n; ++i) {
    const std::int64_t p = model.cylinders[i].parent;
    if (p < -1 || p >= n || p == i)
      throw OptionsError("branch structure: piece " + std::to_string(i) + " has parent " + std::to_string(p) + " of " +
                         std::to_string(n) + " pieces");
    (p < 0 ? roots : kids[p]).push_back(i);
    givenOrders = givenOrders && model.cylinders[i].branchOrder >= 0;
  }
  auto low = [&](std::int64_t i) {
    const ModelCylinder& c = model.cylinders[i];
    return std::min(height(c.start, up), height(c.end, up));
  };
  std::stable_sort(roots.begin(), roots.end(), [&](std::int64_t a, std::int64_t c) { return low(a) < low(c); });
  // Each branch is walked from its first piece along the extensions; other children are queued
  // as the first pieces of new branches (breadth first, so branch indices grow with order).
  std::vector<std::int64_t> queue(roots.begin(), roots.end());
  std::vector<std::int64_t> queueParent(roots.size(), -1);
  std::size_t visited = 0;
  for (std::size_t q = 0; q < queue.size(); ++q) {
    const std::int64_t first = queue[q], parentBranch = queueParent[q];
    const auto id = static_cast<std::int64_t>(b.branchOrder.size());
    std::int32_t order = 0;
    if (givenOrders)
      order = model.cylinders[first].branchOrder;
    else if (parentBranch >= 0)
      order = b.branchOrder[parentBranch] + 1;
    else
      order = q == 0 ? 0 : 1;
    b.branchOrder.push_back(order);
    b.branchParent.push_back(parentBranch);
    std::int64_t pos = 0;
    for (std::int64_t i = first; i >= 0; i = b.extension[i]) {
      if (b.branch[i] >= 0) throw OptionsError("branch structure: the parent links form a cycle");
      b.branch[i] = id;
      b.order[i] = order;
      b.position[i] = pos++;
      ++visited;
      b.extension[i] = continuation(model, i, kids[i], givenOrders);
      for (std::int64_t k : kids[i])
        if (k != b.extension[i]) {
          queue.push_back(k);
          queueParent.push_back(id);
        }
    }
  }
  if (visited != static_cast<std::size_t>(n))
    throw OptionsError("branch structure: the parent links form a cycle (" + std::to_string(n - visited) +
                       " pieces not reachable from a root)");
  return b;
}

}  // namespace treesketch::geom
