// Generalized-cylinder sweep of fitted discs (thesis §3.1.4, §4.4).
#include "treesketch/sweep/tube_mesh.h"

#include <cmath>
#include <set>
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

std::map<NodeId, NodeId> fittedParents(const std::vector<SweepNode>& nodes) {
  std::map<NodeId, const SweepNode*> byId;
  for (const auto& n : nodes) byId[n.id] = &n;
  std::map<NodeId, NodeId> out;
  for (const auto& n : nodes) {
    if (!usable(n)) continue;
    NodeId p = n.parent;
    std::size_t steps = 0;
    while (p != kNoNode) {
      auto it = byId.find(p);
      if (it == byId.end()) {
        p = kNoNode;
        break;
      }
      if (usable(*it->second)) break;
      p = it->second->parent;
      if (++steps > nodes.size()) throw OptionsError("sweep: the node hierarchy has a cycle at node " + std::to_string(n.id));
    }
    if (p == n.id) throw OptionsError("sweep: the node hierarchy has a cycle at node " + std::to_string(n.id));
    out[n.id] = p;
  }
  return out;
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
  // 1. Rings: rebuild changed discs, drop rings of nodes gone or no longer fitted.
  std::set<NodeId> live;
  for (const auto& n : nodes) {
    if (!usable(n)) continue;
    live.insert(n.id);
    auto it = rings_.find(n.id);
    if (it != rings_.end() && it->second.disc == n.disc) continue;
    Ring& ring = rings_[n.id];
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
  for (auto it = rings_.begin(); it != rings_.end();) it = live.count(it->first) ? std::next(it) : rings_.erase(it);

  // 2. Bands: one per (fitted parent, fitted child); rebuilt when either ring changed.
  auto parentOf = fittedParents(nodes);
  std::map<SegmentKey, Band> bands;
  for (const auto& [child, parent] : parentOf) {
    if (parent == kNoNode) continue;
    SegmentKey key{parent, child};
    const Ring& rp = rings_.at(parent);
    const Ring& rc = rings_.at(child);
    auto old = bands_.find(key);
    if (old != bands_.end() && old->second.parentVersion == rp.version && old->second.childVersion == rc.version) {
      bands[key] = std::move(old->second);
      continue;
    }
    Band band;
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
    bands[key] = std::move(band);
  }
  bands_ = std::move(bands);
  assemble(parentOf);
}

void TubeSweeper::assemble(const std::map<NodeId, NodeId>& parentOf) {
  const int kRing = options_.ringVertices;
  mesh_ = geom::TriMesh{};
  std::map<NodeId, std::uint32_t> base;
  for (const auto& [id, ring] : rings_) {
    base[id] = std::uint32_t(mesh_.vertices.size());
    mesh_.vertices.insert(mesh_.vertices.end(), ring.vertices.begin(), ring.vertices.end());
  }
  for (const auto& [key, band] : bands_) {
    std::uint32_t bp = base.at(key.first), bc = base.at(key.second);
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
  std::map<NodeId, Vec3> childDir;
  std::set<NodeId> hasChild;
  for (const auto& [child, parent] : parentOf) {
    if (parent == kNoNode) continue;
    hasChild.insert(parent);
    Vec3 d = rings_.at(child).disc.centre - rings_.at(parent).disc.centre;
    if (d.norm() > 0.0) {
      // Eigen vectors are not zero-initialised: insert an explicit zero before summing.
      auto it = childDir.try_emplace(parent, Vec3::Zero()).first;
      it->second += d.normalized();
    }
  }
  auto addCap = [&](NodeId id, const Vec3& outward) {
    const Ring& ring = rings_.at(id);
    Vec3 n = ring.disc.normal.normalized();
    auto centre = std::uint32_t(mesh_.vertices.size());
    mesh_.vertices.push_back(ring.disc.centre);
    const bool ccw = n.dot(outward) >= 0.0;  // ring CCW around the outward direction
    const std::uint32_t b = base.at(id);
    for (int j = 0; j < kRing; ++j) {
      std::uint32_t v0 = b + j, v1 = b + (j + 1) % kRing;
      if (ccw)
        mesh_.triangles.push_back({centre, v0, v1});
      else
        mesh_.triangles.push_back({centre, v1, v0});
    }
  };
  for (const auto& [id, parent] : parentOf) {
    const Vec3 n = rings_.at(id).disc.normal.normalized();
    if (parent == kNoNode) {
      auto it = childDir.find(id);
      Vec3 toward = (it != childDir.end() && it->second.norm() > 1e-12) ? it->second : n;
      addCap(id, -toward);
    }
    if (!hasChild.count(id)) {
      Vec3 away = n;
      if (parent != kNoNode) {
        Vec3 d = rings_.at(id).disc.centre - rings_.at(parent).disc.centre;
        if (d.norm() > 1e-12) away = d;
      }
      addCap(id, away);
    }
  }
}

geom::TriMesh sweepTubes(const std::vector<SweepNode>& nodes, const SweepOptions& options) {
  TubeSweeper sweeper(options);
  sweeper.update(nodes);
  return sweeper.mesh();
}

}  // namespace treesketch::sweep
