// Generalized-cylinder sweep of fitted discs (thesis §3.1.4, §4.4).
#include "treesketch/sweep/tube_mesh.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "treesketch/util/error.h"

namespace treesketch::sweep {

using geom::Vec3;

namespace {

bool usable(const SweepNode& n) {
  return n.fitted && n.disc.centre.allFinite() && n.disc.normal.allFinite() && n.disc.normal.norm() > 0.0 &&
         std::isfinite(n.disc.radius) && n.disc.radius > 0.0;
}

// The ring's own frame: e1 = a fixed perpendicular of the normal, e2 = n × e1 (ring CCW around n).
void ringFrame(const Disc& d, Vec3* n, Vec3* e1, Vec3* e2) {
  *n = d.normal.normalized();
  *e1 = geom::anyPerpendicular(*n);
  *e2 = n->cross(*e1);
}

}  // namespace

namespace {

// For every usable node, its nearest usable ancestor (kNoNode if none), sorted by child id.
// `byId` is scratch space.
void resolveFittedParents(const std::vector<SweepNode>& nodes, std::vector<std::pair<NodeId, std::size_t>>& byId,
                          std::vector<std::pair<NodeId, NodeId>>& out) {
  byId.clear();
  for (std::size_t i = 0; i < nodes.size(); ++i) byId.emplace_back(nodes[i].id, i);
  std::sort(byId.begin(), byId.end());
  auto find = [&](NodeId id) -> const SweepNode* {
    auto it = std::lower_bound(byId.begin(), byId.end(), std::make_pair(id, std::size_t(0)));
    return it != byId.end() && it->first == id ? &nodes[it->second] : nullptr;
  };
  out.clear();
  for (const auto& [id, i] : byId) {
    const SweepNode& n = nodes[i];
    if (!usable(n)) continue;
    NodeId p = n.parent;
    std::size_t steps = 0;
    while (p != kNoNode) {
      const SweepNode* q = find(p);
      if (!q) {
        p = kNoNode;
        break;
      }
      if (usable(*q)) break;
      p = q->parent;
      if (++steps > nodes.size()) throw OptionsError("sweep: the node hierarchy has a cycle at node " + std::to_string(n.id));
    }
    if (p == n.id) throw OptionsError("sweep: the node hierarchy has a cycle at node " + std::to_string(n.id));
    out.emplace_back(n.id, p);
  }
}

}  // namespace

std::map<NodeId, NodeId> fittedParents(const std::vector<SweepNode>& nodes) {
  std::vector<std::pair<NodeId, std::size_t>> byId;
  std::vector<std::pair<NodeId, NodeId>> list;
  resolveFittedParents(nodes, byId, list);
  return std::map<NodeId, NodeId>(list.begin(), list.end());
}

TubeSweeper::TubeSweeper(const SweepOptions& options) : options_(options) {
  if (options_.ringVertices < 3) throw OptionsError("sweep: ringVertices must be at least 3");
}

std::vector<SegmentKey> TubeSweeper::segmentKeys() const {
  std::vector<SegmentKey> keys;
  for (const auto& [k, b] : bands_) keys.push_back(k);
  return keys;
}

void TubeSweeper::update(const std::vector<SweepNode>& nodes) {
  const int kRing = options_.ringVertices;
  const std::uint64_t stamp = ++stamp_;
  // 1. Rings: rebuild changed discs, drop rings of nodes gone or no longer fitted.
  for (const auto& n : nodes) {
    if (!usable(n)) continue;
    Ring& ring = rings_[n.id];
    ring.stamp = stamp;
    if (ring.version != 0 && ring.disc == n.disc) continue;
    ring.disc = n.disc;
    ring.version = nextVersion_++;
    Vec3 nn, e1, e2;
    ringFrame(n.disc, &nn, &e1, &e2);
    ring.vertices.resize(kRing);
    for (int j = 0; j < kRing; ++j) {
      double a = 2.0 * M_PI * j / kRing;
      ring.vertices[j] = n.disc.centre + n.disc.radius * (std::cos(a) * e1 + std::sin(a) * e2);
    }
  }
  for (auto it = rings_.begin(); it != rings_.end();) it = it->second.stamp == stamp ? std::next(it) : rings_.erase(it);

  // 2. Bands: one per (fitted parent, fitted child); rebuilt when either ring changed.
  resolveFittedParents(nodes, byId_, parentOf_);
  for (const auto& [child, parent] : parentOf_) {
    if (parent == kNoNode) continue;
    const Ring& rp = rings_.at(parent);
    const Ring& rc = rings_.at(child);
    Band& band = bands_[SegmentKey{parent, child}];
    band.stamp = stamp;
    if (band.parentVersion == rp.version && band.childVersion == rc.version) continue;
    band.parentVersion = rp.version;
    band.childVersion = rc.version;
    Vec3 d = rc.disc.centre - rp.disc.centre;
    Vec3 np, ep1, ep2, nc, ec1, ec2;
    ringFrame(rp.disc, &np, &ep1, &ep2);
    ringFrame(rc.disc, &nc, &ec1, &ec2);
    if (d.norm() < 1e-12) d = np;
    // Walk both rings counter-clockwise around d.
    const int sp = np.dot(d) >= 0.0 ? 1 : -1;
    const int sc = nc.dot(d) >= 0.0 ? 1 : -1;
    // Parallel transport of the parent's start vector into the child's plane picks the child's
    // start vertex (the nearest ring vertex to the transported direction).
    Vec3 ref = ep1 - ep1.dot(nc) * nc;
    int offset = 0;
    if (ref.norm() > 1e-12) {
      double phi = std::atan2(ref.dot(ec2), ref.dot(ec1));
      offset = int(std::lround(phi / (2.0 * M_PI / kRing)));
      offset = ((offset % kRing) + kRing) % kRing;
    }
    band.parentIdx.resize(kRing);
    band.childIdx.resize(kRing);
    for (int j = 0; j < kRing; ++j) {
      band.parentIdx[j] = ((sp * j) % kRing + kRing) % kRing;
      band.childIdx[j] = ((offset + sc * j) % kRing + kRing) % kRing;
    }
    ++segmentBuilds_;
  }
  for (auto it = bands_.begin(); it != bands_.end();) it = it->second.stamp == stamp ? std::next(it) : bands_.erase(it);
  assemble(parentOf_);
}

void TubeSweeper::assemble(const ParentList& parentOf) {
  const int kRing = options_.ringVertices;
  // Cleared, not replaced: the arrays keep their capacity from one update to the next.
  mesh_.vertices.clear();
  mesh_.triangles.clear();
  mesh_.colors.clear();
  mesh_.quality.clear();
  for (auto& [id, ring] : rings_) {
    ring.base = std::uint32_t(mesh_.vertices.size());
    ring.hasChild = false;
    ring.childDir = Vec3::Zero();
    mesh_.vertices.insert(mesh_.vertices.end(), ring.vertices.begin(), ring.vertices.end());
  }
  for (const auto& [key, band] : bands_) {
    const std::uint32_t bp = rings_.at(key.first).base, bc = rings_.at(key.second).base;
    for (int j = 0; j < kRing; ++j) {
      int j1 = (j + 1) % kRing;
      std::uint32_t a0 = bp + band.parentIdx[j], a1 = bp + band.parentIdx[j1];
      std::uint32_t b0 = bc + band.childIdx[j], b1 = bc + band.childIdx[j1];
      mesh_.triangles.push_back({a0, a1, b1});
      mesh_.triangles.push_back({a0, b1, b0});
    }
  }
  // Caps: a fan at each ring without a fitted parent (facing away from its children) and at each
  // ring without fitted children (facing away from its parent).
  for (const auto& [child, parent] : parentOf) {
    if (parent == kNoNode) continue;
    Ring& rp = rings_.at(parent);
    rp.hasChild = true;
    const Vec3 d = rings_.at(child).disc.centre - rp.disc.centre;
    if (d.norm() > 0.0) rp.childDir += d.normalized();
  }
  auto addCap = [&](const Ring& ring, const Vec3& outward) {
    const Vec3 n = ring.disc.normal.normalized();
    const auto centre = std::uint32_t(mesh_.vertices.size());
    mesh_.vertices.push_back(ring.disc.centre);
    const bool ccw = n.dot(outward) >= 0.0;  // ring CCW around the outward direction
    const std::uint32_t b = ring.base;
    for (int j = 0; j < kRing; ++j) {
      std::uint32_t v0 = b + j, v1 = b + (j + 1) % kRing;
      if (ccw)
        mesh_.triangles.push_back({centre, v0, v1});
      else
        mesh_.triangles.push_back({centre, v1, v0});
    }
  };
  for (const auto& [id, parent] : parentOf) {
    const Ring& ring = rings_.at(id);
    const Vec3 n = ring.disc.normal.normalized();
    if (parent == kNoNode) addCap(ring, -(ring.childDir.norm() > 1e-12 ? ring.childDir : n));
    if (!ring.hasChild) {
      Vec3 away = n;
      if (parent != kNoNode) {
        const Vec3 d = ring.disc.centre - rings_.at(parent).disc.centre;
        if (d.norm() > 1e-12) away = d;
      }
      addCap(ring, away);
    }
  }
}

geom::TriMesh sweepTubes(const std::vector<SweepNode>& nodes, const SweepOptions& options) {
  TubeSweeper sweeper(options);
  sweeper.update(nodes);
  return sweeper.mesh();
}

}  // namespace treesketch::sweep
