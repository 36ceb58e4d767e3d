// Multi-scale covariance features of every point (classify/features.h): one k-nearest query per
// point at the largest scale, the smaller scales read from its nearest-first prefix.
#include "treesketch/classify/features.h"

#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>

#include "graph_features.h"
#include "treesketch/accel/point_index.h"
#include "treesketch/util/error.h"

namespace treesketch::classify {

namespace {

constexpr int kPerScale = 7;
constexpr int kPerNormalScale = 3;
constexpr std::uint32_t kNoNeighbour = 0xFFFFFFFFu;

/// The covariance features of one neighbourhood whose coordinate sums (relative to the query
/// point) are `sum` and `outer` over `k` points; `r` is the distance to its farthest point.
void scaleFeatures(const geom::Vec3& sum, const geom::Mat3& outer, int k, double r, double spacing,
                   const geom::Vec3& up, float* out, geom::Vec3* normal) {
  const geom::Vec3 mean = sum / k;
  geom::Mat3 cov = outer / k - mean * mean.transpose();
  Eigen::SelfAdjointEigenSolver<geom::Mat3> eig;
  eig.computeDirect(cov);
  const geom::Vec3 ev = eig.eigenvalues().cwiseMax(0.0);  // ascending
  const double l1 = std::max(ev[2], 1e-30), l2 = ev[1], l3 = ev[0];
  out[0] = static_cast<float>((l1 - l2) / l1);                               // linearity
  out[1] = static_cast<float>((l2 - l3) / l1);                               // planarity
  out[2] = static_cast<float>(l3 / l1);                                      // scattering
  out[3] = static_cast<float>(std::abs(eig.eigenvectors().col(2).dot(up)));  // principal axis up
  out[4] = static_cast<float>(std::abs(eig.eigenvectors().col(0).dot(up)));  // normal up
  out[5] = static_cast<float>(std::log(std::max(r, 1e-12) / spacing));       // density
  out[6] = static_cast<float>(mean.norm() / std::max(r, 1e-12));             // centroid offset
  if (normal) *normal = eig.eigenvectors().col(0);
}

/// How the unit normals summed as `scatter` (the sum of n n^T over `k` neighbours) turn: with
/// eigenvalues m1 >= m2 >= m3 of scatter / k (they add up to 1), the spread 1 - m1 (0 when every
/// normal agrees: one flat patch), the fan m2 - m3 (normals turning about one axis only: a
/// cylinder's bark) and the scatter m3 (normals turning every way: leaves of every orientation).
void normalTurn(const geom::Mat3& scatter, int k, float* out) {
  Eigen::SelfAdjointEigenSolver<geom::Mat3> eig;
  eig.computeDirect(scatter / k);
  const geom::Vec3 ev = eig.eigenvalues().cwiseMax(0.0);  // ascending
  const double total = std::max(ev.sum(), 1e-30);
  out[0] = static_cast<float>(1.0 - ev[2] / total);
  out[1] = static_cast<float>((ev[1] - ev[0]) / total);
  out[2] = static_cast<float>(ev[0] / total);
}

/// The normal features of point i at every scale of `scales` after the first (kPerNormalScale
/// each, into `out`): `lists` holds every point's neighbours, nearest first and itself first,
/// `stride` a point, ended early by kNoNeighbour.
void normalFeatures(const std::vector<geom::Vec3>& normals, const std::vector<std::uint32_t>& lists, std::size_t stride,
                    std::size_t i, const std::vector<int>& scales, float* out) {
  geom::Mat3 scatter = geom::Mat3::Zero();
  std::size_t scale = 1;
  int taken = 0;
  for (std::size_t j = 0; j < stride && scale < scales.size(); ++j) {
    const std::uint32_t k = lists[i * stride + j];
    const bool last = j + 1 == stride || lists[i * stride + j + 1] == kNoNeighbour;
    if (k == kNoNeighbour) break;
    scatter += normals[k] * normals[k].transpose();
    ++taken;
    for (; scale < scales.size() && (taken >= scales[scale] + 1 || last); ++scale)
      normalTurn(scatter, taken, out + (scale - 1) * kPerNormalScale);
  }
}

/// Keeps `nb`'s indices (nearest first) as point i's row of `lists`, padded with kNoNeighbour.
void keepNeighbours(const std::vector<accel::Neighbour>& nb, std::size_t i, std::size_t stride,
                    std::vector<std::uint32_t>& lists) {
  for (std::size_t j = 0; j < stride; ++j) lists[i * stride + j] = j < nb.size() ? nb[j].index : kNoNeighbour;
}

void checkOptions(const FeatureOptions& o) {
  if (o.scales.empty()) throw OptionsError("classify: no feature scales");
  for (std::size_t s = 0; s < o.scales.size(); ++s)
    if (o.scales[s] < 3 || (s > 0 && o.scales[s] <= o.scales[s - 1]))
      throw OptionsError("classify: feature scales must be increasing and at least 3 points");
  if (o.graphNeighbours < 1 || o.graphNeighbours > o.scales.back())
    throw OptionsError("classify: graph neighbours must be between 1 and the largest scale");
  if (!(o.coreSpacings >= 0) || !std::isfinite(o.coreSpacings))
    throw OptionsError("classify: core spacings must be 0 or more");
  if (!(o.minSpacingHeightFraction >= 0 && o.minSpacingHeightFraction < 1))
    throw OptionsError("classify: the least spacing must be a fraction of the height from 0 to below 1");
  for (std::size_t s = 0; s < o.coarseScales.size(); ++s)
    if (o.coarseScales[s] < 3 || (s > 0 && o.coarseScales[s] <= o.coarseScales[s - 1]))
      throw OptionsError("classify: coarse scales must be increasing and at least 3 points");
  if (!o.coarseScales.empty() && !(o.coarseHeightFraction > 0 && o.coarseHeightFraction < 1))
    throw OptionsError("classify: the coarse cube must be a fraction of the height between 0 and 1");
}

void checkCores(std::size_t cores, std::size_t points, const FeatureOptions& o) {
  if (cores < static_cast<std::size_t>(o.scales.back()) + 1)
    throw DegenerateInputError("classify: the cloud has " + std::to_string(points) + " points (" +
                               std::to_string(cores) + " after thinning); at least " +
                               std::to_string(o.scales.back() + 1) + " are needed");
}

/// Cuts `points` into cubes of side `size` and returns each non-empty cube's centroid; fills
/// `coreOf` (per point) and `coreSize` (per cube). size 0: every point is its own core.
std::vector<geom::Vec3> makeCores(const std::vector<geom::Vec3>& points, double size,
                                  std::vector<std::uint32_t>& coreOf, std::vector<std::uint32_t>& coreSize) {
  const std::size_t n = points.size();
  coreOf.resize(n);
  coreSize.clear();
  if (size <= 0) {
    for (std::size_t i = 0; i < n; ++i) coreOf[i] = static_cast<std::uint32_t>(i);
    coreSize.assign(n, 1);
    return points;
  }
  geom::BBox box;
  for (const auto& p : points) box.add(p);
  std::vector<std::pair<std::uint64_t, std::uint32_t>> keys(n);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 4096), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t i = r.begin(); i != r.end(); ++i) {
      const geom::Vec3 c = ((points[i] - box.min) / size).array().floor();
      const auto x = static_cast<std::uint64_t>(c.x()), y = static_cast<std::uint64_t>(c.y()),
                 z = static_cast<std::uint64_t>(c.z());
      keys[i] = {(x & 0x1FFFFF) << 42 | (y & 0x1FFFFF) << 21 | (z & 0x1FFFFF), static_cast<std::uint32_t>(i)};
    }
  });
  tbb::parallel_sort(keys.begin(), keys.end());
  std::vector<geom::Vec3> cores;
  for (std::size_t i = 0; i < n;) {
    std::size_t j = i;
    geom::Vec3 sum = geom::Vec3::Zero();
    for (; j < n && keys[j].first == keys[i].first; ++j) {
      sum += points[keys[j].second];
      coreOf[keys[j].second] = static_cast<std::uint32_t>(cores.size());
    }
    cores.push_back(sum / static_cast<double>(j - i));
    coreSize.push_back(static_cast<std::uint32_t>(j - i));
    i = j;
  }
  return cores;
}

/// The covariance features of point i of `index` at every scale of `scales` (kPerScale each, into
/// `out`); `nb` receives its neighbours, nearest first (itself included), and `normal` (when not
/// null) the normal of the first scale's neighbourhood.
void pointFeatures(const accel::PointIndex& index, std::uint32_t i, const std::vector<int>& scales, double unit,
                   const geom::Vec3& up, float* out, std::vector<accel::Neighbour>& nb, geom::Vec3* normal) {
  const geom::Vec3& p = index.point(i);
  nb = index.nearest(p, static_cast<std::size_t>(scales.back()) + 1);
  geom::Vec3 sum = geom::Vec3::Zero();
  geom::Mat3 outer = geom::Mat3::Zero();
  std::size_t scale = 0;
  int taken = 0;
  for (std::size_t j = 0; j < nb.size() && scale < scales.size(); ++j) {
    const geom::Vec3 d = index.point(nb[j].index) - p;
    sum += d;
    outer += d * d.transpose();
    ++taken;
    if (taken == scales[scale] + 1 || j + 1 == nb.size()) {
      // A cloud with fewer points than the scale: the larger scales repeat the whole cloud's.
      for (; scale < scales.size() && (taken >= scales[scale] + 1 || j + 1 == nb.size()); ++scale)
        scaleFeatures(sum, outer, taken, std::sqrt(nb[j].distance2), unit, up, out + scale * kPerScale,
                      scale == 0 ? normal : nullptr);
    }
  }
}

/// The normal features of every point (rows of `values`, `rowStride` apart, from `column`), once
/// every point's normal and neighbour list are known.
void normalFeaturesOfAll(const std::vector<geom::Vec3>& normals, const std::vector<std::uint32_t>& lists,
                         const std::vector<int>& scales, float* values, std::size_t rowStride, std::size_t column) {
  const std::size_t stride = static_cast<std::size_t>(scales.back()) + 1;
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, normals.size(), 1024),
                    [&](const tbb::blocked_range<std::size_t>& r) {
                      for (std::size_t i = r.begin(); i != r.end(); ++i)
                        normalFeatures(normals, lists, stride, i, scales, values + i * rowStride + column);
                    });
}

/// Number of normal feature columns for `scales` (none with one scale or less).
std::size_t normalColumns(const std::vector<int>& scales) {
  return scales.size() < 2 ? 0 : (scales.size() - 1) * kPerNormalScale;
}

/// Features of the coarse level: cubes of `fraction` of the height over the cores, their
/// covariance features at `scales` (columns from `column`) and their normal features (from
/// `normalColumn`, with o.normalFeatures), copied to every core of each cube.
void coarseFeatures(const std::vector<geom::Vec3>& cores, const FeatureOptions& o, const geom::Vec3& up, int column,
                    int normalColumn, FeatureTable& t) {
  if (o.coarseScales.empty()) return;
  const double size = o.coarseHeightFraction * t.treeHeight;
  std::vector<std::uint32_t> coarseOf, coarseSize;
  const std::vector<geom::Vec3> coarse = makeCores(cores, size, coarseOf, coarseSize);
  const accel::PointIndex index(coarse);
  const std::size_t covariance = o.coarseScales.size() * kPerScale;
  const std::size_t turn = o.normalFeatures ? normalColumns(o.coarseScales) : 0, per = covariance + turn;
  const std::size_t stride = static_cast<std::size_t>(o.coarseScales.back()) + 1;
  std::vector<float> values(coarse.size() * per);
  std::vector<geom::Vec3> normals(coarse.size());
  std::vector<std::uint32_t> lists(turn > 0 ? coarse.size() * stride : 0);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, coarse.size(), 256),
                    [&](const tbb::blocked_range<std::size_t>& r) {
                      std::vector<accel::Neighbour> nb;
                      for (std::size_t i = r.begin(); i != r.end(); ++i) {
                        pointFeatures(index, static_cast<std::uint32_t>(i), o.coarseScales, size, up,
                                      values.data() + i * per, nb, &normals[i]);
                        if (turn > 0) keepNeighbours(nb, i, stride, lists);
                      }
                    });
  if (turn > 0) normalFeaturesOfAll(normals, lists, o.coarseScales, values.data(), per, covariance);
  for (std::size_t i = 0; i < cores.size(); ++i) {
    const float* from = values.data() + coarseOf[i] * per;
    std::copy_n(from, covariance, t.values.data() + i * t.count + column);
    std::copy_n(from + covariance, turn, t.values.data() + i * t.count + normalColumn);
  }
}

/// Keeps core i's t.neighbourCount nearest neighbours of `nb` (itself left out; padded with
/// itself at distance 0 in a tiny cloud) as its row of the graph.
void keepGraphNeighbours(const std::vector<accel::Neighbour>& nb, std::size_t i, FeatureTable& t) {
  const int g = t.neighbourCount;
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
}

/// The median nearest-neighbour distance over up to ~20k evenly spread points. A point repeated at
/// the same position (a file written twice, returns rounded together) is not a neighbour: with
/// them the median was 0 on a cloud written twice.
double medianSpacing(const std::vector<geom::Vec3>& points) {
  constexpr std::size_t kLooked = 8;  // neighbours looked at for one at a distance
  const accel::PointIndex index(points);
  const std::size_t n = index.size(), step = std::max<std::size_t>(1, n / 20000);
  std::vector<double> d;
  for (std::size_t i = 0; i < n; i += step) {
    for (const auto& nb : index.nearest(index.point(static_cast<std::uint32_t>(i)), kLooked))
      if (nb.distance2 > 0) {
        d.push_back(std::sqrt(nb.distance2));
        break;
      }
  }
  std::nth_element(d.begin(), d.begin() + d.size() / 2, d.end());
  const double s = d.empty() ? 0.0 : d[d.size() / 2];
  return s > 0 ? s : 1e-6;
}

/// The extent of `points` along the up axis.
double heightRange(const std::vector<geom::Vec3>& points, geom::UpAxis up) {
  double lo = INFINITY, hi = -INFINITY;
  for (const auto& p : points) {
    lo = std::min(lo, geom::height(p, up));
    hi = std::max(hi, geom::height(p, up));
  }
  return points.empty() ? 0.0 : hi - lo;
}

/// Heights above the lowest core and the base's centre (the mean of the lowest 2 % of the height).
geom::Vec3 heightsAndBase(const std::vector<geom::Vec3>& cores, geom::UpAxis up, FeatureTable& t) {
  const std::size_t n = cores.size();
  double lo = INFINITY, hi = -INFINITY;
  for (const auto& p : cores) {
    lo = std::min(lo, geom::height(p, up));
    hi = std::max(hi, geom::height(p, up));
  }
  t.treeHeight = std::max(hi - lo, 1e-12);
  t.heights.resize(n);
  geom::Vec3 base = geom::Vec3::Zero();
  std::size_t baseCount = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const double h = geom::height(cores[i], up) - lo;
    t.heights[i] = static_cast<float>(h);
    if (h <= 0.02 * t.treeHeight) {
      base += cores[i];
      ++baseCount;
    }
  }
  return base / static_cast<double>(std::max<std::size_t>(baseCount, 1));
}

}  // namespace

std::vector<std::string> featureNames(const FeatureOptions& options) {
  static const char* per[kPerScale] = {"linearity", "planarity", "scattering",     "axis_up",
                                       "normal_up", "density",   "centroid_offset"};
  std::vector<std::string> names;
  for (int k : options.scales)
    for (const char* p : per) names.push_back(std::string(p) + "_k" + std::to_string(k));
  for (int k : options.coarseScales)
    for (const char* p : per) names.push_back(std::string(p) + "_coarse_k" + std::to_string(k));
  static const char* turn[kPerNormalScale] = {"normal_spread", "normal_fan", "normal_scatter"};
  if (options.normalFeatures) {
    for (std::size_t s = 1; s < options.scales.size(); ++s)
      for (const char* p : turn) names.push_back(std::string(p) + "_k" + std::to_string(options.scales[s]));
    for (std::size_t s = 1; s < options.coarseScales.size(); ++s)
      for (const char* p : turn)
        names.push_back(std::string(p) + "_coarse_k" + std::to_string(options.coarseScales[s]));
  }
  if (options.graphFeatures)
    for (const auto& name : detail::graphFeatureNames()) names.push_back(name);
  if (options.positionFeatures) {
    names.push_back("height");
    names.push_back("radial");
  }
  return names;
}

FeatureTable computeFeatures(const geom::PointCloud& cloud, geom::UpAxis up, const FeatureOptions& options) {
  checkOptions(options);
  checkCores(cloud.size(), cloud.size(), options);
  FeatureTable t;
  t.names = featureNames(options);
  t.count = static_cast<int>(t.names.size());
  t.measuredSpacing = medianSpacing(cloud.positions);
  t.spacing = std::max(t.measuredSpacing, options.minSpacingHeightFraction * heightRange(cloud.positions, up));
  const std::vector<geom::Vec3> cores =
      makeCores(cloud.positions, options.coreSpacings * t.spacing, t.coreOf, t.coreSize);
  const std::size_t n = cores.size();
  checkCores(n, cloud.size(), options);
  const accel::PointIndex index(cores);
  const geom::Vec3 base = heightsAndBase(cores, up, t);
  const geom::Vec3 upv = geom::upVector(up);
  const int g = options.graphNeighbours;
  t.values.assign(n * t.count, 0.0f);
  t.neighbourCount = g;
  t.neighbours.resize(n * g);
  t.neighbourDistances.resize(n * g);
  const std::size_t normalColumn = (options.scales.size() + options.coarseScales.size()) * kPerScale;
  const std::size_t fineTurn = options.normalFeatures ? normalColumns(options.scales) : 0;
  const std::size_t coarseTurn = options.normalFeatures ? normalColumns(options.coarseScales) : 0;
  const std::size_t graphColumn = normalColumn + fineTurn + coarseTurn;
  const std::size_t stride = static_cast<std::size_t>(options.scales.back()) + 1;
  std::vector<geom::Vec3> normals(n);
  std::vector<std::uint32_t> lists(fineTurn > 0 ? n * stride : 0);
  const std::size_t global = graphColumn + (options.graphFeatures ? detail::graphFeatureNames().size() : 0);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 1024), [&](const tbb::blocked_range<std::size_t>& r) {
    std::vector<accel::Neighbour> nb;
    for (std::size_t i = r.begin(); i != r.end(); ++i) {
      float* row = t.values.data() + i * t.count;
      pointFeatures(index, static_cast<std::uint32_t>(i), options.scales, t.spacing, upv, row, nb, &normals[i]);
      if (fineTurn > 0) keepNeighbours(nb, i, stride, lists);
      keepGraphNeighbours(nb, i, t);
      if (options.positionFeatures) {
        row[global] = static_cast<float>(t.heights[i] / t.treeHeight);
        const geom::Vec3 off = cores[i] - base;
        row[global + 1] = static_cast<float>((off - off.dot(upv) * upv).norm() / t.treeHeight);
      }
    }
  });
  if (fineTurn > 0) normalFeaturesOfAll(normals, lists, options.scales, t.values.data(), t.count, normalColumn);
  coarseFeatures(cores, options, upv, static_cast<int>(options.scales.size() * kPerScale),
                 static_cast<int>(normalColumn + fineTurn), t);
  if (options.graphFeatures) detail::graphFeatures(cores, 0.02, static_cast<int>(graphColumn), t);
  return t;
}

}  // namespace treesketch::classify
