// The simulated careful user ("user" method): its screen sketch drawn from the true branch axes,
// fitted to the points the wood/leaf classification calls wood on a leaf-on scan, and why each of
// its nodes has or lacks a circle (eval/user_node_causes.h).
#include <algorithm>
#include <cmath>
#include <limits>

#include "eval_methods.h"
#include "treesketch/accel/point_index.h"
#include "treesketch/classify/classify.h"
#include "treesketch/eval/user_node_causes.h"
#include "treesketch/sketch/auto_sketch.h"

namespace treesketch::eval {

namespace detail {

namespace {

double polylineLength(const sketch::BranchPolyline& b) {
  double l = 0;
  for (std::size_t i = 1; i < b.points.size(); ++i) l += (b.points[i] - b.points[i - 1]).norm();
  return l;
}

/// A careful user with a budget of about `nodeCount` nodes draws the trunk and the branches long
/// enough to deserve a node at the chosen spacing s: a branch (whose parent is drawn) is drawn when
/// its length is at least s, with max(1, round(length / s)) nodes (as sketchFromPolylines places
/// them). s is found by bisection so that the node count is as close to the budget as possible.
std::vector<bool> branchesAtSpacing(const std::vector<sketch::BranchPolyline>& axes, double s, int* nodes) {
  std::vector<bool> keep(axes.size(), false);
  int count = 0;
  for (std::size_t i = 0; i < axes.size(); ++i) {  // parents come before children in both sources
    bool isRoot = axes[i].parent < 0;
    double len = polylineLength(axes[i]);
    bool parentKept = isRoot || (axes[i].parent < static_cast<int>(i) && keep[axes[i].parent]);
    keep[i] = isRoot || (parentKept && len >= s);
    if (keep[i]) count += std::max(1, static_cast<int>(std::lround(len / s))) + (isRoot ? 1 : 0);
  }
  *nodes = count;
  return keep;
}

std::vector<sketch::BranchPolyline> branchesForBudget(const std::vector<sketch::BranchPolyline>& axes, int nodeCount,
                                                      double* spacingOut) {
  double total = 0;
  for (const auto& a : axes) total += polylineLength(a);
  double lo = total * 1e-4, hi = total;  // count(lo) >= budget >= count(hi), mostly
  int n = 0;
  for (int iter = 0; iter < 60; ++iter) {
    double mid = std::sqrt(lo * hi);
    branchesAtSpacing(axes, mid, &n);
    if (n > nodeCount)
      lo = mid;
    else
      hi = mid;
  }
  int nLo = 0, nHi = 0;
  auto keepLo = branchesAtSpacing(axes, lo, &nLo);
  auto keepHi = branchesAtSpacing(axes, hi, &nHi);
  bool useLo = std::abs(nLo - nodeCount) < std::abs(nHi - nodeCount);
  const std::vector<bool>& keep = useLo ? keepLo : keepHi;
  std::vector<int> newIndex(axes.size(), -1);
  std::vector<sketch::BranchPolyline> out;
  for (std::size_t i = 0; i < axes.size(); ++i) {
    if (!keep[i]) continue;
    newIndex[i] = static_cast<int>(out.size());
    out.push_back(axes[i]);
  }
  for (auto& b : out)
    if (b.parent >= 0) b.parent = newIndex[b.parent];
  if (spacingOut) *spacingOut = useLo ? lo : hi;
  return out;
}

// The true limb under each planned node: the ideal user's point nodes (same plan, same id order)
// and the radius at the tree's axis vertex nearest each (0 when the tree has no radii).
std::vector<TrueNode> trueNodes(const TreeCase& tree, const std::vector<sketch::BranchPolyline>& axes,
                                const sketch::PolylineSketchOptions& po) {
  const sketch::Sketch ideal = sketch::pointNodesFromPolylines(axes, po);
  std::vector<TrueNode> out;
  for (const auto& [id, node] : ideal.nodes()) {
    TrueNode t;
    t.point = node.point;
    t.tangent = node.normal.normalized();
    double best = std::numeric_limits<double>::infinity();
    for (std::size_t a = 0; a < tree.axes.size() && a < tree.axisRadii.size(); ++a)
      for (std::size_t v = 0; v < tree.axes[a].points.size() && v < tree.axisRadii[a].size(); ++v) {
        const double d = (tree.axes[a].points[v] - node.point).squaredNorm();
        if (d < best) {
          best = d;
          t.radius = tree.axisRadii[a][v];
        }
      }
    out.push_back(t);
  }
  return out;
}

}  // namespace

std::vector<sketch::BranchPolyline> seenBranches(const std::vector<sketch::BranchPolyline>& axes,
                                                 const std::vector<std::vector<double>>& radii,
                                                 const geom::PointCloud& seen, double halfThickness, int minPoints) {
  const accel::PointIndex index(seen);
  std::vector<std::uint32_t> near;
  // Whether the points show the branch at p (tangent t, radius r): enough of them in the slab
  // across it, within two radii and a slab's half-thickness (where a node there would fit).
  auto shows = [&](const geom::Vec3& p, const geom::Vec3& t, double r) {
    index.withinRadius(p, 2 * r + halfThickness, near);
    int n = 0;
    for (std::uint32_t i : near)
      if (std::abs((index.point(i) - p).dot(t)) <= halfThickness && ++n >= minPoints) return true;
    return false;
  };
  // drawn[i]: how many of branch i's vertices are drawn (0: the branch is not).
  std::vector<std::size_t> drawn(axes.size(), 0);
  for (std::size_t i = 0; i < axes.size(); ++i) {
    const auto& b = axes[i];
    const int parent = b.parent;
    if (parent >= static_cast<int>(i)) continue;  // parents come first; anything else is not drawn
    if (parent >= 0 && (drawn[parent] == 0 || b.parentVertex >= drawn[parent])) continue;
    const std::vector<double>* rs = i < radii.size() && radii[i].size() == b.points.size() ? &radii[i] : nullptr;
    // Vertex 0, then each segment sampled a radius apart (at least a slab's thickness) up to its
    // end vertex: the vertices reached while every sample shows the branch are drawn.
    auto radiusAt = [&](std::size_t v) { return rs ? std::max((*rs)[v], 0.0) : 0.0; };
    std::size_t count = 0;
    if (b.points.size() >= 2) {
      const geom::Vec3 d0 = b.points[1] - b.points[0];
      const geom::Vec3 t0 = d0.norm() > 0 ? geom::Vec3(d0.normalized()) : geom::Vec3::UnitY();
      if (shows(b.points[0], t0, radiusAt(0))) count = 1;
    }
    for (std::size_t v = 0; count == v + 1 && v + 1 < b.points.size(); ++v) {
      const geom::Vec3 a = b.points[v], e = b.points[v + 1];
      const double len = (e - a).norm();
      if (!(len > 0)) {
        count = v + 2;
        continue;
      }
      const geom::Vec3 t = (e - a) / len;
      const double ra = radiusAt(v), re = radiusAt(v + 1);
      const double step = std::max(std::max(ra, re), 2 * halfThickness);
      const int samples = std::max(1, static_cast<int>(std::ceil(len / step)));
      bool ok = true;
      for (int k = 1; k <= samples && ok; ++k) {
        const double f = static_cast<double>(k) / samples;
        ok = shows(a + f * (e - a), t, ra + f * (re - ra));
      }
      if (ok) count = v + 2;
    }
    // A branch drawn is a line: its base and one more vertex at least.
    drawn[i] = count >= 2 ? count : 0;
  }
  std::vector<int> newIndex(axes.size(), -1);
  std::vector<sketch::BranchPolyline> out;
  for (std::size_t i = 0; i < axes.size(); ++i) {
    if (drawn[i] == 0) continue;
    newIndex[i] = static_cast<int>(out.size());
    sketch::BranchPolyline b = axes[i];
    b.points.resize(drawn[i]);
    if (b.parent >= 0) b.parent = newIndex[b.parent];
    out.push_back(std::move(b));
  }
  return out;
}

sketch::PolylineSketchOptions userOptions(const MethodInput& in, std::vector<sketch::BranchPolyline>& axes) {
  return userOptions(in, in.tree.axes, axes);
}

sketch::PolylineSketchOptions userOptions(const MethodInput& in, const std::vector<sketch::BranchPolyline>& source,
                                          std::vector<sketch::BranchPolyline>& axes) {
  sketch::PolylineSketchOptions po;
  double spacing = 0;
  axes = branchesForBudget(source, in.nodeCount, &spacing);
  po.nodeSpacing = spacing;
  po.pixelNoise = in.options.pixelNoise;
  po.seed = in.options.seed;
  po.params = sketch::defaultSamplingFor(in.cloud.bounds());
  po.up = in.tree.up;
  return po;
}

void setCauses(EvalRow& row, const NodeCauseCounts& c) {
  auto count = [&](NodeCause k) { return c.causes.count(k) ? c.causes.at(k) : 0; };
  row.skippedOffLimb = count(NodeCause::OffLimb);
  row.skippedHidden = count(NodeCause::Hidden);
  row.skippedClassedLeaf = count(NodeCause::ClassedLeaf);
  row.skippedRejected = count(NodeCause::Rejected);
  row.fittedOnLimb = c.onLimb;
  for (const auto& [test, n] : c.tests)
    row.rejectedBy += (row.rejectedBy.empty() ? "" : ";") + test + ":" + std::to_string(n);
}

}  // namespace detail

recon::ReconstructionOptions carefulUserFitOptions(const EvalOptions& o, double metresPerUnit) {
  recon::ReconstructionOptions ro;
  ro.seed = o.seed;
  ro.fit.chooseDepth = o.chooseDepth;
  ro.radii.enabled = o.chooseDepth;  // as the viewer fits a person's sketch
  ro.fit.growScreenNodes = o.userGrowth;
  if (o.userInlierBandMetres > 0 && metresPerUnit > 0 && std::isfinite(metresPerUnit))
    ro.fit.circle.inlierThreshold = o.userInlierBandMetres / metresPerUnit;
  return ro;
}

namespace detail {

std::vector<std::uint8_t> carefulUserPoints(const MethodInput& in) {
  if (in.leafOn && in.options.userFitsOnWood) {
    classify::Classification c = classify::classifyWood(in.cloud, in.tree.up);
    if (c.woodPoints >= kMinWoodPoints) return std::move(c.wood);  // else no tree's wood: every point
  }
  return std::vector<std::uint8_t>(in.cloud.size(), 1);
}

const geom::PointCloud& pointsKept(const geom::PointCloud& cloud, const std::vector<std::uint8_t>& kept,
                                  geom::PointCloud& storage) {
  if (std::all_of(kept.begin(), kept.end(), [](std::uint8_t k) { return k != 0; })) return cloud;
  storage = pointsWhere(cloud, kept);
  return storage;
}

sketch::PolylineSketchOptions carefulUserPlan(const MethodInput& in, const geom::PointCloud& seen, int minPoints,
                                              std::vector<sketch::BranchPolyline>& axes) {
  if (!in.options.userDrawsWhatItSees) return userOptions(in, axes);
  // A person sketches over what the view shows: the points its nodes are fitted on.
  const double h = sketch::defaultSamplingFor(in.cloud.bounds()).sliceHalfThickness;
  const auto drawn = seenBranches(in.tree.axes, in.tree.axisRadii, seen, h, minPoints);
  // A scan that shows not even the trunk's base: every branch, as the thesis planned it.
  return userOptions(in, drawn.empty() ? in.tree.axes : drawn, axes);
}

// The careful user draws what the points it fits on show; on a leaf-on scan those are the points
// the wood/leaf classification calls wood (EvalOptions::userFitsOnWood), as the desktop tool fits a
// person's nodes once the cloud is classified. With the scanner's labels (a simulated scan) each
// node's cause is recorded (not timed).
MethodOutput methodUser(const MethodInput& in) {
  const Stopwatch timer;
  const recon::ReconstructionOptions ro = carefulUserFitOptions(in.options, in.tree.metresPerUnit);
  const std::vector<std::uint8_t> kept = carefulUserPoints(in);
  geom::PointCloud wood;
  const geom::PointCloud& fitCloud = pointsKept(in.cloud, kept, wood);
  std::vector<sketch::BranchPolyline> axes;
  const sketch::PolylineSketchOptions po = carefulUserPlan(in, fitCloud, ro.fit.circle.minInliers, axes);
  sketch::Sketch sk = sketch::sketchFromPolylines(axes, viewCamera(in), po);
  MethodOutput out;
  NodeResults results;
  out = reconstructSketch(sk, fitCloud, ro, timer, &results);
  if (in.cloud.meshId.size() == in.cloud.size() && !in.cloud.empty()) {
    fit::NodeFitOptions fo = ro.fit;
    fo.circle.seed = ro.seed;  // the base seed, as recon's
    const std::vector<TrueNode> truth = trueNodes(in.tree, axes, po);
    out.causes = countCauses(userNodeCauses(NodeCauseInput{in.cloud, kept, sk, truth, results, fo}));
  }
  return out;
}

}  // namespace detail

}  // namespace treesketch::eval
