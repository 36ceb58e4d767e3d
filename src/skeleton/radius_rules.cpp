// The automatic model's radii from its fits (RadiusRules): fits set aside where implausible, the
// rest interpolated along each branch against the pipe law, smoothed, tapered and bounded.
#include "skeleton/radius_rules.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "skeleton/axis_smoothing.h"
#include "skeleton/radius_allometry.h"
#include "treesketch/util/error.h"

namespace treesketch::skeleton {
namespace {

/// Weight of an interpolated (not fitted) radius in the taper fit, relative to a trusted fit's.
constexpr double kInterpolatedRadiusWeight = 0.25;
/// The fits below a node its growth is judged against (RadiusRules::maxGrowthRatio): the last
/// three kept on its branch, so one odd fit below does not set the reference.
constexpr std::ptrdiff_t kGrowthWindow = 3;

}  // namespace

namespace detail {

void checkRadiusRules(const RadiusRules& r) {
  if (!(r.maxRadiusRatio > 0) || !(r.maxCentreShiftRadii > 0) || !(r.maxRelativeRms > 0))
    throw OptionsError("skeleton radii: maxRadiusRatio, maxCentreShiftRadii and maxRelativeRms must be > 0");
  if (r.medianWindow < 1) throw OptionsError("skeleton radii: medianWindow must be >= 1");
  if (!(r.allometryMaxRatio == 0 || r.allometryMaxRatio >= 1) || !std::isfinite(r.allometryMaxRatio))
    throw OptionsError("skeleton radii: allometryMaxRatio must be 0 (off) or >= 1");
  if (!(r.maxGrowthRatio == 0 || r.maxGrowthRatio >= 1) || !std::isfinite(r.maxGrowthRatio))
    throw OptionsError("skeleton radii: maxGrowthRatio must be 0 (off) or >= 1");
  if (!(r.slackVoxels >= 0) || !(r.rmsFloorVoxels >= 0) || !std::isfinite(r.slackVoxels) ||
      !std::isfinite(r.rmsFloorVoxels))
    throw OptionsError("skeleton radii: slackVoxels and rmsFloorVoxels must be finite numbers >= 0");
}

}  // namespace detail

namespace {

/// Step 1 of regularizeRadii: rejected fits interpolated along each branch by arc length (the
/// fork at a side branch's start is the parent's node: it is read, not written).
void interpolateRejected(const std::vector<SkeletonNode>& nodes, const std::vector<std::vector<std::int32_t>>& chains,
                         const std::vector<char>& ok, const detail::Allometry& allometry, std::vector<double>& r) {
  std::vector<double> arc;
  for (const auto& chain : chains) {
    arc.assign(chain.size(), 0.0);
    for (std::size_t k = 1; k < chain.size(); ++k)
      arc[k] = arc[k - 1] + (nodes[chain[k]].position - nodes[chain[k - 1]].position).norm();
    std::vector<std::size_t> good;
    for (std::size_t k = 0; k < chain.size(); ++k)
      if (ok[chain[k]]) good.push_back(k);
    if (good.empty()) {
      // No fit on the whole branch: the pipe law where there is one (the level-set
      // pieces' own radii are the spread of whatever the bins held: twigs and noise), else
      // those estimates.
      if (allometry.valid)
        for (std::size_t id : chain) r[id] = allometry.predict(id);
      continue;
    }
    for (std::size_t k = 0; k < chain.size(); ++k) {
      if (ok[chain[k]]) continue;
      // With the pipe law, the fits give the scale and the law the shape: the
      // ratio fit / prediction is interpolated, so a branch still tapers past its last fit
      // instead of keeping that fit's radius out to its tip. Without one, the radii themselves.
      auto value = [&](std::size_t j) {
        return allometry.valid ? r[chain[j]] / allometry.predict(chain[j]) : r[chain[j]];
      };
      auto after = std::lower_bound(good.begin(), good.end(), k);
      double v;
      if (after == good.begin()) {
        v = value(*after);
      } else if (after == good.end()) {
        v = value(good.back());
      } else {
        const std::size_t b = *after, a = *(after - 1);
        const double t = arc[b] > arc[a] ? (arc[k] - arc[a]) / (arc[b] - arc[a]) : 0.5;
        v = (1 - t) * value(a) + t * value(b);
      }
      r[chain[k]] = allometry.valid ? v * allometry.predict(chain[k]) : v;
    }
  }
}

/// Step 0b: along each branch (parent-first), a fit wider than `ratio` times the median of the
/// last kGrowthWindow fits kept below it, and wider than the pipe law, is set aside (RadiusRules::
/// maxGrowthRatio); measured (tracked stem) radii are kept and count as fits below.
void setAsideGrowth(const std::vector<std::vector<std::int32_t>>& chains, const std::vector<char>& measured,
                    const detail::Allometry& allometry, double ratio, const std::vector<double>& r,
                    std::vector<char>& ok) {
  std::vector<double> below, last;
  for (const auto& chain : chains) {
    below.clear();
    for (const std::int32_t id : chain) {
      if (!ok[id]) continue;
      if (!measured[id] && !below.empty()) {
        last.assign(below.end() - std::min<std::ptrdiff_t>(kGrowthWindow, std::ssize(below)), below.end());
        std::nth_element(last.begin(), last.begin() + std::ssize(last) / 2, last.end());
        const bool overLaw = !allometry.valid || r[id] > allometry.predict(static_cast<std::size_t>(id));
        if (r[id] > ratio * last[last.size() / 2] && overLaw) {
          ok[id] = 0;
          continue;
        }
      }
      below.push_back(r[id]);
    }
  }
}

/// Step 2: a running median of `size` nodes along each branch.
void medianAlongBranches(const std::vector<std::vector<std::int32_t>>& chains, int size, std::vector<double>& r) {
  {
    std::vector<double> smoothed = r, window;
    const int half = size / 2;
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
}

/// Step 3: the pipe model at forks, bottom-up (nodes are parent-first); measured nodes keep theirs.
void pipeAtForks(const std::vector<SkeletonNode>& nodes, const std::vector<char>& measured, std::vector<double>& r) {
  for (std::size_t i = nodes.size(); i-- > 0;) {
    if (nodes[i].children.size() < 2 || measured[i]) continue;
    double sum = 0;
    for (std::int32_t c : nodes[i].children) sum += r[c] * r[c];
    r[i] = std::max(r[i], std::sqrt(sum));
  }
}

/// Step 4: no child thicker than its parent (see RadiusRules::childNotThicker).
void taperAlongBranches(const std::vector<SkeletonNode>& nodes, const std::vector<std::vector<std::int32_t>>& chains,
                        const std::vector<char>& ok, std::vector<double>& r) {
  // Along each branch the least-absolute-deviations non-increasing radii (isotonic regression, trusted fits
  // weighing most), so one thin fit lowers its neighbours a little instead of capping the whole
  // branch above it; then a branch is capped by the node it forks from (chains are parent-first,
  // so that node is final).
  for (const auto& chain : chains) {
    std::vector<double> values(chain.size()), weights(chain.size());
    for (std::size_t k = 0; k < chain.size(); ++k) {
      values[k] = r[chain[k]];
      weights[k] = ok[chain[k]] ? 1.0 : kInterpolatedRadiusWeight;
    }
    detail::nonIncreasingFit(values, weights);
    const std::int32_t parent = nodes[chain.front()].parent;
    const double cap = parent >= 0 ? r[parent] : std::numeric_limits<double>::infinity();
    for (std::size_t k = 0; k < chain.size(); ++k) r[chain[k]] = std::min(values[k], cap);
  }
}

}  // namespace

std::vector<double> regularizeRadii(const std::vector<SkeletonNode>& nodes, const std::vector<double>& fitted,
                                    const std::vector<char>& valid, const RadiusRules& rules, std::vector<char>* kept) {
  detail::checkRadiusRules(rules);
  if (fitted.size() != nodes.size() || valid.size() != nodes.size())
    throw OptionsError("skeleton radii: one fitted radius and one validity flag per node expected");
  const std::size_t n = nodes.size();
  std::vector<double> r(n);
  std::vector<char> ok(n);
  // A node on the tracked stem has a measured radius even without a fit of its own (the stem's
  // circle fits over whole slabs), and no rule below raises it: the pipe model and the allometry
  // stand in for radii the data cannot give. (Leaf-on, the allometry, fitted mostly to leaf
  // clusters that carry thousands of leaf pieces, gave an oak's 0.14 m trunk a 0.57 m radius.)
  std::vector<char> measured(n);
  for (std::size_t i = 0; i < n; ++i) {
    ok[i] = valid[i] && std::isfinite(fitted[i]) && fitted[i] > 0;
    r[i] = ok[i] ? fitted[i] : nodes[i].radius;
    measured[i] = nodes[i].stem && nodes[i].radius > 0;
    ok[i] = ok[i] || measured[i];
  }
  // 0. Fits much thicker than the pipe model anchored at the stem (radius against the length a
  // node carries) are rejected; no radius ends above that bound (step 5).
  detail::Allometry allometry;
  if (rules.allometryMaxRatio > 0) {
    allometry = detail::fitAllometry(nodes, r, ok, measured);
    if (allometry.valid)
      for (std::size_t i = 0; i < n; ++i) {
        const double p = allometry.predict(i);
        if (ok[i] && !measured[i] && r[i] > p * rules.allometryMaxRatio) ok[i] = 0;
      }
  }
  const auto chains = detail::branchChains(nodes);
  if (rules.maxGrowthRatio > 0) setAsideGrowth(chains, measured, allometry, rules.maxGrowthRatio, r, ok);
  if (kept) *kept = ok;
  interpolateRejected(nodes, chains, ok, allometry, r);
  if (rules.medianWindow > 1) medianAlongBranches(chains, rules.medianWindow, r);
  if (rules.pipeModel) pipeAtForks(nodes, measured, r);
  if (rules.childNotThicker) taperAlongBranches(nodes, chains, ok, r);
  // 5. Not above the pipe law's bound.
  if (allometry.valid)
    for (std::size_t i = 0; i < n; ++i) {
      if (measured[i]) continue;
      const double p = allometry.predict(i);
      r[i] = std::min(r[i], p * rules.allometryMaxRatio);
    }
  return r;
}

}  // namespace treesketch::skeleton
