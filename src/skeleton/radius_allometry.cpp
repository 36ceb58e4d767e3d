#include "skeleton/radius_allometry.h"

#include <algorithm>
#include <cmath>

namespace treesketch::skeleton::detail {
namespace {

// Fewer trusted fits than this cannot pin down a slope.
constexpr std::size_t kMinFits = 12;
// The slope is kept within what tree architecture allows: 0.25 (long, thin, whip-like growth) to
// 0.75 (stout, short-branched); the pipe model's 0.5 in between.
constexpr double kMinSlope = 0.25, kMaxSlope = 0.75;
// Tukey biweight tuning constant (95 % efficiency for normal residuals) and iterations.
constexpr double kTukey = 4.685;
constexpr int kIterations = 10;

double median(std::vector<double> v) {
  if (v.empty()) return 0;
  const std::size_t m = v.size() / 2;
  std::nth_element(v.begin(), v.begin() + m, v.end());
  return v[m];
}

/// Length carried by each node: its own segment (from its parent) and every segment above it,
/// plus the median segment (a tip's wood goes on a little past its last node).
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

}  // namespace

double Allometry::predict(std::size_t i) const { return std::exp(logA + b * std::log(carried[i])); }

Allometry fitAllometry(const std::vector<SkeletonNode>& nodes, const std::vector<double>& r,
                       const std::vector<char>& trusted) {
  Allometry a;
  a.carried = carriedLengths(nodes);
  std::vector<double> x, y;
  for (std::size_t i = 0; i < nodes.size(); ++i)
    if (trusted[i] && r[i] > 0 && std::isfinite(r[i])) {
      x.push_back(std::log(a.carried[i]));
      y.push_back(std::log(r[i]));
    }
  if (x.size() < kMinFits) return a;
  std::vector<double> w(x.size(), 1.0), res(x.size());
  for (int it = 0; it < kIterations; ++it) {
    double sw = 0, sx = 0, sy = 0;
    for (std::size_t k = 0; k < x.size(); ++k) {
      sw += w[k];
      sx += w[k] * x[k];
      sy += w[k] * y[k];
    }
    if (!(sw > 0)) break;
    const double mx = sx / sw, my = sy / sw;
    double sxx = 0, sxy = 0;
    for (std::size_t k = 0; k < x.size(); ++k) {
      sxx += w[k] * (x[k] - mx) * (x[k] - mx);
      sxy += w[k] * (x[k] - mx) * (y[k] - my);
    }
    a.b = std::clamp(sxx > 0 ? sxy / sxx : 0.5, kMinSlope, kMaxSlope);
    for (std::size_t k = 0; k < x.size(); ++k) res[k] = y[k] - a.b * x[k];
    a.logA = median(res);  // robust intercept for the clamped slope
    for (std::size_t k = 0; k < x.size(); ++k) res[k] = std::abs(res[k] - a.logA);
    const double scale = std::max(1.4826 * median(res), 1e-6);
    for (std::size_t k = 0; k < x.size(); ++k) {
      const double u = res[k] / (kTukey * scale);
      w[k] = u < 1 ? (1 - u * u) * (1 - u * u) : 0.0;
    }
  }
  a.valid = true;
  return a;
}

void nonIncreasingFit(std::vector<double>& values, const std::vector<double>& weights) {
  struct Block {
    double mean, weight;
    std::size_t count;
  };
  std::vector<Block> blocks;
  for (std::size_t k = 0; k < values.size(); ++k) {
    blocks.push_back({values[k], weights[k], 1});
    // Pool while a block is above the one before it (the sequence must not rise).
    while (blocks.size() > 1 && blocks.back().mean > blocks[blocks.size() - 2].mean) {
      const Block b = blocks.back();
      blocks.pop_back();
      Block& a = blocks.back();
      const double w = a.weight + b.weight;
      a.mean = (a.mean * a.weight + b.mean * b.weight) / w;
      a.weight = w;
      a.count += b.count;
    }
  }
  std::size_t k = 0;
  for (const Block& b : blocks)
    for (std::size_t j = 0; j < b.count; ++j) values[k++] = b.mean;
}

}  // namespace treesketch::skeleton::detail
