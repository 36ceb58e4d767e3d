// Multi-scale covariance features of every point (classify/features.h): one k-nearest query per
// point at the largest scale, the smaller scales read from its nearest-first prefix.
#include "treesketch/classify/features.h"

#include <tbb/parallel_for.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>

#include "treesketch/accel/point_index.h"
#include "treesketch/util/error.h"

namespace treesketch::classify {

namespace {

constexpr int kPerScale = 7;

/// The covariance features of one neighbourhood whose coordinate sums (relative to the query
/// point) are `sum` and `outer` over `k` points; `r` is the distance to its farthest point.
void scaleFeatures(const geom::Vec3& sum, const geom::Mat3& outer, int k, double r, double spacing,
                   const geom::Vec3& up, float* out) {
  const geom::Vec3 mean = sum / k;
  geom::Mat3 cov = outer / k - mean * mean.transpose();
  Eigen::SelfAdjointEigenSolver<geom::Mat3> eig;
  eig.computeDirect(cov);
  const geom::Vec3 ev = eig.eigenvalues().cwiseMax(0.0);  // ascending
  const double l1 = std::max(ev[2], 1e-30), l2 = ev[1], l3 = ev[0];
  out[0] = static_cast<float>((l1 - l2) / l1);                                  // linearity
  out[1] = static_cast<float>((l2 - l3) / l1);                                  // planarity
  out[2] = static_cast<float>(l3 / l1);                                         // scattering
  out[3] = static_cast<float>(std::abs(eig.eigenvectors().col(2).dot(up)));     // principal axis up
  out[4] = static_cast<float>(std::abs(eig.eigenvectors().col(0).dot(up)));     // normal up
  out[5] = static_cast<float>(std::log(std::max(r, 1e-12) / spacing));          // density
  out[6] = static_cast<float>(mean.norm() / std::max(r, 1e-12));                // centroid offset
}

void checkOptions(const FeatureOptions& o, std::size_t points) {
  if (o.scales.empty()) throw OptionsError("classify: no feature scales");
  for (std::size_t s = 0; s < o.scales.size(); ++s)
    if (o.scales[s] < 3 || (s > 0 && o.scales[s] <= o.scales[s - 1]))
      throw OptionsError("classify: feature scales must be increasing and at least 3 points");
  if (o.graphNeighbours < 1 || o.graphNeighbours > o.scales.back())
    throw OptionsError("classify: graph neighbours must be between 1 and the largest scale");
  if (points < static_cast<std::size_t>(o.scales.back()) + 1)
    throw DegenerateInputError("classify: the cloud has " + std::to_string(points) + " points; at least " +
                               std::to_string(o.scales.back() + 1) + " are needed");
}

/// The median nearest-neighbour distance over up to ~20k evenly spread points.
double medianSpacing(const accel::PointIndex& index) {
  const std::size_t n = index.size(), step = std::max<std::size_t>(1, n / 20000);
  std::vector<double> d;
  for (std::size_t i = 0; i < n; i += step) {
    auto nb = index.nearest(index.point(static_cast<std::uint32_t>(i)), 2);
    if (nb.size() == 2) d.push_back(std::sqrt(nb[1].distance2));
  }
  std::nth_element(d.begin(), d.begin() + d.size() / 2, d.end());
  const double s = d.empty() ? 0.0 : d[d.size() / 2];
  return s > 0 ? s : 1e-6;
}

/// Heights above the lowest point and the base's centre (the mean of the lowest 2 % of the height).
geom::Vec3 heightsAndBase(const geom::PointCloud& cloud, geom::UpAxis up, FeatureTable& t) {
  const std::size_t n = cloud.size();
  double lo = INFINITY, hi = -INFINITY;
  for (const auto& p : cloud.positions) {
    lo = std::min(lo, geom::height(p, up));
    hi = std::max(hi, geom::height(p, up));
  }
  t.treeHeight = std::max(hi - lo, 1e-12);
  t.heights.resize(n);
  geom::Vec3 base = geom::Vec3::Zero();
  std::size_t baseCount = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const double h = geom::height(cloud.positions[i], up) - lo;
    t.heights[i] = static_cast<float>(h);
    if (h <= 0.02 * t.treeHeight) {
      base += cloud.positions[i];
      ++baseCount;
    }
  }
  return base / static_cast<double>(std::max<std::size_t>(baseCount, 1));
}

}  // namespace

std::vector<std::string> featureNames(const FeatureOptions& options) {
  static const char* per[kPerScale] = {"linearity",   "planarity", "scattering", "axis_up",
                                       "normal_up",   "density",   "centroid_offset"};
  std::vector<std::string> names;
  for (int k : options.scales)
    for (const char* p : per) names.push_back(std::string(p) + "_k" + std::to_string(k));
  names.push_back("height");
  names.push_back("radial");
  return names;
}

FeatureTable computeFeatures(const geom::PointCloud& cloud, geom::UpAxis up, const FeatureOptions& options) {
  checkOptions(options, cloud.size());
  FeatureTable t;
  t.names = featureNames(options);
  t.count = static_cast<int>(t.names.size());
  const std::size_t n = cloud.size();
  const accel::PointIndex index(cloud.positions);
  t.spacing = medianSpacing(index);
  const geom::Vec3 base = heightsAndBase(cloud, up, t);
  const geom::Vec3 upv = geom::upVector(up);
  const int kMax = options.scales.back(), g = options.graphNeighbours;
  t.values.assign(n * t.count, 0.0f);
  t.neighbourCount = g;
  t.neighbours.resize(n * g);
  t.neighbourDistances.resize(n * g);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 1024), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t i = r.begin(); i != r.end(); ++i) {
      const geom::Vec3& p = cloud.positions[i];
      const auto nb = index.nearest(p, static_cast<std::size_t>(kMax) + 1);
      float* row = t.values.data() + i * t.count;
      geom::Vec3 sum = geom::Vec3::Zero();
      geom::Mat3 outer = geom::Mat3::Zero();
      std::size_t scale = 0;
      int taken = 0;
      for (std::size_t j = 0; j < nb.size() && scale < options.scales.size(); ++j) {
        const geom::Vec3 d = index.point(nb[j].index) - p;
        sum += d;
        outer += d * d.transpose();
        ++taken;
        if (taken == options.scales[scale] + 1 || j + 1 == nb.size()) {
          scaleFeatures(sum, outer, taken, std::sqrt(nb[j].distance2), t.spacing, upv, row + scale * kPerScale);
          ++scale;
        }
      }
      int kept = 0;
      for (std::size_t j = 0; j < nb.size() && kept < g; ++j) {
        if (nb[j].index == i) continue;
        t.neighbours[i * g + kept] = nb[j].index;
        t.neighbourDistances[i * g + kept] = static_cast<float>(std::sqrt(nb[j].distance2));
        ++kept;
      }
      for (; kept < g; ++kept) {
        t.neighbours[i * g + kept] = static_cast<std::uint32_t>(i);
        t.neighbourDistances[i * g + kept] = 0.0f;
      }
      const std::size_t global = options.scales.size() * kPerScale;
      row[global] = static_cast<float>(t.heights[i] / t.treeHeight);
      const geom::Vec3 off = p - base;
      row[global + 1] = static_cast<float>((off - off.dot(upv) * upv).norm() / t.treeHeight);
    }
  });
  return t;
}

}  // namespace treesketch::classify
