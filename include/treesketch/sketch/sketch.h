// The sketch: a tree of nodes a user draws over a view of the cloud (or an automatic method
// proposes). Each node becomes a 3D line and a plane (thesis §3.1.2, §4.3); the fit module
// slices the cloud with that plane and fits the branch's circle.
//
// Nodes are of two kinds:
//  - screen nodes: a 2D position (pixels, top-left origin) under one of the sketch's cameras.
//    Because each node keeps its own camera, one sketch can mix nodes drawn from several views
//    (thesis §6.3, future work).
//  - point nodes: a 3D point and a plane normal given directly (automatic methods).
//
// Module rule: sketch is the model and depends only on geom and util. Reading and writing
// sketches (and camera files) is io's job (io/sketch_file.h): io may include sketch, sketch never
// includes io, so the two cannot form a cycle.
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "treesketch/geom/camera.h"
#include "treesketch/geom/types.h"
#include "treesketch/sketch/node_id.h"

namespace treesketch::sketch {

/// Sine of the angle below which two view rays count as parallel in Sketch::geometry (a numerical
/// tolerance, not a tunable: one pixel of a 30° perspective view at 1280 px is ~4e-4 rad).
constexpr double kParallelTolerance = 1e-6;

/// Per-node sampling sizes, in world units (the cloud's units). Thesis §4.4, appendix B.
struct SamplingParams {
  /// Half-thickness ε of the slab around the node's plane: points closer than this to the plane
  /// form the slice ("nearPts"). Thesis: the constant EPSILON.
  double sliceHalfThickness = 0.05;
  /// Initial radius of the cylinder around the node's line L: slice points closer than this to L
  /// are the RANSAC test points ("testPts"). Thesis: the user-defined lineEpsilon.
  double lineEpsilon = 0.25;
  /// How much lineEpsilon grows after each failed fit (thesis: lineEpsilon++, i.e. one unit).
  double lineEpsilonStep = 0.25;
  /// A disabled node keeps its place in the hierarchy but is not fitted (treated as skipped).
  bool enabled = true;
  /// Cap on lineEpsilon growth steps for this node; -1 (default) grows until the test points are
  /// the whole slice, as the thesis does. The automatic skeleton's nodes carry 3: such a node knows
  /// where its branch is, and one that fails gets an interpolated radius rather than a circle from
  /// the whole slice (and thousands of failing nodes would otherwise each grow over the cloud).
  int maxGrowthSteps = -1;

  bool operator==(const SamplingParams&) const = default;
};

/// A cross-section that comes with the node instead of being measured: what an automatic method
/// already found there (the skeleton sketch stores its model's circle in every node, so that a
/// rebuild, in the viewer or by `treesketch reconstruct --sketch`, gives the automatic model
/// itself and an edit changes only what it touches). Point nodes only: their plane does not
/// depend on a camera or a parent. The circle lies in the node's plane (the centre is projected
/// onto it when used) with the plane's normal.
struct KeptCircle {
  geom::Vec3 centre = geom::Vec3::Zero();  ///< world
  double radius = 0.0;                     ///< world units, > 0

  bool operator==(const KeptCircle&) const = default;
};

/// A not-wood lasso: a closed screen polygon drawn under one of the sketch's cameras.
/// Every cloud point whose projection under that camera falls inside the polygon (at any depth
/// in front of the camera, as CloudCompare's segmentation tool cuts through the whole view) is
/// not wood: the fits and the automatic skeleton leave it out. Stored as the polygon, not as point
/// indices, so the sketch file stays independent of the cloud's point order and an edit stays
/// small; membership is computed where the cloud is (recon, the correction tools).
/// A lasso with `wood` set says the opposite: its points are wood, whatever a wood/leaf
/// classification called them (and whatever an earlier not-wood lasso said). Where lassos overlap,
/// the one drawn last decides (Sketch::lassoClass).
struct NotWoodLasso {
  int camera = -1;                    ///< index into Sketch::cameras
  std::vector<geom::Vec2> polygon;    ///< pixels, top-left origin; >= 3 vertices, closed implicitly
  bool wood = false;                  ///< a wood lasso (its points are wood), not a not-wood one

  bool operator==(const NotWoodLasso&) const = default;
};

/// Even-odd point-in-polygon test (pixels); a polygon with < 3 vertices contains nothing.
bool polygonContains(const std::vector<geom::Vec2>& polygon, const geom::Vec2& p);

struct Node {
  NodeId id = kNoNode;
  NodeId parent = kNoNode;
  std::vector<NodeId> children;  ///< maintained by Sketch, in insertion order
  /// Index into Sketch::cameras for a screen node; -1 for a point node.
  int camera = -1;
  geom::Vec2 screen = geom::Vec2::Zero();  ///< screen nodes: pixels, top-left origin, y down
  geom::Vec3 point = geom::Vec3::Zero();   ///< point nodes: a point on the branch axis (world)
  geom::Vec3 normal = geom::Vec3::Zero();  ///< point nodes: the slice plane's normal (world)
  SamplingParams params;
  /// When set (and the node enabled), the reconstruction uses this circle and does not fit the
  /// node. Sketch drops it when the node's inputs change (movePointNode, setParams with
  /// different params): it no longer says what those inputs would measure.
  std::optional<KeptCircle> kept;

  bool isScreenNode() const { return camera >= 0; }
};

/// The 3D geometry a node stands for (world frame).
struct NodeGeometry {
  /// Screen nodes: the line L through the node, from the near-plane point (linePoint) along the
  /// unit direction lineDir (the view ray A). Point nodes have no line: hasLine = false and the
  /// test region is the disc of radius lineEpsilon around `planePoint` instead of the cylinder.
  bool hasLine = false;
  geom::Vec3 linePoint = geom::Vec3::Zero();
  geom::Vec3 lineDir = geom::Vec3::Zero();
  /// The slice plane: contains L (screen nodes) or `point` (point nodes); unit normal.
  geom::Vec3 planePoint = geom::Vec3::Zero();
  geom::Vec3 planeNormal = geom::Vec3::UnitY();

  bool operator==(const NodeGeometry&) const = default;
};

class Sketch {
 public:
  /// Sampling sizes given to new nodes.
  SamplingParams defaults;
  /// The world's up axis: the root's plane uses -up in place of A_parent (thesis: (0,-1,0)).
  geom::UpAxis up = geom::UpAxis::Y;

  /// Adds a camera (returns the index of an identical existing one if present). Throws
  /// OptionsError for a degenerate camera.
  int addCamera(const geom::Camera& camera);
  const std::vector<geom::Camera>& cameras() const { return cameras_; }

  /// Adds a screen node under camera `camera` as a child of `parent` (kNoNode: the root; throws
  /// OptionsError if a root exists already or `parent`/`camera` is unknown). Returns its id.
  NodeId addScreenNode(NodeId parent, int camera, const geom::Vec2& screen);
  NodeId addScreenNode(NodeId parent, int camera, const geom::Vec2& screen, const SamplingParams& params);
  /// Adds a point node (3D point + plane normal, world frame). Throws OptionsError for a zero
  /// normal or NaN.
  NodeId addPointNode(NodeId parent, const geom::Vec3& point, const geom::Vec3& normal);
  NodeId addPointNode(NodeId parent, const geom::Vec3& point, const geom::Vec3& normal,
                      const SamplingParams& params);
  /// Removes a node. withSubtree: its descendants go too. Otherwise its children are
  /// re-attached to its parent; removing the root without its subtree makes its first child the
  /// new root and re-attaches the other children to it. Throws OptionsError for an unknown id.
  void removeNode(NodeId id, bool withSubtree);
  /// Moves a screen node on screen (or a point node in 3D).
  void moveNode(NodeId id, const geom::Vec2& screen);
  void movePointNode(NodeId id, const geom::Vec3& point, const geom::Vec3& normal);
  void setParams(NodeId id, const SamplingParams& params);
  /// Sets (or, with nullopt, drops) a point node's kept circle. Throws OptionsError for a screen
  /// node, a non-finite centre or a radius that is not > 0.
  void setKeptCircle(NodeId id, const std::optional<KeptCircle>& circle);
  /// Drops every kept circle ("refit all from the cloud"); returns how many there were.
  std::size_t clearKeptCircles();
  /// Nodes with a kept circle.
  std::size_t keptCircleCount() const;
  /// Re-parents `id` under `newParent` (throws if that would make a cycle).
  void setParent(NodeId id, NodeId newParent);

  /// Not-wood and wood lassos (see NotWoodLasso), in the order drawn. addNotWoodLasso /
  /// addWoodLasso throw OptionsError for an unknown camera, fewer than 3 vertices or a non-finite
  /// vertex; they return the lasso's index.
  std::size_t addNotWoodLasso(int camera, const std::vector<geom::Vec2>& polygon);
  std::size_t addWoodLasso(int camera, const std::vector<geom::Vec2>& polygon);
  /// Removes lasso `index` (OptionsError when out of range) / every lasso of both kinds (returns
  /// how many).
  void removeNotWoodLasso(std::size_t index);
  std::size_t clearNotWood();
  /// Every lasso, not-wood and wood, in the order drawn.
  const std::vector<NotWoodLasso>& notWood() const { return notWood_; }
  /// How many of the lassos are wood lassos.
  std::size_t woodLassoCount() const;
  /// What the lassos say of `p` (world): None when it projects inside no lasso (in front of
  /// the lasso's camera), else the class of the last lasso drawn that holds it.
  enum class LassoClass { None, NotWood, Wood };
  LassoClass lassoClass(const geom::Vec3& p) const;
  /// True when the lassos call `p` not wood (lassoClass(p) == NotWood).
  bool isNotWood(const geom::Vec3& p) const;

  bool contains(NodeId id) const { return nodes_.count(id) != 0; }
  const Node& node(NodeId id) const;  ///< throws OptionsError for an unknown id
  NodeId root() const;                ///< kNoNode when empty
  std::size_t size() const { return nodes_.size(); }
  bool empty() const { return nodes_.empty(); }
  /// All ids in increasing order.
  std::vector<NodeId> ids() const;
  /// Ids in parent-before-child order (depth first from the root).
  std::vector<NodeId> topologicalOrder() const;
  const std::map<NodeId, Node>& nodes() const { return nodes_; }

  /// The node's 3D line and plane (see NodeGeometry), world frame. Screen nodes: L by
  /// unprojecting the screen point at window depth 0 and 1 (linePoint = the near point, lineDir
  /// A = unit far - near; planePoint = linePoint). Normal, first rule that gives one:
  ///  1. N = (A × A_parent) × A (thesis §4.3), A_parent = the parent's own view ray (under its own
  ///     camera, so mixed views work), or -up for the root; used when |A × A_parent| >
  ///     kParallelTolerance. A point-node parent has no ray: go to 2.
  ///  2. (Orthographic camera, or parallel rays from two views.) The screen-space stroke: the
  ///     parent is projected into this node's camera (a same-camera screen parent: its screen
  ///     position; another camera's screen parent: the point of its line closest to this node's
  ///     line, or the middle of its near-far segment when the lines are parallel; a point parent:
  ///     its point); stroke = node.screen - parent.screen in pixels, taken to world along the
  ///     camera's right and up vectors (screen y is down), minus its A component.
  ///  3. Zero stroke (node drawn on its parent): the parent's normal minus its A component.
  ///  4. Root with A parallel to up (top view), or nothing else: the camera's screen-up made
  ///     perpendicular to A.
  /// N is unit and oriented from the parent towards the node (for the root: up), i.e. the way the
  /// branch grows, as point nodes' normals (branch tangents). The plane is the thesis's; only the
  /// sign convention is fixed. Point nodes: their point and normalized normal, hasLine = false.
  /// Throws OptionsError for an unknown id or a singular camera.
  NodeGeometry geometry(NodeId id) const;

  /// Checks the whole structure: one root, parents exist, no cycles, children lists agree,
  /// cameras valid and referenced ones exist, finite values, positive sampling sizes (of the
  /// nodes and of `defaults`, which a sketch file carries too), kept circles on point nodes only
  /// with finite centres and radii > 0, not-wood lassos on existing cameras with >= 3 finite
  /// vertices. Throws OptionsError naming the node (or the defaults, or the lasso).
  void validate() const;

  /// Low-level insertion used by readers (keeps the given id and parent; call validate() after).
  /// node.children is ignored: children lists are rebuilt from parent links (in insertion order,
  /// so insert parents before children to keep an order). Throws OptionsError for a duplicate or
  /// negative id. Later addScreenNode/addPointNode ids continue after the largest id.
  void insertRaw(const Node& node);
  /// Low-level camera insertion used by readers (no de-duplication).
  int insertRawCamera(const geom::Camera& camera);

 private:
  NodeId attachNew(NodeId parent, Node node);
  Node& mutableNode(NodeId id);
  /// A node's line (screen node) or point and normal (point node); no plane normal for screen nodes.
  NodeGeometry lineOf(const Node& node) const;

  std::map<NodeId, Node> nodes_;
  std::vector<geom::Camera> cameras_;
  std::vector<NotWoodLasso> notWood_;
  NodeId nextId_ = 0;
  /// insertRaw: nodes inserted before their parent (an upper bound; 0 skips the adoption scan).
  std::size_t waitingChildren_ = 0;
};

}  // namespace treesketch::sketch
