// The simulated careful user ("user" method): its screen sketch drawn from the true branch axes,
// fitted to the points the wood/leaf classification calls wood on a leaf-on scan, and why each of
// its nodes has or lacks a circle (eval/user_node_causes.h).
#include <algorithm>
#include <cmath>
#include <limits>

#include "eval_methods.h"
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

sketch::PolylineSketchOptions userOptions(const MethodInput& in, std::vector<sketch::BranchPolyline>& axes) {
  sketch::PolylineSketchOptions po;
  double spacing = 0;
  axes = branchesForBudget(in.tree.axes, in.nodeCount, &spacing);
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

// The careful user draws over the whole cloud, as the person sees it; on a leaf-on scan its nodes
// are fitted to the points the wood/leaf classification calls wood (EvalOptions::userFitsOnWood),
// as the desktop tool fits a person's nodes once the cloud is classified. With the scanner's
// labels (a simulated scan) each node's cause is recorded (not timed).
MethodOutput methodUser(const MethodInput& in) {
  const Stopwatch timer;
  std::vector<sketch::BranchPolyline> axes;
  auto po = userOptions(in, axes);
  sketch::Sketch sk = sketch::sketchFromPolylines(axes, viewCamera(in), po);
  const recon::ReconstructionOptions ro = carefulUserFitOptions(in.options, in.tree.metresPerUnit);
  std::vector<std::uint8_t> kept(in.cloud.size(), 1);
  MethodOutput out;
  NodeResults results;
  bool fitted = false;
  if (in.leafOn && in.options.userFitsOnWood) {
    classify::Classification c = classify::classifyWood(in.cloud, in.tree.up);
    if (c.woodPoints >= kMinWoodPoints) {  // else no tree's wood: every point, as before
      kept = std::move(c.wood);
      out = reconstructSketch(sk, pointsWhere(in.cloud, kept), ro, timer, &results);
      fitted = true;
    }
  }
  if (!fitted) out = reconstructSketch(sk, in.cloud, ro, timer, &results);
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
