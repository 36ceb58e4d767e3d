// Skeleton → sketch → fitted, regularised model. The pipe model is Shinozaki et al. 1964 (as used
// by Xu et al. 2007 for branch thickness); the node fit is the thesis's (fit module).
#include "treesketch/skeleton/skeleton_sketch.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>

#include "treesketch/fit/cloud_index.h"
#include "treesketch/sweep/tube_mesh.h"
#include "treesketch/util/error.h"

namespace treesketch::skeleton {
namespace {

using geom::Vec3;

double elapsedMs(std::chrono::steady_clock::time_point since) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - since).count();
}

sketch::SamplingParams paramsFor(double radius, double voxel, const SkeletonSketchOptions& o) {
  sketch::SamplingParams p;
  p.sliceHalfThickness = std::max(o.sliceRadii * radius, o.sliceVoxels * voxel);
  p.lineEpsilon = o.lineRadii * radius + o.lineVoxels * voxel;
  p.lineEpsilonStep = o.stepRadii * radius + o.stepVoxels * voxel;
  p.maxGrowthSteps = autoNodeFitOptions().maxGrowthSteps;  // the same cap in the GUI and `reconstruct --sketch`
  return p;
}

void checkRules(const RadiusRules& r) {
  if (!(r.maxRadiusRatio > 0) || !(r.maxCentreShiftRadii > 0) || !(r.maxRelativeRms > 0))
    throw OptionsError("skeleton radii: maxRadiusRatio, maxCentreShiftRadii and maxRelativeRms must be > 0");
  if (r.medianWindow < 1) throw OptionsError("skeleton radii: medianWindow must be >= 1");
  if (!(r.pipeExponent > 0) || !std::isfinite(r.pipeExponent))
    throw OptionsError("skeleton radii: pipeExponent must be > 0");
}

/// Branches as node chains: each starts at the root or at a child whose branch order differs
/// from its parent's, and follows the child of the same order.
std::vector<std::vector<std::int32_t>> branchChains(const std::vector<SkeletonNode>& nodes) {
  std::vector<std::vector<std::int32_t>> chains;
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    const auto& n = nodes[i];
    const bool starts = n.parent < 0 || nodes[n.parent].branchOrder != n.branchOrder;
    if (!starts) continue;
    std::vector<std::int32_t> chain;
    std::int32_t cur = static_cast<std::int32_t>(i);
    while (cur >= 0) {
      chain.push_back(cur);
      std::int32_t next = -1;
      for (std::int32_t c : nodes[cur].children)
        if (nodes[c].branchOrder == nodes[cur].branchOrder) {
          next = c;
          break;
        }
      cur = next;
    }
    chains.push_back(std::move(chain));
  }
  return chains;
}

}  // namespace

sketch::Sketch skeletonToSketch(const Skeleton& skeleton, const SkeletonSketchOptions& options) {
  sketch::Sketch s;
  s.up = skeleton.up;
  const double voxel = skeleton.graph.voxelSize > 0 ? skeleton.graph.voxelSize : 1.0;
  if (skeleton.nodes.empty()) return s;
  s.defaults = paramsFor(skeleton.nodes.front().radius, voxel, options);
  for (std::size_t i = 0; i < skeleton.nodes.size(); ++i) {
    const auto& n = skeleton.nodes[i];
    const sketch::NodeId parent = n.parent < 0 ? sketch::kNoNode : n.parent;
    const sketch::NodeId id = s.addPointNode(parent, n.position, n.direction, paramsFor(n.radius, voxel, options));
    if (id != static_cast<sketch::NodeId>(i)) throw OptionsError("skeleton: sketch ids out of step with nodes");
  }
  return s;
}

std::vector<double> regularizeRadii(const std::vector<SkeletonNode>& nodes, const std::vector<double>& fitted,
                                    const std::vector<char>& valid, const RadiusRules& rules) {
  checkRules(rules);
  if (fitted.size() != nodes.size() || valid.size() != nodes.size())
    throw OptionsError("skeleton radii: one fitted radius and one validity flag per node expected");
  const std::size_t n = nodes.size();
  std::vector<double> r(n);
  std::vector<char> ok(n);
  for (std::size_t i = 0; i < n; ++i) {
    ok[i] = valid[i] && std::isfinite(fitted[i]) && fitted[i] > 0;
    r[i] = ok[i] ? fitted[i] : nodes[i].radius;
  }
  const auto chains = branchChains(nodes);
  // 1. Interpolate rejected fits along each branch by arc length (the fork at a side branch's
  // start is the parent's node: it is read, not written).
  std::vector<double> arc;
  for (const auto& chain : chains) {
    arc.assign(chain.size(), 0.0);
    for (std::size_t k = 1; k < chain.size(); ++k)
      arc[k] = arc[k - 1] + (nodes[chain[k]].position - nodes[chain[k - 1]].position).norm();
    std::vector<std::size_t> good;
    for (std::size_t k = 0; k < chain.size(); ++k)
      if (ok[chain[k]]) good.push_back(k);
    if (good.empty()) continue;  // keep the skeleton's estimates
    for (std::size_t k = 0; k < chain.size(); ++k) {
      if (ok[chain[k]]) continue;
      auto after = std::lower_bound(good.begin(), good.end(), k);
      double value;
      if (after == good.begin()) {
        value = r[chain[*after]];
      } else if (after == good.end()) {
        value = r[chain[good.back()]];
      } else {
        const std::size_t b = *after, a = *(after - 1);
        const double t = arc[b] > arc[a] ? (arc[k] - arc[a]) / (arc[b] - arc[a]) : 0.5;
        value = (1 - t) * r[chain[a]] + t * r[chain[b]];
      }
      r[chain[k]] = value;
    }
  }
  // 2. Running median along each branch.
  if (rules.medianWindow > 1) {
    std::vector<double> smoothed = r, window;
    const int half = rules.medianWindow / 2;
    for (const auto& chain : chains) {
      const int m = static_cast<int>(chain.size());
      for (int k = 0; k < m; ++k) {
        window.clear();
        for (int j = std::max(0, k - half); j <= std::min(m - 1, k + half); ++j) window.push_back(r[chain[j]]);
        std::nth_element(window.begin(), window.begin() + window.size() / 2, window.end());
        smoothed[chain[k]] = window[window.size() / 2];
      }
    }
    r = smoothed;
  }
  // 3. Pipe model at forks, bottom-up (nodes are parent-first).
  if (rules.pipeModel) {
    for (std::size_t i = n; i-- > 0;) {
      if (nodes[i].children.size() < 2) continue;
      double sum = 0;
      for (std::int32_t c : nodes[i].children) sum += std::pow(r[c], rules.pipeExponent);
      r[i] = std::max(r[i], std::pow(sum, 1.0 / rules.pipeExponent));
    }
  }
  // 4. No child thicker than its parent, top-down.
  if (rules.childNotThicker)
    for (std::size_t i = 0; i < n; ++i)
      if (nodes[i].parent >= 0) r[i] = std::min(r[i], r[nodes[i].parent]);
  return r;
}

AutoSkeletonResult autoSkeletonSketch(const geom::PointCloud& cloud, const AutoSkeletonOptions& options,
                                      const ProgressFn& progress) {
  checkRules(options.radii);
  if (!(options.maxFitFlatFraction >= 0 && options.maxFitFlatFraction <= 1))
    throw OptionsError("skeleton: maxFitFlatFraction must be in [0, 1]");
  if (!(options.minInlierBandVoxels >= 0) || !std::isfinite(options.minInlierBandVoxels))
    throw OptionsError("skeleton: minInlierBandVoxels must be a finite number >= 0");
  AutoSkeletonResult res;
  auto t0 = std::chrono::steady_clock::now();
  res.skeleton = extractSkeleton(cloud, options.skeleton);
  res.sketch = skeletonToSketch(res.skeleton, options.sketch);
  res.skeletonMs = elapsedMs(t0);
  const auto& nodes = res.skeleton.nodes;
  const std::size_t n = nodes.size();
  if (n == 0) return res;

  t0 = std::chrono::steady_clock::now();
  const fit::CloudIndex index(cloud);
  const double voxel = res.skeleton.graph.voxelSize;
  fit::NodeFitOptions fitOptions = options.fit;
  fitOptions.circle.inlierThreshold = std::max(fitOptions.circle.inlierThreshold, options.minInlierBandVoxels * voxel);
  res.fits.resize(n);
  std::atomic<std::uint64_t> done{0};
  tbb::parallel_for(std::size_t{0}, n, [&](std::size_t i) {
    fit::NodeFitOptions fo = fitOptions;
    fo.circle.seed = options.seed + i;
    const auto id = static_cast<sketch::NodeId>(i);
    if (isLeafPiece(nodes[i], options)) {
      res.fits[i].status = fit::NodeStatus::Skipped;
      res.fits[i].reason = "leaf piece (mostly flat voxels): not fitted";
    } else {
      res.fits[i] = fit::fitNode(index, res.sketch.geometry(id), res.sketch.node(id).params, fo);
    }
    const std::uint64_t d = ++done;
    if (progress && (d % 64 == 0 || d == n)) progress(d, n);
  });
  res.fitMs = elapsedMs(t0);

  t0 = std::chrono::steady_clock::now();
  const RadiusRules& rules = options.radii;
  res.fitAccepted.assign(n, 0);
  std::vector<double> fitted(n, 0.0);
  res.model = nodes;
  for (std::size_t i = 0; i < n; ++i) {
    const auto& f = res.fits[i];
    if (f.status != fit::NodeStatus::Fitted) continue;
    const double est = nodes[i].radius;
    const bool ok = f.radius <= rules.maxRadiusRatio * est + voxel &&
                    (f.centre - nodes[i].position).norm() <= rules.maxCentreShiftRadii * est + voxel &&
                    f.rms <= rules.maxRelativeRms * f.radius + 0.25 * voxel;
    if (!ok) continue;
    res.fitAccepted[i] = 1;
    fitted[i] = f.radius;
    res.model[i].position = f.centre;
  }
  if (options.trimUnfittedTips) {
    // Reverse order visits children before parents.
    std::vector<char> keep(n, 1);
    for (std::size_t i = n; i-- > 1;) {
      if (res.fitAccepted[i]) continue;
      bool anyChild = false;
      for (std::int32_t c : nodes[i].children) anyChild |= keep[c] != 0;
      keep[i] = anyChild;
    }
    std::vector<std::int32_t> newIndex(n, -1);
    std::vector<SkeletonNode> kept;
    std::vector<fit::NodeResult> keptFits;
    std::vector<char> keptAccepted;
    std::vector<double> keptFitted;
    for (std::size_t i = 0; i < n; ++i) {
      if (!keep[i]) continue;
      newIndex[i] = static_cast<std::int32_t>(kept.size());
      SkeletonNode node = nodes[i];
      node.parent = node.parent >= 0 ? newIndex[node.parent] : -1;
      node.children.clear();
      kept.push_back(node);
      keptFits.push_back(std::move(res.fits[i]));
      keptAccepted.push_back(res.fitAccepted[i]);
      keptFitted.push_back(fitted[i]);
    }
    for (std::size_t i = 0; i < kept.size(); ++i)
      if (kept[i].parent >= 0) kept[kept[i].parent].children.push_back(static_cast<std::int32_t>(i));
    if (kept.size() != n) {
      std::vector<geom::Vec3> centres;
      for (std::size_t i = 0; i < n; ++i)
        if (keep[i]) centres.push_back(res.model[i].position);
      Skeleton trimmed;
      trimmed.up = res.skeleton.up;
      trimmed.graph.voxelSize = voxel;
      trimmed.nodes = kept;
      res.sketch = skeletonToSketch(trimmed, options.sketch);
      res.model = kept;
      for (std::size_t i = 0; i < kept.size(); ++i) res.model[i].position = centres[i];
      res.fits = std::move(keptFits);
      res.fitAccepted = std::move(keptAccepted);
      fitted = std::move(keptFitted);
      res.skeleton.nodes = std::move(kept);
    }
  }
  const std::size_t m = res.model.size();
  const std::vector<double> radii = regularizeRadii(res.skeleton.nodes, fitted, res.fitAccepted, rules);
  for (std::size_t i = 0; i < m; ++i) res.model[i].radius = radii[i];

  std::vector<sweep::SweepNode> sweepNodes(m);
  for (std::size_t i = 0; i < m; ++i) {
    auto& s = sweepNodes[i];
    s.id = static_cast<sketch::NodeId>(i);
    s.parent = res.model[i].parent < 0 ? sketch::kNoNode : res.model[i].parent;
    const bool fork = res.model[i].parent >= 0 && res.model[i].children.size() >= 2;
    s.fitted = !(options.bridgeUnfittedForks && fork && !res.fitAccepted[i]);
    s.disc = sweep::Disc{res.model[i].position, res.model[i].direction, radii[i]};
    if (options.keepModelCircles) {
      const auto id = static_cast<sketch::NodeId>(i);
      if (s.fitted) {
        res.sketch.setKeptCircle(id, sketch::KeptCircle{res.model[i].position, radii[i]});
      } else {
        sketch::SamplingParams p = res.sketch.node(id).params;
        p.enabled = false;
        res.sketch.setParams(id, p);
      }
    }
  }
  sweep::SweepOptions so;
  so.ringVertices = options.ringVertices;
  res.mesh = sweep::sweepTubes(sweepNodes, so);
  res.sweepMs = elapsedMs(t0);
  return res;
}

}  // namespace treesketch::skeleton
