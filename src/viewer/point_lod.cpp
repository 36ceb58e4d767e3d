#include "treesketch/viewer/point_lod.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <numeric>
#include <random>

namespace treesketch::viewer {

void PointLod::build(std::size_t count, std::uint64_t seed) {
  order_.resize(count);
  std::iota(order_.begin(), order_.end(), 0u);
  std::mt19937_64 rng(seed);
  std::shuffle(order_.begin(), order_.end(), rng);
  place_.resize(count);
  for (std::size_t i = 0; i < count; ++i) place_[order_[i]] = static_cast<std::uint32_t>(i);
  keptFrom_.clear();
  kept_.clear();
}

const std::vector<std::uint8_t>& PointLod::keptColors(const std::vector<render::Rgb>& colors) {
  if (keptFrom_.size() != colors.size() || colors.size() != order_.size()) {
    this->colors(colors, kept_);
    keptFrom_ = colors;
    return kept_;
  }
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, colors.size(), 1 << 16), [&](const auto& r) {
    for (std::size_t i = r.begin(); i != r.end(); ++i) {
      const render::Rgb& c = colors[i];
      if (c == keptFrom_[i]) continue;
      keptFrom_[i] = c;
      const std::size_t k = 3 * static_cast<std::size_t>(place_[i]);
      kept_[k] = c.r;
      kept_[k + 1] = c.g;
      kept_[k + 2] = c.b;
    }
  });
  return kept_;
}

void PointLod::positions(const geom::PointCloud& cloud, const geom::Vec3& origin, std::vector<float>& out) const {
  out.resize(3 * order_.size());
  for (std::size_t i = 0; i < order_.size(); ++i) {
    const geom::Vec3& p = cloud.positions[order_[i]];
    for (int k = 0; k < 3; ++k) out[3 * i + k] = static_cast<float>(p[k] - origin[k]);
  }
}

void PointLod::colors(const std::vector<render::Rgb>& colors, std::vector<std::uint8_t>& out) const {
  out.resize(3 * order_.size());
  // A gather in random order: bound by memory latency, so the threads' loads overlap.
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, order_.size(), 1 << 16), [&](const auto& r) {
    for (std::size_t i = r.begin(); i != r.end(); ++i) {
      const render::Rgb& c = colors[order_[i]];
      out[3 * i] = c.r;
      out[3 * i + 1] = c.g;
      out[3 * i + 2] = c.b;
    }
  });
}

std::size_t adaptPointBudget(std::size_t current, double frameMs, double targetMs, std::size_t minPoints,
                             std::size_t total) {
  std::size_t lo = std::min(minPoints, total);
  if (!(frameMs > 0) || !(targetMs > 0)) return std::clamp(current, lo, total);
  // Damped: at most halve or double per frame, so one slow frame does not empty the view.
  double k = std::clamp(targetMs / frameMs, 0.5, 2.0);
  double next = static_cast<double>(std::max<std::size_t>(current, 1)) * k;
  return std::clamp(static_cast<std::size_t>(next), lo, total);
}

}  // namespace treesketch::viewer
