#include "skeleton/axis_smoothing.h"

#include <algorithm>
#include <cmath>

namespace treesketch::skeleton::detail {

using geom::Vec3;

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

namespace {

/// One sample of a chain: arc length, position, weight (the node's reliability).
struct Sample {
  double s = 0;
  Vec3 p = Vec3::Zero();
  double w = 0;
};

/// Weighted line fit p(s) = a + b (s - s0) over `samples` with weights w·kernel·robust, evaluated at s0.
Vec3 localLine(const std::vector<Sample>& samples, const std::vector<double>& weights, double s0) {
  double sw = 0, ss = 0, sss = 0;
  Vec3 sp = Vec3::Zero(), ssp = Vec3::Zero();
  for (std::size_t k = 0; k < samples.size(); ++k) {
    const double w = weights[k];
    if (!(w > 0)) continue;
    const double d = samples[k].s - s0;
    sw += w;
    ss += w * d;
    sss += w * d * d;
    sp += w * samples[k].p;
    ssp += w * d * samples[k].p;
  }
  const double det = sw * sss - ss * ss;
  if (!(sw > 0)) return Vec3::Constant(std::nan(""));
  if (!(det > 1e-12 * sw * sss) || !(sss > 0)) return sp / sw;  // one point or all at s0: the mean
  return (sss * sp - ss * ssp) / det;                           // the intercept at s0
}

/// The smoothed positions of one chain's samples (index 0 may be a fixed anchor).
std::vector<Vec3> smoothChain(const std::vector<Sample>& samples, bool anchored, const AxisRules& rules) {
  const int m = static_cast<int>(samples.size());
  std::vector<Vec3> out(m);
  std::vector<double> weights, res, sorted;
  std::vector<Sample> window;
  for (int k = 0; k < m; ++k) {
    out[k] = samples[k].p;
    if ((anchored && k == 0) || samples[k].w >= 1) continue;  // anchors and circle centres stay
    const int lo = std::max(0, k - rules.halfWindowNodes), hi = std::min(m - 1, k + rules.halfWindowNodes);
    window.assign(samples.begin() + lo, samples.begin() + hi + 1);
    double h = 0;
    for (const auto& x : window) h = std::max(h, std::abs(x.s - samples[k].s));
    h = h > 0 ? h * 1.25 : 1.0;  // tricube support just beyond the window's farthest node
    weights.assign(window.size(), 0.0);
    for (std::size_t j = 0; j < window.size(); ++j) {
      const double u = std::min(1.0, std::abs(window[j].s - samples[k].s) / h);
      const double t = 1 - u * u * u;
      weights[j] = window[j].w * t * t * t;
    }
    Vec3 fit = localLine(window, weights, samples[k].s);
    // One robust step (Tukey biweight on the residuals, scale = 4.685 × median residual): a node
    // far off the local line does not drag it.
    res.resize(window.size());
    for (std::size_t j = 0; j < window.size(); ++j)
      res[j] = (window[j].p - localLine(window, weights, window[j].s)).norm();
    sorted = res;
    std::nth_element(sorted.begin(), sorted.begin() + sorted.size() / 2, sorted.end());
    const double scale = 4.685 * std::max(sorted[sorted.size() / 2], 1e-12);
    for (std::size_t j = 0; j < window.size(); ++j) {
      const double u = std::min(1.0, res[j] / scale);
      weights[j] *= (1 - u * u) * (1 - u * u);
    }
    const Vec3 robust = localLine(window, weights, samples[k].s);
    if (robust.allFinite()) fit = robust;
    if (fit.allFinite()) out[k] = fit;
  }
  return out;
}

}  // namespace

std::vector<Vec3> smoothAxes(const std::vector<SkeletonNode>& nodes, const std::vector<char>& fitted,
                             const std::vector<double>& radii, const AxisRules& rules) {
  std::vector<Vec3> pos(nodes.size());
  for (std::size_t i = 0; i < nodes.size(); ++i) pos[i] = nodes[i].position;
  if (rules.halfWindowNodes <= 0) return pos;
  std::vector<Sample> samples;
  // Chains start parent-first, so a side branch's parent chain is smoothed before it.
  for (const auto& chain : branchChains(nodes)) {
    samples.clear();
    const std::int32_t parent = nodes[chain.front()].parent;
    const bool anchored = parent >= 0;
    if (anchored) samples.push_back({0.0, pos[parent], 1.0});
    for (std::int32_t i : chain) {
      const Vec3& p = nodes[i].position;
      const double s = samples.empty() ? 0.0 : samples.back().s + (p - samples.back().p).norm();
      samples.push_back({s, p, fitted[i] ? 1.0 : rules.unfittedWeight});
    }
    const std::vector<Vec3> smoothed = smoothChain(samples, anchored, rules);
    for (std::size_t k = 0; k < chain.size(); ++k) {
      // A centroid of surface points lies within one radius of the axis: a longer move would cut
      // a real bend.
      const std::int32_t i = chain[k];
      const Vec3 move = smoothed[k + (anchored ? 1 : 0)] - nodes[i].position;
      const double limit = std::max(0.0, rules.maxShiftRadii * radii[i]), len = move.norm();
      pos[i] = nodes[i].position + (len > limit && len > 0 ? move * (limit / len) : move);
    }
  }
  return pos;
}

}  // namespace treesketch::skeleton::detail
