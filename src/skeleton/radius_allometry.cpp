#include "skeleton/radius_allometry.h"

#include <algorithm>
#include <cmath>
#include <utility>

namespace treesketch::skeleton::detail {
namespace {

// The pipe model's exponent: cross-section area proportional to the carried length.
constexpr double kPipeExponent = 0.5;

double median(std::vector<double> v) {
  if (v.empty()) return 0;
  const std::size_t m = v.size() / 2;
  std::nth_element(v.begin(), v.begin() + m, v.end());
  return v[m];
}

}  // namespace

std::vector<double> carriedLengths(const std::vector<SkeletonNode>& nodes) {
  const std::size_t n = nodes.size();
  std::vector<double> own(n, 0.0);
  for (std::size_t i = 0; i < n; ++i)
    if (nodes[i].parent >= 0) own[i] = (nodes[i].position - nodes[nodes[i].parent].position).norm();
  std::vector<double> segments;
  for (std::size_t i = 0; i < n; ++i)
    if (nodes[i].parent >= 0) segments.push_back(own[i]);
  const double tip = std::max(median(segments), 1e-12);
  std::vector<double> carried(own);
  for (std::size_t i = n; i-- > 1;)
    if (nodes[i].parent >= 0) carried[nodes[i].parent] += carried[i];
  for (double& c : carried) c += tip;
  return carried;
}

void capByPipeModel(std::vector<SkeletonNode>& nodes, std::size_t from) {
  const std::vector<double> carried = carriedLengths(nodes);
  for (std::size_t i = from; i < nodes.size(); ++i) {
    const std::int32_t p = nodes[i].parent;
    if (p < 0) continue;
    double r = std::min(nodes[i].radius, nodes[p].radius);
    if (carried[p] > 0) r = std::min(r, nodes[p].radius * std::sqrt(carried[i] / carried[p]));
    nodes[i].radius = r;
  }
}

double Allometry::predict(std::size_t i) const { return std::exp(logA + b * std::log(carried[i])); }

Allometry fitAllometry(const std::vector<SkeletonNode>& nodes, const std::vector<double>& r,
                       const std::vector<char>& trusted, const std::vector<char>& stem) {
  Allometry a;
  a.carried = carriedLengths(nodes);
  a.b = kPipeExponent;
  const auto usable = [&](std::size_t i) { return r[i] > 0 && std::isfinite(r[i]); };
  std::vector<double> logScale;
  for (std::size_t i = 0; i < nodes.size(); ++i)
    if (stem[i] && usable(i)) logScale.push_back(std::log(r[i]) - a.b * std::log(a.carried[i]));
  // Without a measured stem: the fits of the lower trunk (the nodes carrying at least half the
  // tree), then any fits.
  const double most = a.carried.empty() ? 0.0 : *std::max_element(a.carried.begin(), a.carried.end());
  for (const double share : {0.5, 0.0}) {
    if (logScale.size() >= kMinAllometryAnchors) break;
    logScale.clear();
    for (std::size_t i = 0; i < nodes.size(); ++i)
      if (trusted[i] && usable(i) && a.carried[i] >= share * most)
        logScale.push_back(std::log(r[i]) - a.b * std::log(a.carried[i]));
  }
  if (logScale.size() < kMinAllometryAnchors) return a;
  a.logA = median(logScale);
  a.valid = true;
  return a;
}

std::vector<double> pipeRadii(const std::vector<SkeletonNode>& nodes, double rootRadius) {
  const std::vector<double> carried = carriedLengths(nodes);
  std::vector<double> r(nodes.size(), rootRadius);
  if (nodes.empty() || !(carried[0] > 0)) return r;
  for (std::size_t i = 0; i < nodes.size(); ++i) r[i] = rootRadius * std::pow(carried[i] / carried[0], kPipeExponent);
  return r;
}

}  // namespace treesketch::skeleton::detail
