// The correction tools (see correction_tools.h).
#include "treesketch/edit/correction_tools.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>

#include "treesketch/util/error.h"

namespace treesketch::edit {

using geom::Vec2;
using geom::Vec3;

std::map<NodeId, NodeAnchor> nodeAnchors(const sketch::Sketch& sketch, const recon::Reconstruction* recon) {
  std::map<NodeId, NodeAnchor> out;
  for (const auto& [id, node] : sketch.nodes()) {
    const fit::NodeResult* r = recon ? recon->result(id) : nullptr;
    if (r && r->status == fit::NodeStatus::Fitted) {
      out[id] = NodeAnchor{r->centre, r->radius};
    } else if (node.kept) {
      out[id] = NodeAnchor{node.kept->centre, node.kept->radius};
    } else if (!node.isScreenNode()) {
      out[id] = NodeAnchor{node.point, 0.0};
    }
  }
  return out;
}

// ---- view picker ---------------------------------------------------------------------------------

ViewPicker::ViewPicker(const geom::PointCloud& cloud, const geom::Camera& camera, double cellPx,
                       const std::function<bool(std::size_t, const Vec3&)>& skip)
    : camera_(camera), cell_(std::max(cellPx, 1.0)) {
  camera_.validate("view picker camera");
  const geom::Viewport& vp = camera_.viewport;
  cols_ = std::max(1, int(std::ceil(vp.width / cell_)));
  rows_ = std::max(1, int(std::ceil(vp.height / cell_)));
  const geom::Mat4 m = camera_.projection * camera_.view;
  const Vec3 eye = camera_.eye(), fwd = camera_.forward();
  const bool ortho = camera_.isOrthographic();
  const std::size_t n = cloud.size();
  screen_.assign(n, Vec2::Constant(std::numeric_limits<double>::quiet_NaN()));
  depth_.assign(n, 0.0);
  std::vector<std::uint32_t> cellOf(n, std::uint32_t(-1));
  start_.assign(std::size_t(cols_) * rows_ + 1, 0);
  for (std::size_t i = 0; i < n; ++i) {
    const Vec3& p = cloud.positions[i];
    if (!p.allFinite() || (skip && skip(i, p))) continue;
    Eigen::Vector4d c = m * Eigen::Vector4d(p.x(), p.y(), p.z(), 1.0);
    if (!(c.w() > 0) && !ortho) continue;  // behind the eye
    const double x = c.x() / c.w(), y = c.y() / c.w(), z = c.z() / c.w();
    if (z < -1.0 || z > 1.0) continue;
    const Vec2 s(vp.x + (x + 1.0) * 0.5 * vp.width, vp.y + (1.0 - y) * 0.5 * vp.height);
    const int cx = int(std::floor((s.x() - vp.x) / cell_)), cy = int(std::floor((s.y() - vp.y) / cell_));
    if (cx < 0 || cy < 0 || cx >= cols_ || cy >= rows_) continue;
    screen_[i] = s;
    depth_[i] = ortho ? (p - eye).dot(fwd) : (p - eye).norm();
    cellOf[i] = std::uint32_t(std::size_t(cy) * cols_ + cx);
    ++start_[cellOf[i] + 1];
  }
  for (std::size_t c = 1; c < start_.size(); ++c) start_[c] += start_[c - 1];
  ids_.resize(start_.back());
  std::vector<std::uint32_t> fill(start_.begin(), start_.end() - 1);
  for (std::size_t i = 0; i < n; ++i)
    if (cellOf[i] != std::uint32_t(-1)) ids_[fill[cellOf[i]]++] = std::uint32_t(i);
}

std::vector<ViewPicker::Candidate> ViewPicker::near(const Vec2& screen, double radiusPx) const {
  std::vector<Candidate> out;
  const geom::Viewport& vp = camera_.viewport;
  const int x0 = std::max(0, int(std::floor((screen.x() - radiusPx - vp.x) / cell_)));
  const int x1 = std::min(cols_ - 1, int(std::floor((screen.x() + radiusPx - vp.x) / cell_)));
  const int y0 = std::max(0, int(std::floor((screen.y() - radiusPx - vp.y) / cell_)));
  const int y1 = std::min(rows_ - 1, int(std::floor((screen.y() + radiusPx - vp.y) / cell_)));
  const double r2 = radiusPx * radiusPx;
  for (int cy = y0; cy <= y1; ++cy)
    for (int cx = x0; cx <= x1; ++cx) {
      const std::size_t c = std::size_t(cy) * cols_ + cx;
      for (std::uint32_t k = start_[c]; k < start_[c + 1]; ++k) {
        const std::uint32_t i = ids_[k];
        if ((screen_[i] - screen).squaredNorm() <= r2) out.push_back({i, depth_[i]});
      }
    }
  std::sort(out.begin(), out.end(), [](const Candidate& a, const Candidate& b) { return a.depth < b.depth; });
  return out;
}

void ViewPicker::ray(const Vec2& screen, Vec3* origin, Vec3* dir) const {
  const Vec3 a = camera_.unproject(screen, 0.0), b = camera_.unproject(screen, 1.0);
  *origin = a;
  *dir = (b - a).normalized();
}

double ViewPicker::depthOf(const Vec3& p) const {
  return camera_.isOrthographic() ? (p - camera_.eye()).dot(camera_.forward()) : (p - camera_.eye()).norm();
}

namespace {

/// The point at `depth` (ViewPicker's measure) on the ray through `screen`.
Vec3 pointAtDepth(const ViewPicker& picker, const Vec2& screen, double depth) {
  Vec3 o, d;
  picker.ray(screen, &o, &d);
  const geom::Camera& cam = picker.camera();
  if (cam.isOrthographic()) return o + (depth - (o - cam.eye()).dot(cam.forward())) * d;
  return cam.eye() + depth * d;
}

struct Surface {
  double depth;  ///< median depth of its candidates
  int count;
};

/// Splits depth-sorted candidates into surfaces at gaps wider than `gap`.
std::vector<Surface> surfaces(const std::vector<ViewPicker::Candidate>& c, double gap, int minPoints) {
  std::vector<Surface> out;
  std::size_t b = 0;
  for (std::size_t i = 1; i <= c.size(); ++i) {
    if (i < c.size() && c[i].depth - c[i - 1].depth <= gap) continue;
    const int count = int(i - b);
    if (count >= minPoints) out.push_back({c[b + (i - b) / 2].depth, count});
    b = i;
  }
  return out;
}

std::vector<Vec2> resample(const std::vector<Vec2>& line, double step) {
  std::vector<Vec2> out{line.front()};
  double carry = 0.0;
  for (std::size_t i = 1; i < line.size(); ++i) {
    const Vec2 a = line[i - 1], b = line[i];
    const double len = (b - a).norm();
    double t = step - carry;
    while (t <= len) {
      out.push_back(a + (b - a) * (t / len));
      t += step;
    }
    carry = len - (t - step);
  }
  if ((out.back() - line.back()).norm() > 1e-9) out.push_back(line.back());
  return out;
}

double pathLength(const std::vector<Vec3>& p) {
  double l = 0;
  for (std::size_t i = 1; i < p.size(); ++i) l += (p[i] - p[i - 1]).norm();
  return l;
}

/// Point at arc length `s` of a polyline (clamped to its ends).
Vec3 pointAt(const std::vector<Vec3>& p, double s) {
  double acc = 0;
  for (std::size_t i = 1; i < p.size(); ++i) {
    const double len = (p[i] - p[i - 1]).norm();
    if (acc + len >= s) {
      const double t = len > 0 ? std::clamp((s - acc) / len, 0.0, 1.0) : 0.0;
      return p[i - 1] + t * (p[i] - p[i - 1]);
    }
    acc += len;
  }
  return p.back();
}

/// Point and unit tangent at arc length `s`; the tangent is the chord over ±h of arc length
/// (a segment alone carries the depth noise of the picked surfaces).
void atArcLength(const std::vector<Vec3>& p, double s, double h, Vec3* point, Vec3* tangent) {
  *point = pointAt(p, s);
  Vec3 d = pointAt(p, s + h) - pointAt(p, std::max(0.0, s - h));
  if (!(d.norm() > 0)) d = p.back() - p.front();
  *tangent = d.normalized();
}

}  // namespace

namespace {

// Attach: the node whose anchor projects nearest to the stroke's start (what the person started
// the stroke on); sets res.attachedTo and returns its distance in pixels (infinity: none).
double nearestAnchor(const geom::Camera& cam, const Vec2& start, const std::map<NodeId, NodeAnchor>& anchors,
                     StrokeResult& res) {
  double bestPx = std::numeric_limits<double>::infinity();
  for (const auto& [id, a] : anchors) {
    const Vec3 s = cam.project(a.centre);
    if (!s.allFinite() || s.z() < 0 || s.z() > 1) continue;
    const double d = (s.head<2>() - start).norm();
    if (d < bestPx) {
      bestPx = d;
      res.attachedTo = id;
    }
  }
  return bestPx;
}

// Depth along the stroke: among each sample's surfaces, the one nearest the expected depth (the
// previous sample's, starting from the attach node); without one, the front-most surface (what
// the person sees). Returns the picked points; counts the samples without points, the depth jumps
// and the picks behind the front surface in res.
std::vector<Vec3> followStroke(const ViewPicker& picker, const std::vector<Vec2>& samples, double gap, double expected,
                               double localRadius, const StrokeOptions& o, StrokeResult& res) {
  std::vector<Vec3> path;
  for (const Vec2& s : samples) {
    std::vector<Surface> surf = surfaces(picker.near(s, o.pickRadiusPx), gap, o.minSurfacePoints);
    if (surf.empty()) {
      ++res.samplesWithoutPoints;
      continue;
    }
    std::size_t pick = 0;
    if (std::isfinite(expected)) {
      for (std::size_t k = 1; k < surf.size(); ++k)
        if (std::abs(surf[k].depth - expected) < std::abs(surf[pick].depth - expected)) pick = k;
      // Stroke samples are 2 px apart: the limb's depth moves little between them.
      if (std::abs(surf[pick].depth - expected) > 2.0 * gap + 2.0 * localRadius) ++res.depthJumps;
    }
    if (pick != 0) ++res.behindFront;
    expected = surf[pick].depth;
    path.push_back(pointAtDepth(picker, s, expected));
  }
  return path;
}

// Nodes at the midpoints of equal pieces of `smooth`, as the simulated careful user places them,
// chained under res.attachedTo.
void placeStrokeNodes(sketch::Sketch& sketch, const geom::Camera& cam, const std::vector<Vec3>& smooth,
                      double localRadius, const StrokeOptions& o, StrokeResult& res) {
  const sketch::SamplingParams& defaults = sketch.defaults;
  if (!(localRadius > 0)) localRadius = 0.25 * defaults.lineEpsilon;
  const double spacing =
      std::clamp(o.spacingRadii * localRadius, 2.5 * defaults.sliceHalfThickness, defaults.lineEpsilon);
  const double length = pathLength(smooth);
  const int n = std::max(1, int(std::lround(length / spacing)));
  sketch::SamplingParams params = defaults;
  params.lineEpsilon = std::min(defaults.lineEpsilon, std::max(4.0 * localRadius, 2.0 * defaults.sliceHalfThickness));
  params.maxGrowthSteps = 3;
  NodeId parent = res.attachedTo;
  for (int k = 0; k < n; ++k) {
    Vec3 p, t;
    atArcLength(smooth, (k + 0.5) * length / n, 0.5 * length / n, &p, &t);
    if (!(t.norm() > 0) || !t.allFinite()) t = -cam.forward().cross(cam.right());
    parent = sketch.addPointNode(parent, p, t, params);
    res.added.push_back(parent);
  }
}

}  // namespace

StrokeResult drawLimb(sketch::Sketch& sketch, const ViewPicker& picker, const geom::PointCloud& cloud,
                      const std::vector<Vec2>& stroke, const std::map<NodeId, NodeAnchor>& anchors,
                      const StrokeOptions& o) {
  (void)cloud;
  if (stroke.size() < 2) throw OptionsError("stroke: draw at least two points");
  for (const Vec2& p : stroke)
    if (!p.allFinite()) throw OptionsError("stroke: a point is not finite");
  StrokeResult res;
  const geom::Camera& cam = picker.camera();
  const sketch::SamplingParams& defaults = sketch.defaults;
  const double gap = o.depthGapFraction * defaults.lineEpsilon;

  double expected = std::numeric_limits<double>::quiet_NaN();
  double localRadius = 0.0;
  const double bestPx = nearestAnchor(cam, stroke.front(), anchors, res);
  if (res.attachedTo != kNoNode) {
    expected = picker.depthOf(anchors.at(res.attachedTo).centre);
    localRadius = anchors.at(res.attachedTo).radius;
    if (bestPx > o.attachWarnPx)
      res.warning = "the stroke starts " + std::to_string(int(bestPx)) + " px from the nearest node (" +
                    std::to_string(res.attachedTo) + "), attached there";
  } else if (!sketch.empty()) {
    res.attachedTo = sketch.root();  // no node has a known place yet: the root, as a click does
  }

  std::vector<Vec3> path = followStroke(picker, resample(stroke, o.sampleStepPx), gap, expected, localRadius, o, res);
  // The stroke starts on the parent's tube: the samples over it picked the parent's surface, not
  // the limb's. Drop the leading samples within 1.5 parent radii of the parent's axis.
  if (res.attachedTo != kNoNode && anchors.count(res.attachedTo) && localRadius > 0) {
    const Vec3 c = anchors.at(res.attachedTo).centre;
    Vec3 axis = sketch.geometry(res.attachedTo).planeNormal.normalized();
    std::size_t k = 0;
    while (k + 2 < path.size()) {
      const Vec3 d = path[k] - c;
      if ((d - d.dot(axis) * axis).norm() > 1.5 * localRadius) break;
      ++k;
    }
    path.erase(path.begin(), path.begin() + static_cast<std::ptrdiff_t>(k));
  }
  if (path.size() < 2) throw OptionsError("stroke: no cloud points along it (nothing to follow)");
  // Smooth the depth noise of the picked path (a moving average over 5 samples, ends kept).
  std::vector<Vec3> smooth = path;
  for (std::size_t i = 2; i + 2 < path.size(); ++i)
    smooth[i] = (path[i - 2] + path[i - 1] + path[i] + path[i + 1] + path[i + 2]) / 5.0;
  res.path = smooth;

  placeStrokeNodes(sketch, cam, smooth, localRadius, o, res);
  if (res.depthJumps > 0) {
    res.warning += std::string(res.warning.empty() ? "" : "; ") + "the depth jumped at " +
                   std::to_string(res.depthJumps) + " stroke samples (check the new limb from the side)";
  }
  return res;
}

std::size_t lassoNotWood(sketch::Sketch& sketch, const geom::PointCloud& cloud, const geom::Camera& camera,
                         const std::vector<Vec2>& polygon) {
  const int cam = sketch.addCamera(camera);
  sketch::Sketch one;  // count what this lasso alone marks
  one.addNotWoodLasso(one.addCamera(camera), polygon);
  sketch.addNotWoodLasso(cam, polygon);
  std::size_t n = 0;
  for (const Vec3& p : cloud.positions) n += one.isNotWood(p);
  return n;
}

std::size_t lassoWood(sketch::Sketch& sketch, const geom::PointCloud& cloud, const geom::Camera& camera,
                      const std::vector<Vec2>& polygon) {
  const int cam = sketch.addCamera(camera);
  sketch::Sketch one;  // count what this lasso alone marks
  one.addWoodLasso(one.addCamera(camera), polygon);
  sketch.addWoodLasso(cam, polygon);
  std::size_t n = 0;
  for (const Vec3& p : cloud.positions) n += one.lassoClass(p) == sketch::Sketch::LassoClass::Wood;
  return n;
}

void copyNotWood(const sketch::Sketch& from, sketch::Sketch& to) {
  for (const sketch::NotWoodLasso& l : from.notWood()) {
    const sketch::NotWoodLasso* same = nullptr;
    for (const sketch::NotWoodLasso& m : to.notWood())
      if (m.polygon == l.polygon && m.wood == l.wood && to.cameras()[m.camera].view == from.cameras()[l.camera].view)
        same = &m;
    if (same) continue;
    const int cam = to.addCamera(from.cameras()[l.camera]);
    if (l.wood)
      to.addWoodLasso(cam, l.polygon);
    else
      to.addNotWoodLasso(cam, l.polygon);
  }
}

std::size_t refitNotWoodCircles(sketch::Sketch& sketch) {
  if (sketch.notWood().empty()) return 0;
  std::vector<NodeId> inside;
  for (const auto& [id, node] : sketch.nodes())
    if (node.kept && sketch.isNotWood(node.kept->centre)) inside.push_back(id);
  for (NodeId id : inside) sketch.setKeptCircle(id, std::nullopt);
  return inside.size();
}

geom::PointCloud woodOnly(const geom::PointCloud& cloud, const sketch::Sketch& sketch) {
  return woodOnly(cloud, sketch, {});
}

bool isWoodPoint(const sketch::Sketch& sketch, const std::vector<std::uint8_t>& leaf, std::size_t i,
                 const geom::Vec3& p) {
  if (sketch.notWood().empty()) return leaf.empty() || !leaf[i];
  const sketch::Sketch::LassoClass c = sketch.lassoClass(p);
  if (c != sketch::Sketch::LassoClass::None) return c == sketch::Sketch::LassoClass::Wood;
  return leaf.empty() || !leaf[i];
}

geom::PointCloud woodOnly(const geom::PointCloud& cloud, const sketch::Sketch& sketch,
                          const std::vector<std::uint8_t>& leaf) {
  if (!leaf.empty() && leaf.size() != cloud.size())
    throw OptionsError("wood points: " + std::to_string(leaf.size()) + " classes for a cloud of " +
                       std::to_string(cloud.size()) + " points");
  if (sketch.notWood().empty() && leaf.empty()) return cloud;
  geom::PointCloud out;
  out.up = cloud.up;
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    if (!isWoodPoint(sketch, leaf, i, cloud.positions[i])) continue;
    out.positions.push_back(cloud.positions[i]);
    if (!cloud.station.empty()) out.station.push_back(cloud.station[i]);
    if (!cloud.meshId.empty()) out.meshId.push_back(cloud.meshId[i]);
    if (!cloud.scanner.empty()) out.scanner.push_back(cloud.scanner[i]);
  }
  return out;
}

namespace {

/// Runs the skeleton on `region` and merges it under `attachTo` (kNoNode: nearest node to its root).
AutoHereResult mergeRegion(sketch::Sketch& sketch, const geom::PointCloud& region, NodeId attachTo,
                           const std::map<NodeId, NodeAnchor>& anchors, const AutoHereOptions& o) {
  AutoHereResult res;
  res.regionPoints = region.size();
  if (region.size() < 50)
    throw OptionsError("automatic from here: only " + std::to_string(region.size()) +
                       " points in the region (too few for a skeleton)");
  skeleton::AutoSkeletonResult r = skeleton::autoSkeletonSketch(region, o.skeleton);
  const sketch::Sketch& piece = r.sketch;
  if (piece.empty()) throw OptionsError("automatic from here: no skeleton found in the region");
  // Drop the region's nodes that repeat an existing node.
  const double floor = sketch.defaults.sliceHalfThickness;
  std::vector<NodeId> drop;
  for (const auto& [pid, pn] : piece.nodes()) {
    const Vec3 c = pn.kept ? pn.kept->centre : pn.point;
    const double pr = pn.kept ? pn.kept->radius : 0.0;
    for (const auto& [id, a] : anchors) {
      const double lim = std::max(floor, o.duplicateRadii * std::max(pr, a.radius));
      if ((a.centre - c).norm() < lim) {
        drop.push_back(pid);
        break;
      }
    }
  }
  res.duplicates = drop.size();
  if (drop.size() == piece.size()) return res;  // the region holds nothing new
  if (attachTo == kNoNode && !sketch.empty()) {
    // The piece's first kept node's nearest existing node.
    Vec3 start = Vec3::Zero();
    std::set<NodeId> dropped(drop.begin(), drop.end());
    for (NodeId pid : piece.topologicalOrder())
      if (!dropped.count(pid)) {
        const auto& pn = piece.node(pid);
        start = pn.kept ? pn.kept->centre : pn.point;
        break;
      }
    double best = std::numeric_limits<double>::infinity();
    for (const auto& [id, a] : anchors)
      if ((a.centre - start).norm() < best) {
        best = (a.centre - start).norm();
        attachTo = id;
      }
    if (attachTo == kNoNode) attachTo = sketch.root();
  }
  res.attachedTo = attachTo;
  res.added = sketch::graft(sketch, piece, attachTo, drop);
  return res;
}

}  // namespace

AutoHereResult automaticBelow(sketch::Sketch& sketch, const geom::PointCloud& cloud, NodeId node,
                              const std::map<NodeId, NodeAnchor>& anchors, const AutoHereOptions& o) {
  sketch.node(node);  // throws for an unknown id
  auto it = anchors.find(node);
  if (it == anchors.end())
    throw OptionsError("automatic from here: node " + std::to_string(node) + " has no circle yet");
  const Vec3 c = it->second.centre;
  const sketch::NodeGeometry g = sketch.geometry(node);
  const Vec3 n = g.planeNormal.normalized();
  const double radius = o.regionRadius > 0 ? o.regionRadius : 0.25 * cloud.bounds().diagonal();
  geom::PointCloud region;
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    const Vec3& p = cloud.positions[i];
    if ((p - c).dot(n) < 0 || (p - c).norm() > radius || sketch.isNotWood(p)) continue;
    region.positions.push_back(p);
  }
  return mergeRegion(sketch, region, node, anchors, o);
}

AutoHereResult automaticInRegion(sketch::Sketch& sketch, const geom::PointCloud& cloud, const geom::Camera& camera,
                                 const std::vector<Vec2>& polygon, const std::map<NodeId, NodeAnchor>& anchors,
                                 const AutoHereOptions& o) {
  if (polygon.size() < 3) throw OptionsError("automatic in region: the region needs at least 3 vertices");
  geom::PointCloud region;
  for (const Vec3& p : cloud.positions) {
    const Vec3 s = camera.project(p);
    if (!s.allFinite() || s.z() < 0 || s.z() > 1 || !sketch::polygonContains(polygon, s.head<2>())) continue;
    if (sketch.isNotWood(p)) continue;
    region.positions.push_back(p);
  }
  return mergeRegion(sketch, region, kNoNode, anchors, o);
}

}  // namespace treesketch::edit
