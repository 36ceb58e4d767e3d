// The sweep: fitted discs become rings of vertices in their nodes' planes, parent and child rings
// are joined by bands of triangles (generalized cylinders), and the ends get triangle-fan caps
// (thesis §3.1.4, §4.4 "triangles from the disc to the parent's disc... a triangle fan").
//
// Topology: one band ("segment") per fitted node and its nearest fitted ancestor, keyed by
// (parent, child). A skipped or disabled node is bridged: its fitted children join its nearest
// fitted ancestor. At a branching node every child's band starts at the parent's ring (shared
// vertices), so the mesh is a watertight tube along each chain but non-manifold at the ring of a
// branching node (its ring edges belong to more than two triangles): branch junctions are not
// blended (known limit, as in the thesis).
// Twist: each ring has its own frame; a band matches the child ring's start vertex to the
// parent's start vector transported into the child's plane (projected), so a band twists by at
// most half a vertex step. Band orientation follows the parent→child direction, so normals point
// outward whatever the sign of the sketch's plane normals.
#pragma once

#include <cstdint>
#include <map>
#include <utility>
#include <vector>

#include "treesketch/geom/tri_mesh.h"
#include "treesketch/geom/types.h"
#include "treesketch/sketch/node_id.h"

namespace treesketch::sweep {

using sketch::kNoNode;
using sketch::NodeId;

/// A fitted cross-section: centre (world), unit plane normal (either sign), radius (world units).
struct Disc {
  geom::Vec3 centre = geom::Vec3::Zero();
  geom::Vec3 normal = geom::Vec3::UnitY();
  double radius = 0.0;
  bool operator==(const Disc&) const = default;
};

/// One sketch node as the sweep sees it: its sketch parent (kNoNode for the root), whether it
/// was fitted, and its disc (ignored when not fitted).
struct SweepNode {
  NodeId id = kNoNode;
  NodeId parent = kNoNode;
  bool fitted = false;
  Disc disc;
};

struct SweepOptions {
  /// Vertices per ring (K). Design choice: 16 (the thesis does not give its count).
  int ringVertices = 16;
};

using SegmentKey = std::pair<NodeId, NodeId>;  ///< (fitted parent, fitted child)

/// For every fitted node, its nearest fitted ancestor (kNoNode if none). Nodes whose parent is
/// unknown are treated as roots. Throws OptionsError on a parent cycle.
std::map<NodeId, NodeId> fittedParents(const std::vector<SweepNode>& nodes);

/// Keeps rings and bands between updates and rebuilds only the bands whose rings changed.
class TubeSweeper {
 public:
  /// Throws OptionsError for ringVertices < 3.
  explicit TubeSweeper(const SweepOptions& options = {});

  /// Brings the mesh up to date with `nodes` (the whole sketch each time; cheap to diff). Rings
  /// are rebuilt for discs that changed, bands for (parent, child) pairs whose rings changed or
  /// that are new; caps are always rebuilt (K triangles each). A fitted node with a zero or
  /// non-finite radius or normal is treated as not fitted.
  void update(const std::vector<SweepNode>& nodes);

  /// The assembled mesh: ring vertices of each fitted node (in id order), cap centres, then bands
  /// and caps. Empty when nothing is fitted.
  const geom::TriMesh& mesh() const { return mesh_; }
  /// Current bands, in key order.
  std::vector<SegmentKey> segmentKeys() const;
  /// Number of bands built since construction (for tests of incremental updates).
  std::size_t segmentBuilds() const { return segmentBuilds_; }

 private:
  struct Ring {
    Disc disc;
    std::vector<geom::Vec3> vertices;
    std::uint64_t version = 0;
    std::uint64_t stamp = 0;  ///< the update that last saw this ring's node fitted
    // Scratch of assemble(): first vertex in the mesh, whether a fitted child hangs from this
    // ring, and the sum of the unit directions towards those children.
    std::uint32_t base = 0;
    bool hasChild = false;
    geom::Vec3 childDir = geom::Vec3::Zero();
  };
  struct Band {
    std::uint64_t parentVersion = 0, childVersion = 0;
    std::uint64_t stamp = 0;               ///< the update that last needed this band
    std::vector<int> parentIdx, childIdx;  ///< ring-local vertex index of step j on each ring
  };
  /// (child, nearest fitted ancestor or kNoNode) for every fitted node, by child id.
  using ParentList = std::vector<std::pair<NodeId, NodeId>>;
  void assemble(const ParentList& parentOf);

  // Per-update bookkeeping lives in the rings and bands themselves (stamps, scratch fields), so
  // that an update after a one-node edit allocates nothing but what changed: an edit's re-sweep
  // is on the interactive path (measured: the node-keyed sets and maps rebuilt on every update
  // were a fifth of a one-node edit).
  SweepOptions options_;
  std::map<NodeId, Ring> rings_;
  std::map<SegmentKey, Band> bands_;
  std::uint64_t nextVersion_ = 1;
  std::uint64_t stamp_ = 0;
  std::vector<std::pair<NodeId, std::size_t>> byId_;  ///< scratch: node id → index in the input
  ParentList parentOf_;                               ///< scratch
  std::size_t segmentBuilds_ = 0;
  geom::TriMesh mesh_;
};

/// One-shot sweep (a fresh TubeSweeper). Empty mesh when no node is fitted.
geom::TriMesh sweepTubes(const std::vector<SweepNode>& nodes, const SweepOptions& options = {});

}  // namespace treesketch::sweep
