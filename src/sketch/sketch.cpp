// The sketch node tree and each node's 3D line and plane. Method: Leavenworth 2012, §3.1.2 and
// §4.3 (unproject the node at the near and far clip planes; N = (A × A_parent) × A), extended to
// orthographic cameras and to nodes drawn under different cameras (see Sketch::geometry).
#include "treesketch/sketch/sketch.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "treesketch/util/error.h"

namespace treesketch::sketch {

using geom::Vec2;
using geom::Vec3;

namespace {

std::string nodeName(NodeId id) { return "node " + std::to_string(id); }

bool finite(const SamplingParams& p) {
  return std::isfinite(p.sliceHalfThickness) && std::isfinite(p.lineEpsilon) && std::isfinite(p.lineEpsilonStep);
}

void checkParams(const SamplingParams& p, const std::string& what) {
  if (!finite(p)) throw OptionsError(what + ": sampling sizes must be finite numbers");
  if (!(p.sliceHalfThickness > 0)) throw OptionsError(what + ": sliceHalfThickness must be > 0");
  if (!(p.lineEpsilon > 0)) throw OptionsError(what + ": lineEpsilon must be > 0");
  if (!(p.lineEpsilonStep > 0)) throw OptionsError(what + ": lineEpsilonStep must be > 0");
  if (p.maxGrowthSteps < -1) throw OptionsError(what + ": maxGrowthSteps must be >= -1 (-1: unlimited)");
}

bool sameCamera(const geom::Camera& a, const geom::Camera& b) {
  return a.view == b.view && a.projection == b.projection && a.viewport.x == b.viewport.x &&
         a.viewport.y == b.viewport.y && a.viewport.width == b.viewport.width &&
         a.viewport.height == b.viewport.height;
}

/// Point of line (p1, d1) closest to line (p2, d2); d1, d2 unit. For (near-)parallel lines, p1.
Vec3 closestPointOnFirstLine(const Vec3& p1, const Vec3& d1, const Vec3& p2, const Vec3& d2) {
  double b = d1.dot(d2);
  double denom = 1.0 - b * b;
  if (denom < 1e-12) return p1;
  Vec3 r = p1 - p2;
  double s = (b * d2.dot(r) - d1.dot(r)) / denom;
  return p1 + s * d1;
}

/// `v` without its component along unit `a`, normalized; zero when that is (nearly) nothing.
Vec3 perpendicularPart(const Vec3& v, const Vec3& a) {
  Vec3 p = v - a * a.dot(v);
  double n = p.norm();
  if (!(n > kParallelTolerance * std::max(v.norm(), 1e-300))) return Vec3::Zero();
  return p / n;
}

void checkKeptCircle(const Node& n, const KeptCircle& c, const std::string& what) {
  if (n.isScreenNode()) throw OptionsError(what + ": a kept circle needs a point node (this is a screen node)");
  if (!c.centre.allFinite()) throw OptionsError(what + ": kept circle centre is not finite");
  if (!(c.radius > 0) || !std::isfinite(c.radius))
    throw OptionsError(what + ": kept circle radius must be > 0 and finite");
}

}  // namespace

int Sketch::addCamera(const geom::Camera& camera) {
  camera.validate("camera");
  for (std::size_t i = 0; i < cameras_.size(); ++i)
    if (sameCamera(cameras_[i], camera)) return static_cast<int>(i);
  cameras_.push_back(camera);
  return static_cast<int>(cameras_.size()) - 1;
}

int Sketch::insertRawCamera(const geom::Camera& camera) {
  cameras_.push_back(camera);
  return static_cast<int>(cameras_.size()) - 1;
}

NodeId Sketch::addScreenNode(NodeId parent, int camera, const Vec2& screen) {
  return addScreenNode(parent, camera, screen, defaults);
}

NodeId Sketch::addScreenNode(NodeId parent, int camera, const Vec2& screen, const SamplingParams& params) {
  std::string what = "new node";
  if (camera < 0 || camera >= static_cast<int>(cameras_.size()))
    throw OptionsError(what + ": camera " + std::to_string(camera) + " does not exist");
  if (!screen.allFinite()) throw OptionsError(what + ": screen position is not finite");
  checkParams(params, what);
  Node n;
  n.camera = camera;
  n.screen = screen;
  n.params = params;
  return attachNew(parent, n);
}

NodeId Sketch::addPointNode(NodeId parent, const Vec3& point, const Vec3& normal) {
  return addPointNode(parent, point, normal, defaults);
}

NodeId Sketch::addPointNode(NodeId parent, const Vec3& point, const Vec3& normal, const SamplingParams& params) {
  std::string what = "new node";
  if (!point.allFinite() || !normal.allFinite()) throw OptionsError(what + ": point or normal is not finite");
  if (!(normal.norm() > 0)) throw OptionsError(what + ": normal is zero");
  checkParams(params, what);
  Node n;
  n.camera = -1;
  n.point = point;
  n.normal = normal;
  n.params = params;
  return attachNew(parent, n);
}

NodeId Sketch::attachNew(NodeId parent, Node n) {
  if (parent == kNoNode) {
    if (!nodes_.empty()) throw OptionsError("new node: the sketch has a root already (node " + std::to_string(root()) + ")");
  } else if (!contains(parent)) {
    throw OptionsError("new node: parent " + std::to_string(parent) + " does not exist");
  }
  n.id = nextId_++;
  n.parent = parent;
  n.children.clear();
  if (parent != kNoNode) nodes_.at(parent).children.push_back(n.id);
  nodes_.emplace(n.id, std::move(n));
  return nextId_ - 1;
}

void Sketch::insertRaw(const Node& node) {
  if (contains(node.id)) throw OptionsError(nodeName(node.id) + ": duplicate node id");
  if (node.id < 0) throw OptionsError(nodeName(node.id) + ": node ids must be >= 0");
  Node n = node;
  n.children.clear();
  // Children inserted before their parent are collected here (in id order); later ones append.
  // The scan only runs while such waiting children may exist (readers insert parents first).
  if (waitingChildren_ > 0) {
    for (const auto& [id, other] : nodes_)
      if (other.parent == n.id) n.children.push_back(id);
    waitingChildren_ -= std::min(waitingChildren_, n.children.size());
  }
  if (n.parent != kNoNode) {
    auto it = nodes_.find(n.parent);
    if (it != nodes_.end()) it->second.children.push_back(n.id);
    else ++waitingChildren_;
  }
  nextId_ = std::max(nextId_, n.id + 1);
  nodes_.emplace(n.id, std::move(n));
}

Node& Sketch::mutableNode(NodeId id) {
  auto it = nodes_.find(id);
  if (it == nodes_.end()) throw OptionsError(nodeName(id) + ": no such node");
  return it->second;
}

const Node& Sketch::node(NodeId id) const {
  auto it = nodes_.find(id);
  if (it == nodes_.end()) throw OptionsError(nodeName(id) + ": no such node");
  return it->second;
}

NodeId Sketch::root() const {
  for (const auto& [id, n] : nodes_)
    if (n.parent == kNoNode) return id;
  return kNoNode;
}

std::vector<NodeId> Sketch::ids() const {
  std::vector<NodeId> out;
  out.reserve(nodes_.size());
  for (const auto& [id, n] : nodes_) out.push_back(id);
  return out;
}

std::vector<NodeId> Sketch::topologicalOrder() const {
  std::vector<NodeId> out;
  NodeId r = root();
  if (r == kNoNode) return out;
  out.reserve(nodes_.size());
  std::vector<NodeId> stack{r};
  while (!stack.empty() && out.size() <= nodes_.size()) {
    NodeId id = stack.back();
    stack.pop_back();
    auto it = nodes_.find(id);
    if (it == nodes_.end()) continue;
    out.push_back(id);
    const auto& ch = it->second.children;
    for (auto c = ch.rbegin(); c != ch.rend(); ++c) stack.push_back(*c);
  }
  return out;
}

void Sketch::removeNode(NodeId id, bool withSubtree) {
  Node victim = node(id);  // copy: the map entry goes away below
  if (withSubtree) {
    std::vector<NodeId> stack{id};
    std::vector<NodeId> doomed;
    while (!stack.empty()) {
      NodeId cur = stack.back();
      stack.pop_back();
      doomed.push_back(cur);
      for (NodeId c : nodes_.at(cur).children) stack.push_back(c);
    }
    if (victim.parent != kNoNode) {
      auto& siblings = nodes_.at(victim.parent).children;
      siblings.erase(std::remove(siblings.begin(), siblings.end(), id), siblings.end());
    }
    for (NodeId d : doomed) nodes_.erase(d);
    return;
  }
  if (victim.parent != kNoNode) {
    // Children take the removed node's place in its parent's child list, in their order.
    auto& siblings = nodes_.at(victim.parent).children;
    auto pos = std::find(siblings.begin(), siblings.end(), id);
    pos = siblings.erase(pos);
    siblings.insert(pos, victim.children.begin(), victim.children.end());
    for (NodeId c : victim.children) nodes_.at(c).parent = victim.parent;
  } else if (!victim.children.empty()) {
    // Root: its first child becomes the root and adopts the other children.
    NodeId newRoot = victim.children.front();
    Node& nr = nodes_.at(newRoot);
    nr.parent = kNoNode;
    for (std::size_t i = 1; i < victim.children.size(); ++i) {
      nr.children.push_back(victim.children[i]);
      nodes_.at(victim.children[i]).parent = newRoot;
    }
  }
  nodes_.erase(id);
}

void Sketch::moveNode(NodeId id, const Vec2& screen) {
  Node& n = mutableNode(id);
  if (!n.isScreenNode()) throw OptionsError(nodeName(id) + ": is a point node, not a screen node");
  if (!screen.allFinite()) throw OptionsError(nodeName(id) + ": screen position is not finite");
  n.screen = screen;
}

void Sketch::movePointNode(NodeId id, const Vec3& point, const Vec3& normal) {
  Node& n = mutableNode(id);
  if (n.isScreenNode()) throw OptionsError(nodeName(id) + ": is a screen node, not a point node");
  if (!point.allFinite() || !normal.allFinite()) throw OptionsError(nodeName(id) + ": point or normal is not finite");
  if (!(normal.norm() > 0)) throw OptionsError(nodeName(id) + ": normal is zero");
  if (n.point != point || n.normal != normal) n.kept.reset();
  n.point = point;
  n.normal = normal;
}

void Sketch::setParams(NodeId id, const SamplingParams& params) {
  Node& n = mutableNode(id);
  checkParams(params, nodeName(id));
  if (!(n.params == params)) n.kept.reset();
  n.params = params;
}

void Sketch::setKeptCircle(NodeId id, const std::optional<KeptCircle>& circle) {
  Node& n = mutableNode(id);
  if (circle) checkKeptCircle(n, *circle, nodeName(id));
  n.kept = circle;
}

std::size_t Sketch::clearKeptCircles() {
  std::size_t cleared = 0;
  for (auto& [id, n] : nodes_) {
    cleared += n.kept.has_value();
    n.kept.reset();
  }
  return cleared;
}

std::size_t Sketch::keptCircleCount() const {
  std::size_t count = 0;
  for (const auto& [id, n] : nodes_) count += n.kept.has_value();
  return count;
}

void Sketch::setParent(NodeId id, NodeId newParent) {
  Node& n = mutableNode(id);
  if (newParent == n.parent) return;
  if (newParent == kNoNode) {
    throw OptionsError(nodeName(id) + ": cannot become a root: the sketch has a root already (node " +
                       std::to_string(root()) + ")");
  }
  if (!contains(newParent)) throw OptionsError(nodeName(id) + ": new parent " + std::to_string(newParent) + " does not exist");
  // A cycle arises exactly when the new parent is `id` or one of its descendants.
  std::size_t steps = 0;
  for (NodeId a = newParent; a != kNoNode && steps <= nodes_.size(); a = nodes_.at(a).parent, ++steps) {
    if (a == id)
      throw OptionsError(nodeName(id) + ": cannot move under node " + std::to_string(newParent) +
                         ": that node is in its own subtree (cycle)");
  }
  if (n.parent != kNoNode) {
    auto& siblings = nodes_.at(n.parent).children;
    siblings.erase(std::remove(siblings.begin(), siblings.end(), id), siblings.end());
  }
  n.parent = newParent;
  nodes_.at(newParent).children.push_back(id);
}

NodeGeometry Sketch::lineOf(const Node& n) const {
  NodeGeometry g;
  if (!n.isScreenNode()) {
    g.linePoint = g.planePoint = n.point;
    g.planeNormal = n.normal.normalized();
    return g;
  }
  if (n.camera >= static_cast<int>(cameras_.size()))
    throw OptionsError(nodeName(n.id) + ": camera " + std::to_string(n.camera) + " does not exist");
  const geom::Camera& cam = cameras_[n.camera];
  Vec3 nearP = cam.unproject(n.screen, 0.0);
  Vec3 farP = cam.unproject(n.screen, 1.0);
  g.hasLine = true;
  g.linePoint = g.planePoint = nearP;
  g.lineDir = (farP - nearP).normalized();
  if (!g.lineDir.allFinite()) throw OptionsError(nodeName(n.id) + ": cannot unproject (degenerate camera)");
  return g;
}

NodeGeometry Sketch::geometry(NodeId id) const {
  const Node& n = node(id);
  NodeGeometry g = lineOf(n);
  if (!n.isScreenNode()) return g;
  const geom::Camera& cam = cameras_[n.camera];
  const Vec3 nearP = g.linePoint;
  const Vec3 a = g.lineDir;

  // 1. Thesis rule, N = (A × A_parent) × A, oriented from the parent towards this node (root: up).
  // Only the parent's line is needed here (no recursion up the tree); its normal only in rule 3.
  Vec3 up = geom::upVector(this->up);
  Vec3 aParent = -up;
  const Node* parent = n.parent == kNoNode ? nullptr : &node(n.parent);
  NodeGeometry pg;
  if (parent) {
    pg = lineOf(*parent);
    aParent = pg.hasLine ? pg.lineDir : Vec3::Zero();  // a point parent has no view ray
  }
  Vec3 normal = Vec3::Zero();
  if (a.cross(aParent).norm() > kParallelTolerance) normal = -a.cross(aParent).cross(a).normalized();

  // 2. Rays (nearly) parallel: the screen-space stroke from the parent, in the view plane.
  if (normal.isZero() && parent) {
    Vec2 parentScreen;
    if (parent->isScreenNode() && parent->camera == n.camera) {
      parentScreen = parent->screen;
    } else {
      Vec3 anchor = pg.hasLine ? closestPointOnFirstLine(pg.linePoint, pg.lineDir, nearP, a) : pg.planePoint;
      if (pg.hasLine && anchor == pg.linePoint && parent->isScreenNode()) {
        // Parallel lines: any point of the parent's line will do; take the middle of its near-far segment.
        const geom::Camera& pc = cameras_[parent->camera];
        anchor = 0.5 * (pc.unproject(parent->screen, 0.0) + pc.unproject(parent->screen, 1.0));
      }
      parentScreen = cam.project(anchor).head<2>();
    }
    Vec2 stroke = n.screen - parentScreen;  // pixels, y down
    Vec3 world = stroke.x() * cam.right() - stroke.y() * cam.up();
    if (world.allFinite()) normal = perpendicularPart(world, a);
    // 3. Zero stroke (node drawn on top of its parent): keep the parent's orientation.
    // Skip ancestors stacked on the same pixel, so a long stack does not recurse deeply.
    if (normal.isZero()) {
      NodeId anc = n.parent;
      for (std::size_t guard = 0; guard < nodes_.size(); ++guard) {
        const Node& an = node(anc);
        if (an.parent == kNoNode || !an.isScreenNode()) break;
        const Node& ap = node(an.parent);
        if (!(ap.isScreenNode() && ap.camera == an.camera && ap.screen == an.screen)) break;
        anc = an.parent;
      }
      normal = perpendicularPart(geometry(anc).planeNormal, a);
    }
  }
  // 4. Root under a top view (or nothing else worked): the camera's screen-up.
  if (normal.isZero()) normal = perpendicularPart(cam.up(), a);
  if (normal.isZero()) normal = geom::anyPerpendicular(a);
  g.planeNormal = normal;
  return g;
}

bool polygonContains(const std::vector<Vec2>& poly, const Vec2& p) {
  if (poly.size() < 3) return false;
  bool inside = false;
  for (std::size_t i = 0, j = poly.size() - 1; i < poly.size(); j = i++) {
    const Vec2& a = poly[i];
    const Vec2& b = poly[j];
    if ((a.y() > p.y()) != (b.y() > p.y()) && p.x() < (b.x() - a.x()) * (p.y() - a.y()) / (b.y() - a.y()) + a.x())
      inside = !inside;
  }
  return inside;
}

namespace {

void checkLasso(const NotWoodLasso& l, std::size_t cameras, const std::string& what) {
  if (l.camera < 0 || l.camera >= static_cast<int>(cameras))
    throw OptionsError(what + ": camera " + std::to_string(l.camera) + " does not exist (the sketch has " +
                       std::to_string(cameras) + ")");
  if (l.polygon.size() < 3)
    throw OptionsError(what + ": a lasso needs at least 3 vertices, got " + std::to_string(l.polygon.size()));
  for (const Vec2& v : l.polygon)
    if (!v.allFinite()) throw OptionsError(what + ": a vertex is not finite");
}

}  // namespace

std::size_t Sketch::addNotWoodLasso(int camera, const std::vector<Vec2>& polygon) {
  NotWoodLasso l{camera, polygon, false};
  checkLasso(l, cameras_.size(), "not-wood lasso");
  notWood_.push_back(std::move(l));
  return notWood_.size() - 1;
}

std::size_t Sketch::addWoodLasso(int camera, const std::vector<Vec2>& polygon) {
  NotWoodLasso l{camera, polygon, true};
  checkLasso(l, cameras_.size(), "wood lasso");
  notWood_.push_back(std::move(l));
  return notWood_.size() - 1;
}

std::size_t Sketch::woodLassoCount() const {
  std::size_t n = 0;
  for (const NotWoodLasso& l : notWood_) n += l.wood;
  return n;
}

void Sketch::removeNotWoodLasso(std::size_t index) {
  if (index >= notWood_.size())
    throw OptionsError("not-wood lasso " + std::to_string(index) + " does not exist (the sketch has " +
                       std::to_string(notWood_.size()) + ")");
  notWood_.erase(notWood_.begin() + static_cast<std::ptrdiff_t>(index));
}

std::size_t Sketch::clearNotWood() {
  std::size_t n = notWood_.size();
  notWood_.clear();
  return n;
}

Sketch::LassoClass Sketch::lassoClass(const Vec3& p) const {
  for (auto it = notWood_.rbegin(); it != notWood_.rend(); ++it) {  // the last lasso drawn decides
    const Vec3 s = cameras_[it->camera].project(p);
    if (!s.allFinite() || s.z() < 0.0 || s.z() > 1.0) continue;  // behind the camera or beyond its range
    if (polygonContains(it->polygon, s.head<2>())) return it->wood ? LassoClass::Wood : LassoClass::NotWood;
  }
  return LassoClass::None;
}

bool Sketch::isNotWood(const Vec3& p) const { return lassoClass(p) == LassoClass::NotWood; }

void Sketch::validate() const {
  checkParams(defaults, "sketch defaults");
  for (std::size_t i = 0; i < cameras_.size(); ++i) cameras_[i].validate("camera " + std::to_string(i));
  for (std::size_t i = 0; i < notWood_.size(); ++i)
    checkLasso(notWood_[i], cameras_.size(),
               (notWood_[i].wood ? "wood lasso " : "not-wood lasso ") + std::to_string(i));
  if (nodes_.empty()) return;
  NodeId theRoot = kNoNode;
  for (const auto& [id, n] : nodes_) {
    std::string what = nodeName(id);
    if (n.id != id) throw OptionsError(what + ": stored under a different id (" + std::to_string(n.id) + ")");
    if (n.parent == kNoNode) {
      if (theRoot != kNoNode)
        throw OptionsError(what + ": a second root (node " + std::to_string(theRoot) + " is the root already)");
      theRoot = id;
    } else if (!contains(n.parent)) {
      throw OptionsError(what + ": parent " + std::to_string(n.parent) + " does not exist");
    } else if (n.parent == id) {
      throw OptionsError(what + ": is its own parent (cycle)");
    }
    if (n.camera < -1 || n.camera >= static_cast<int>(cameras_.size()))
      throw OptionsError(what + ": camera " + std::to_string(n.camera) + " does not exist (the sketch has " +
                         std::to_string(cameras_.size()) + ")");
    if (n.isScreenNode()) {
      if (!n.screen.allFinite()) throw OptionsError(what + ": screen position is not finite");
    } else {
      if (!n.point.allFinite()) throw OptionsError(what + ": point is not finite");
      if (!n.normal.allFinite()) throw OptionsError(what + ": normal is not finite");
      if (!(n.normal.norm() > 0)) throw OptionsError(what + ": normal is zero");
    }
    checkParams(n.params, what);
    if (n.kept) checkKeptCircle(n, *n.kept, what);
    // Children lists agree with parent links, both ways.
    for (std::size_t k = 0; k < n.children.size(); ++k) {
      NodeId c = n.children[k];
      auto it = nodes_.find(c);
      if (it == nodes_.end()) throw OptionsError(what + ": child " + std::to_string(c) + " does not exist");
      if (it->second.parent != id)
        throw OptionsError(what + ": lists child " + std::to_string(c) + " whose parent is " +
                           std::to_string(it->second.parent));
      if (std::find(n.children.begin(), n.children.begin() + k, c) != n.children.begin() + k)
        throw OptionsError(what + ": lists child " + std::to_string(c) + " twice");
    }
    if (n.parent != kNoNode && n.parent != id) {
      const auto& sib = nodes_.at(n.parent).children;
      if (std::find(sib.begin(), sib.end(), id) == sib.end())
        throw OptionsError(what + ": missing from the child list of its parent " + std::to_string(n.parent));
    }
  }
  if (theRoot == kNoNode) throw OptionsError("sketch: no root (every node has a parent: a cycle)");
  // No cycles: with the child lists checked above, each node sits in exactly one child list, so
  // a walk down from the root visits a tree; a node it misses is on (or under) a parent cycle.
  std::vector<NodeId> reached = topologicalOrder();
  if (reached.size() != nodes_.size()) {
    std::vector<NodeId> sorted = reached;
    std::sort(sorted.begin(), sorted.end());
    for (const auto& [id, n] : nodes_)
      if (!std::binary_search(sorted.begin(), sorted.end(), id))
        throw OptionsError(nodeName(id) + ": its parents form a cycle (it never reaches the root)");
  }
}

}  // namespace treesketch::sketch
