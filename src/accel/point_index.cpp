// Ball and k-nearest queries on nanoflann's k-d tree.
//
// nanoflann builds the tree and answers nearest-point queries. Ball queries walk the tree's nodes
// here instead of calling its radiusSearch, which tests every point of every leaf it meets and
// returns the hits in traversal order. The skeleton's balls hold hundreds of points and must come
// in increasing index order: here leaves wholly inside the ball are taken without a test, and each
// leaf's points are stored contiguously by increasing index, so an answer is a few increasing runs
// to merge rather than a list to sort. Measured on the leaf-plane test of the 1 M-point leafy
// benchmark scan (42k balls, 11M hits; wall time on two busy cores): radiusSearch then a sort
// 3.2-3.9 s, this 0.6-0.9 s, fit::CloudIndex's grid (answers in its cell order) 0.5-0.8 s.
// After the build the points are stored in leaf order and the tree's permutation is the identity.
#include "treesketch/accel/point_index.h"

#include <algorithm>
#include <limits>
#include <nanoflann.hpp>
#include <numeric>
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
using Node = KdTree::Node;

// The tree's internals this file walks; nanoflann 1.5 renamed them with a trailing underscore
// (templates, so that only the spelling present is looked up).
template <class Tree>
auto& permutation(Tree& t) {
  if constexpr (requires { t.vAcc_; })
    return t.vAcc_;
  else
    return t.vAcc;
}
template <class Tree>
const Node* rootNode(const Tree& t) {
  if constexpr (requires { t.root_node_; })
    return t.root_node_;
  else
    return t.root_node;
}
template <class Tree>
const auto& rootBox(const Tree& t) {
  if constexpr (requires { t.root_bbox_; })
    return t.root_bbox_;
  else
    return t.root_bbox;
}

// A node is pruned when its box is farther than the radius, and taken whole when its farthest
// corner is nearer, each with this relative margin on the squared radius: far above the rounding
// of the box distances, so that the decision agrees with the exact test of every point inside.
constexpr double kBoxMargin = 1e-12;

struct Box {
  double lo[3], hi[3];
};

// Hits of one ball query: increasing runs (one per leaf met), merged at the end.
struct BallScratch {
  std::vector<std::size_t> runs;  ///< start of each run in the output
  std::vector<std::uint32_t> merged;
};
BallScratch& ballScratch() {
  thread_local BallScratch s;
  return s;
}

// Merges the increasing runs of `out` starting at `runs` into one increasing list (pairwise).
void mergeRuns(std::vector<std::uint32_t>& out, std::vector<std::size_t>& runs, std::vector<std::uint32_t>& tmp) {
  runs.push_back(out.size());
  while (runs.size() > 2) {
    tmp.resize(out.size());
    std::size_t kept = 0;
    for (std::size_t r = 0; r + 1 < runs.size(); r += 2) {
      const std::size_t a = runs[r], b = runs[r + 1], c = r + 2 < runs.size() ? runs[r + 2] : runs[r + 1];
      std::merge(out.begin() + a, out.begin() + b, out.begin() + b, out.begin() + c, tmp.begin() + a);
      runs[kept++] = a;
    }
    runs[kept++] = out.size();
    runs.resize(kept);
    out.swap(tmp);
  }
}

}  // namespace

struct PointIndex::Impl {
  Adaptor data;                      ///< the points in leaf order
  std::vector<std::uint32_t> ids;    ///< input index of each stored point; increasing within a leaf
  std::vector<std::uint32_t> slots;  ///< stored position of each input index (inverse of ids)
  std::unique_ptr<KdTree> tree;

  void build(std::vector<Vec3> points, std::size_t leafSize);
  void ball(const Node* node, Box box, const Vec3& c, double r2, bool inside, std::vector<std::uint32_t>& out,
            std::vector<std::size_t>& runs) const;
  /// The input indices of the points inside the ball, as increasing runs in `out`, one run per
  /// leaf met (`runs`: their starts).
  void ballRuns(const Vec3& centre, double radius, std::vector<std::uint32_t>& out,
                std::vector<std::size_t>& runs) const;
};

void PointIndex::Impl::build(std::vector<Vec3> points, std::size_t leafSize) {
  data.pts = std::move(points);
  tree = std::make_unique<KdTree>(3, data, nanoflann::KDTreeSingleIndexAdaptorParams(leafSize));
  // Leaf order, each leaf's points by increasing input index; then the stored points follow it
  // and the tree's permutation becomes the identity (the leaves keep their point sets).
  auto& perm = permutation(*tree);
  ids = perm;
  auto sortLeaves = [&](auto&& self, const Node* n) -> void {
    if (!n->child1) {
      std::sort(ids.begin() + n->node_type.lr.left, ids.begin() + n->node_type.lr.right);
      return;
    }
    self(self, n->child1);
    self(self, n->child2);
  };
  sortLeaves(sortLeaves, rootNode(*tree));
  std::vector<Vec3> ordered(ids.size());
  slots.resize(ids.size());
  for (std::size_t i = 0; i < ids.size(); ++i) {
    ordered[i] = data.pts[ids[i]];
    slots[ids[i]] = static_cast<std::uint32_t>(i);
  }
  data.pts = std::move(ordered);
  std::iota(perm.begin(), perm.end(), std::uint32_t{0});
}

void PointIndex::Impl::ball(const Node* n, Box box, const Vec3& c, double r2, bool inside,
                            std::vector<std::uint32_t>& out, std::vector<std::size_t>& runs) const {
  if (!inside) {
    double near = 0, far = 0;
    for (int a = 0; a < 3; ++a) {
      const double lo = box.lo[a] - c[a], hi = box.hi[a] - c[a];
      if (lo > 0)
        near += lo * lo;
      else if (hi < 0)
        near += hi * hi;
      const double m = std::max(-lo, hi);
      far += m * m;
    }
    if (near > r2 * (1 + kBoxMargin)) return;
    inside = far < r2 * (1 - kBoxMargin);
  }
  if (!n->child1) {
    const std::size_t left = n->node_type.lr.left, right = n->node_type.lr.right;
    runs.push_back(out.size());
    if (inside) {
      out.insert(out.end(), ids.begin() + left, ids.begin() + right);
    } else {
      // Branch-free: whether a point of a leaf the sphere cuts is inside is a coin flip.
      const std::size_t start = out.size();
      out.resize(start + (right - left));
      std::uint32_t* dst = out.data() + start;
      std::size_t kept = 0;
      for (std::size_t i = left; i < right; ++i) {
        dst[kept] = ids[i];
        kept += (data.pts[i] - c).squaredNorm() < r2;
      }
      out.resize(start + kept);
    }
    return;
  }
  const int f = n->node_type.sub.divfeat;
  Box low = box, high = box;
  low.hi[f] = n->node_type.sub.divlow;  // the largest coordinate of the low child's points
  high.lo[f] = n->node_type.sub.divhigh;
  ball(n->child1, low, c, r2, inside, out, runs);
  ball(n->child2, high, c, r2, inside, out, runs);
}

void PointIndex::Impl::ballRuns(const Vec3& centre, double radius, std::vector<std::uint32_t>& out,
                                std::vector<std::size_t>& runs) const {
  out.clear();
  runs.clear();
  if (!tree || !(radius > 0) || !centre.allFinite()) return;
  Box box;
  for (int a = 0; a < 3; ++a) {
    box.lo[a] = rootBox(*tree)[a].low;
    box.hi[a] = rootBox(*tree)[a].high;
  }
  ball(rootNode(*tree), box, centre, radius * radius, false, out, runs);
}

PointIndex::PointIndex(std::vector<Vec3> points, const PointIndexOptions& options) : impl_(std::make_unique<Impl>()) {
  for (std::size_t i = 0; i < points.size(); ++i)
    if (!points[i].allFinite()) throw OptionsError("point index: point " + std::to_string(i) + " is NaN or infinite");
  if (points.size() >= std::numeric_limits<std::uint32_t>::max())
    throw OptionsError("point index: too many points (" + std::to_string(points.size()) + ")");
  if (options.leafSize < 1) throw OptionsError("point index: leafSize must be >= 1");
  if (!points.empty()) impl_->build(std::move(points), options.leafSize);
}
PointIndex::~PointIndex() = default;
PointIndex::PointIndex(PointIndex&&) noexcept = default;
PointIndex& PointIndex::operator=(PointIndex&&) noexcept = default;

std::size_t PointIndex::size() const { return impl_->ids.size(); }

const Vec3& PointIndex::point(std::uint32_t index) const { return impl_->data.pts[impl_->slots[index]]; }

void PointIndex::withinRadius(const Vec3& centre, double radius, std::vector<std::uint32_t>& out) const {
  BallScratch& s = ballScratch();
  impl_->ballRuns(centre, radius, out, s.runs);
  mergeRuns(out, s.runs, s.merged);
}

std::vector<std::uint32_t> PointIndex::withinRadius(const Vec3& centre, double radius) const {
  std::vector<std::uint32_t> out;
  withinRadius(centre, radius, out);
  return out;
}

void PointIndex::withinRadiusByDistance(const Vec3& centre, double radius, std::vector<Neighbour>& out) const {
  thread_local std::vector<std::uint32_t> hits;
  impl_->ballRuns(centre, radius, hits, ballScratch().runs);
  out.clear();
  for (std::uint32_t i : hits) out.push_back(Neighbour{i, (point(i) - centre).squaredNorm()});
  std::sort(out.begin(), out.end(), [](const Neighbour& a, const Neighbour& b) {
    return a.distance2 < b.distance2 || (a.distance2 == b.distance2 && a.index < b.index);
  });
}

std::optional<Neighbour> PointIndex::nearest(const Vec3& query) const {
  if (!impl_->tree || !query.allFinite()) return std::nullopt;
  std::uint32_t slot = 0;
  double d2 = 0;
  if (impl_->tree->knnSearch(query.data(), 1, &slot, &d2) == 0) return std::nullopt;
  // Distances recomputed in double from the stored point (the tree sums the same terms in another
  // order): the exact distance of the point the answer names.
  return Neighbour{impl_->ids[slot], (impl_->data.pts[slot] - query).squaredNorm()};
}

std::vector<Neighbour> PointIndex::nearest(const Vec3& query, std::size_t k) const {
  std::vector<Neighbour> out;
  if (!impl_->tree || k == 0 || !query.allFinite()) return out;
  k = std::min(k, size());
  std::vector<std::uint32_t> slot(k);
  std::vector<double> d2(k);
  const std::size_t found = impl_->tree->knnSearch(query.data(), k, slot.data(), d2.data());
  out.resize(found);
  for (std::size_t j = 0; j < found; ++j)
    out[j] = Neighbour{impl_->ids[slot[j]], (impl_->data.pts[slot[j]] - query).squaredNorm()};
  return out;
}

}  // namespace treesketch::accel
