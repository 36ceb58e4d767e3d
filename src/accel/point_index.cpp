// Ball and k-nearest queries on nanoflann's k-d tree (single index, leaves of up to 10 points).
#include "treesketch/accel/point_index.h"

#include <algorithm>
#include <limits>
#include <nanoflann.hpp>
#include <string>
#include <utility>

#include "treesketch/util/error.h"

namespace treesketch::accel {

using geom::Vec3;

namespace {

struct Adaptor {
  std::vector<Vec3> pts;
  std::size_t kdtree_get_point_count() const { return pts.size(); }
  double kdtree_get_pt(std::size_t i, std::size_t dim) const { return pts[i][static_cast<int>(dim)]; }
  template <class Box>
  bool kdtree_get_bbox(Box&) const {
    return false;
  }
};

using KdTree =
    nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<double, Adaptor>, Adaptor, 3, std::uint32_t>;

// Leaf size of the tree: nanoflann's default. 16 (the skeleton graph's old setting) measured no
// different; 10 keeps the nearest-point answers of accel::CloudClosestPoint unchanged (the leaf size
// shapes the tree, and the tree decides between equally near points).
constexpr std::size_t kLeafSize = 10;

// The tree is asked for a slightly larger ball than the exact test accepts, so that its own
// rounding (a different summation from Eigen's) cannot drop a point that the exact test keeps.
constexpr double kSearchSlack = 1e-9;

}  // namespace

struct PointIndex::Impl {
  Adaptor data;
  std::unique_ptr<KdTree> tree;
  /// Candidates of the tree's ball search (per thread: one allocation, not one per query).
  static std::vector<std::pair<std::uint32_t, double>>& candidates() {
    thread_local std::vector<std::pair<std::uint32_t, double>> c;
    return c;
  }
  /// Calls hit(index, d2) for every point strictly inside the ball, in the tree's order.
  template <class Hit>
  void forEachInBall(const Vec3& centre, double radius, Hit&& hit) const {
    if (!tree || !(radius > 0) || !centre.allFinite()) return;
    const double r2 = radius * radius;
    auto& c = candidates();
    c.clear();
    nanoflann::SearchParams params;
    params.sorted = false;
    tree->radiusSearch(centre.data(), r2 * (1 + kSearchSlack), c, params);
    for (const auto& [i, approx] : c) {
      const double d2 = (data.pts[i] - centre).squaredNorm();
      if (d2 < r2) hit(i, d2);
    }
  }
};

PointIndex::PointIndex(std::vector<Vec3> points) : impl_(std::make_unique<Impl>()) {
  for (std::size_t i = 0; i < points.size(); ++i)
    if (!points[i].allFinite()) throw OptionsError("point index: point " + std::to_string(i) + " is NaN or infinite");
  if (points.size() >= std::numeric_limits<std::uint32_t>::max())
    throw OptionsError("point index: too many points (" + std::to_string(points.size()) + ")");
  impl_->data.pts = std::move(points);
  if (!impl_->data.pts.empty())
    impl_->tree = std::make_unique<KdTree>(3, impl_->data, nanoflann::KDTreeSingleIndexAdaptorParams(kLeafSize));
}
PointIndex::~PointIndex() = default;
PointIndex::PointIndex(PointIndex&&) noexcept = default;
PointIndex& PointIndex::operator=(PointIndex&&) noexcept = default;

std::size_t PointIndex::size() const { return impl_->data.pts.size(); }
const std::vector<Vec3>& PointIndex::points() const { return impl_->data.pts; }

void PointIndex::withinRadius(const Vec3& centre, double radius, std::vector<std::uint32_t>& out) const {
  out.clear();
  impl_->forEachInBall(centre, radius, [&](std::uint32_t i, double) { out.push_back(i); });
  std::sort(out.begin(), out.end());
}

std::vector<std::uint32_t> PointIndex::withinRadius(const Vec3& centre, double radius) const {
  std::vector<std::uint32_t> out;
  withinRadius(centre, radius, out);
  return out;
}

void PointIndex::withinRadiusByDistance(const Vec3& centre, double radius, std::vector<Neighbour>& out) const {
  out.clear();
  impl_->forEachInBall(centre, radius, [&](std::uint32_t i, double d2) { out.push_back(Neighbour{i, d2}); });
  std::sort(out.begin(), out.end(), [](const Neighbour& a, const Neighbour& b) {
    return a.distance2 < b.distance2 || (a.distance2 == b.distance2 && a.index < b.index);
  });
}

std::optional<Neighbour> PointIndex::nearest(const Vec3& query) const {
  if (!impl_->tree || !query.allFinite()) return std::nullopt;
  std::uint32_t idx = 0;
  double d2 = 0;
  if (impl_->tree->knnSearch(query.data(), 1, &idx, &d2) == 0) return std::nullopt;
  return Neighbour{idx, (impl_->data.pts[idx] - query).squaredNorm()};
}

std::vector<Neighbour> PointIndex::nearest(const Vec3& query, std::size_t k) const {
  std::vector<Neighbour> out;
  if (!impl_->tree || k == 0 || !query.allFinite()) return out;
  k = std::min(k, size());
  std::vector<std::uint32_t> idx(k);
  std::vector<double> d2(k);
  const std::size_t found = impl_->tree->knnSearch(query.data(), k, idx.data(), d2.data());
  out.resize(found);
  // Distances recomputed in double from the stored points (the tree accumulates the same terms
  // in another order): the exact distance of the point each answer names.
  for (std::size_t j = 0; j < found; ++j) out[j] = Neighbour{idx[j], (impl_->data.pts[idx[j]] - query).squaredNorm()};
  return out;
}

}  // namespace treesketch::accel
