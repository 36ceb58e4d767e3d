// Simulated users: sketches from known branch polylines (see polyline_sketch.h).
#include "treesketch/sketch/polyline_sketch.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <string>

#include "treesketch/util/error.h"

namespace treesketch::sketch {

using geom::Vec2;
using geom::Vec3;

namespace {

struct PlannedNode {
  Vec3 point;
  Vec3 tangent;
  int parent = -1;  ///< index into the plan; -1 for the root
};

std::string branchName(std::size_t i) { return "branch " + std::to_string(i); }

/// Branch indices in parent-before-child order; throws on bad structure.
std::vector<std::size_t> branchOrder(const std::vector<BranchPolyline>& branches) {
  if (branches.empty()) throw OptionsError("polyline sketch: no branches");
  std::size_t trunks = 0;
  for (std::size_t i = 0; i < branches.size(); ++i) {
    const BranchPolyline& b = branches[i];
    if (b.points.empty()) throw OptionsError("polyline sketch: " + branchName(i) + " has no points");
    for (const Vec3& p : b.points)
      if (!p.allFinite()) throw OptionsError("polyline sketch: " + branchName(i) + " has a NaN or Inf point");
    if (b.parent == -1) {
      ++trunks;
      continue;
    }
    if (b.parent < -1 || b.parent >= static_cast<int>(branches.size()) || b.parent == static_cast<int>(i))
      throw OptionsError("polyline sketch: " + branchName(i) + ": parent branch " + std::to_string(b.parent) +
                         " does not exist");
    if (b.parentVertex >= branches[b.parent].points.size())
      throw OptionsError("polyline sketch: " + branchName(i) + ": parentVertex " + std::to_string(b.parentVertex) +
                         " is past the end of branch " + std::to_string(b.parent));
  }
  if (trunks != 1)
    throw OptionsError("polyline sketch: exactly one branch must be the trunk (parent -1), found " +
                       std::to_string(trunks));
  // Depth of each branch (cycle check), then sort by depth.
  std::vector<int> depth(branches.size(), -1);
  for (std::size_t i = 0; i < branches.size(); ++i) {
    std::vector<std::size_t> path;
    std::size_t cur = i;
    while (depth[cur] < 0 && branches[cur].parent != -1) {
      path.push_back(cur);
      if (path.size() > branches.size())
        throw OptionsError("polyline sketch: " + branchName(i) + ": its parent branches form a cycle");
      cur = static_cast<std::size_t>(branches[cur].parent);
    }
    if (depth[cur] < 0) depth[cur] = 0;  // the trunk
    for (auto it = path.rbegin(); it != path.rend(); ++it) depth[*it] = depth[branches[*it].parent] + 1;
  }
  std::vector<std::size_t> order(branches.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return depth[a] < depth[b]; });
  return order;
}

double polylineLength(const std::vector<Vec3>& pts) {
  double len = 0;
  for (std::size_t i = 1; i < pts.size(); ++i) len += (pts[i] - pts[i - 1]).norm();
  return len;
}

/// Point and unit tangent at arc length t along the polyline (length > 0).
void sampleAt(const std::vector<Vec3>& pts, double t, Vec3& point, Vec3& tangent) {
  double acc = 0;
  std::size_t lastSeg = 0;
  for (std::size_t i = 1; i < pts.size(); ++i) {
    double seg = (pts[i] - pts[i - 1]).norm();
    if (seg <= 0) continue;
    lastSeg = i;
    if (t <= acc + seg) {
      double u = std::clamp((t - acc) / seg, 0.0, 1.0);
      point = pts[i - 1] + u * (pts[i] - pts[i - 1]);
      tangent = (pts[i] - pts[i - 1]) / seg;
      if (u == 1.0) {  // exactly on an interior vertex: mean of the two segments
        for (std::size_t j = i + 1; j < pts.size(); ++j) {
          double next = (pts[j] - pts[j - 1]).norm();
          if (next <= 0) continue;
          Vec3 mean = tangent + (pts[j] - pts[j - 1]) / next;
          if (mean.norm() > 1e-12) tangent = mean.normalized();
          break;
        }
      }
      return;
    }
    acc += seg;
  }
  point = pts[lastSeg];
  tangent = (pts[lastSeg] - pts[lastSeg - 1]).normalized();
}

std::vector<PlannedNode> plan(const std::vector<BranchPolyline>& branches, const PolylineSketchOptions& o) {
  std::vector<std::size_t> order = branchOrder(branches);
  std::vector<double> lengths(branches.size());
  double total = 0;
  for (std::size_t i = 0; i < branches.size(); ++i) total += lengths[i] = polylineLength(branches[i].points);
  if (!std::isfinite(total)) throw OptionsError("polyline sketch: polyline lengths are not finite");
  std::size_t trunk = order.front();
  if (!(lengths[trunk] > 0)) throw OptionsError("polyline sketch: the trunk (" + branchName(trunk) + ") has zero length");
  double spacing = o.nodeSpacing;
  if (!(spacing > 0)) {
    if (o.nodeCount < 1)
      throw OptionsError("polyline sketch: give a node spacing > 0 or a node count >= 1, got " +
                         std::to_string(o.nodeCount));
    spacing = total / o.nodeCount;
  }
  if (!std::isfinite(spacing)) throw OptionsError("polyline sketch: the node spacing is not finite");

  std::vector<PlannedNode> nodes;
  std::vector<std::vector<int>> branchNodes(branches.size());
  for (std::size_t b : order) {
    const BranchPolyline& br = branches[b];
    int attach = -1;
    if (b != trunk) {
      // Nearest node of the nearest ancestor that has nodes.
      std::size_t anc = static_cast<std::size_t>(br.parent);
      while (branchNodes[anc].empty() && branches[anc].parent != -1) anc = static_cast<std::size_t>(branches[anc].parent);
      const Vec3& junction = branches[br.parent].points[br.parentVertex];
      double best = std::numeric_limits<double>::infinity();
      for (int k : branchNodes[anc]) {
        double d = (nodes[k].point - junction).squaredNorm();
        if (d < best) {
          best = d;
          attach = k;
        }
      }
    }
    double len = lengths[b];
    if (!(len > 0)) continue;
    std::vector<double> arcs;
    if (b == trunk) arcs.push_back(0.0);
    long n = std::max(1L, std::lround(len / spacing));
    for (long k = 0; k < n; ++k) arcs.push_back((k + 0.5) * len / n);
    for (double t : arcs) {
      PlannedNode pn;
      sampleAt(br.points, t, pn.point, pn.tangent);
      pn.parent = attach;
      attach = static_cast<int>(nodes.size());
      branchNodes[b].push_back(attach);
      nodes.push_back(pn);
    }
  }
  return nodes;
}

/// A standard normal deviate (Box-Muller on 53-bit uniforms: the same on every platform).
double gaussian(std::mt19937_64& rng) {
  auto uniform = [&] { return (static_cast<double>(rng() >> 11) + 0.5) * 0x1.0p-53; };  // in (0, 1)
  double u1 = uniform(), u2 = uniform();
  return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * M_PI * u2);
}

void checkOptions(const PolylineSketchOptions& o) {
  if (!(o.pixelNoise >= 0) || !std::isfinite(o.pixelNoise))
    throw OptionsError("polyline sketch: pixel noise must be >= 0, got " + std::to_string(o.pixelNoise));
}

}  // namespace

Sketch sketchFromPolylines(const std::vector<BranchPolyline>& branches, const geom::Camera& camera,
                           const PolylineSketchOptions& options) {
  checkOptions(options);
  camera.validate("polyline sketch");
  std::vector<PlannedNode> nodes = plan(branches, options);
  Sketch sk;
  sk.up = options.up;
  sk.defaults = options.params;
  int cam = sk.addCamera(camera);
  std::mt19937_64 rng(options.seed);
  std::vector<NodeId> ids(nodes.size());
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    Vec3 s = camera.project(nodes[i].point);
    if (!s.allFinite() || s.z() < 0.0 || s.z() > 1.0)
      throw OptionsError("polyline sketch: a branch point is behind the camera or outside its depth range");
    Vec2 screen = s.head<2>();
    if (options.pixelNoise > 0) {
      double dx = gaussian(rng), dy = gaussian(rng);
      screen += options.pixelNoise * Vec2(dx, dy);
    }
    NodeId parent = nodes[i].parent < 0 ? kNoNode : ids[nodes[i].parent];
    ids[i] = sk.addScreenNode(parent, cam, screen, options.params);
  }
  return sk;
}

Sketch pointNodesFromPolylines(const std::vector<BranchPolyline>& branches, const PolylineSketchOptions& options) {
  checkOptions(options);
  std::vector<PlannedNode> nodes = plan(branches, options);
  Sketch sk;
  sk.up = options.up;
  sk.defaults = options.params;
  std::vector<NodeId> ids(nodes.size());
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    NodeId parent = nodes[i].parent < 0 ? kNoNode : ids[nodes[i].parent];
    ids[i] = sk.addPointNode(parent, nodes[i].point, nodes[i].tangent, options.params);
  }
  return sk;
}

}  // namespace treesketch::sketch
