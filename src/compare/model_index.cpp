// Signed distances from points to a cylinder model: a piece's own (the frustum in the half-plane
// through its axis) and the union's, through a bounding-volume hierarchy over the pieces' boxes.
#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <memory>
#include <numeric>
#include <string>
#include <utility>

#include "treesketch/compare/model_fit.h"
#include "treesketch/util/error.h"

namespace treesketch::compare {

using geom::Vec3;

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

/// Squared distance in the (axial t, radial ρ) half-plane from (t, ρ) to the segment a→b.
double segmentDistance2dSquared(double t, double rho, double at, double arho, double bt, double brho) {
  const double et = bt - at, er = brho - arho;
  const double wt = t - at, wr = rho - arho;
  const double ee = et * et + er * er;
  const double s = ee > 0 ? std::clamp((wt * et + wr * er) / ee, 0.0, 1.0) : 0.0;
  const double dt = wt - s * et, dr = wr - s * er;
  return dt * dt + dr * dr;
}

/// A frustum's frame, computed once (CylinderModelIndex): signedDistance's arithmetic, step for
/// step, so its values are the same to the last bit.
struct Frame {
  Vec3 start, u;  // u: the unit axis
  double len = 0, r0 = 0, r1 = 0;
  bool openStart = false, openEnd = false;

  Frame(const geom::ModelCylinder& c, bool open0, bool open1) : start(c.start), r0(c.startRadius), r1(c.endRadius) {
    const Vec3 d = c.end - c.start;
    len = d.norm();
    u = d / len;
    openStart = open0;
    openEnd = open1;
  }
  double signedDistance(const Vec3& p) const {
    const Vec3 w = p - start;
    const double t = w.dot(u);
    const double rho = (w - t * u).norm();
    // The smallest of three distances is the root of the smallest square (the rounded square
    // root never decreases), one root instead of three.
    const double cap0 = segmentDistance2dSquared(t, rho, 0, 0, 0, r0);
    const double cap1 = segmentDistance2dSquared(t, rho, len, 0, len, r1);
    const double side = segmentDistance2dSquared(t, rho, 0, r0, len, r1);
    const bool inside = t >= 0 && t <= len && rho <= r0 + (r1 - r0) * (t / len);
    if (!inside) return std::sqrt(std::min({cap0, cap1, side}));
    return -std::sqrt(std::min({openStart ? kInf : cap0, openEnd ? kInf : cap1, side}));
  }
};

}  // namespace

double signedDistance(const Vec3& p, const geom::ModelCylinder& c, bool openStart, bool openEnd) {
  // A frustum is a solid of revolution: in the half-plane through its axis and p it is the
  // trapezoid (0,0) (0,r0) (L,r1) (L,0), whose boundary (apart from the axis, which is interior)
  // is the two caps and the slanted side. The closest surface point lies in that half-plane.
  const Vec3 d = c.end - c.start;
  const double len = d.norm();
  if (!(len > 0)) return kInf;
  const Vec3 u = d / len;
  const Vec3 w = p - c.start;
  const double t = w.dot(u);
  const double rho = (w - t * u).norm();
  const double r0 = c.startRadius, r1 = c.endRadius;
  // Not std::hypot: nothing overflows at tree scales, and its care made the whole measure 1.5×
  // slower (bench_model_fit).
  const double cap0 = std::sqrt(segmentDistance2dSquared(t, rho, 0, 0, 0, r0));
  const double cap1 = std::sqrt(segmentDistance2dSquared(t, rho, len, 0, len, r1));
  const double side = std::sqrt(segmentDistance2dSquared(t, rho, 0, r0, len, r1));
  const bool inside = t >= 0 && t <= len && rho <= r0 + (r1 - r0) * (t / len);
  if (!inside) return std::min({cap0, cap1, side});
  // Inside, an open cap (joined to the next piece) is no surface: the depth is to the rest.
  return -std::min({openStart ? kInf : cap0, openEnd ? kInf : cap1, side});
}

double signedDistance(const Vec3& p, const geom::ModelCylinder& c) { return signedDistance(p, c, false, false); }

std::vector<std::array<bool, 2>> jointCaps(const geom::CylinderModel& model) {
  // Joints: a piece that starts where its parent ends (a chain of segments, a fork) joins it
  // there, and the two caps at the joint lie inside the union. Within a tenth of the radius, for
  // tables that round their coordinates (TreeQSM's text export keeps 0.1 mm).
  std::vector<std::array<bool, 2>> open(model.size(), {false, false});
  for (std::size_t i = 0; i < model.size(); ++i) {
    const geom::ModelCylinder& c = model.cylinders[i];
    if (c.parent < 0 || static_cast<std::size_t>(c.parent) == i || c.parent >= static_cast<std::int64_t>(model.size()))
      continue;
    const geom::ModelCylinder& p = model.cylinders[c.parent];
    if (p.length() > 0 && (c.start - p.end).norm() <= 0.1 * std::max(c.startRadius, p.endRadius)) {
      open[i][0] = true;
      open[c.parent][1] = true;
    }
  }
  return open;
}

// ---- the hierarchy ----------------------------------------------------------------------------

struct CylinderModelIndex::Impl {
  struct Node {
    geom::BBox box;
    std::uint32_t first = 0, count = 0;  // leaf: range in `order`; inner: count = 0
    std::uint32_t left = 0, right = 0;   // inner: children
  };
  std::vector<geom::ModelCylinder> pieces;
  std::vector<std::array<bool, 2>> open;  // per piece: start cap, end cap joined to a neighbour
  std::vector<std::int64_t> modelIndex;   // piece → index in the model
  std::vector<geom::BBox> boxes;
  std::vector<std::uint32_t> order;  // pieces, grouped by leaf
  std::vector<Node> nodes;
  std::vector<Frame> frames;            // per slot (position in `order`): its piece's frame
  std::vector<std::int64_t> slotPiece;  // per slot: its piece's index in the model
  std::vector<geom::BBox> slotBox;      // per slot: its piece's box
  /// An entry of the search's stack: a node and its squared distance from the point asked about
  /// (squaredBoxDistance).
  struct Pending {
    std::uint32_t node;
    double bound;
  };

  static constexpr std::uint32_t kLeafSize = 4;

  // The cells (see "the cells" below): a cube's pieces, remembered once asked for.
  static constexpr std::size_t kCellPieces = 8;      // more: the cell is left to the search
  static constexpr std::size_t kMinCellPieces = 16;  // smaller models: no cells (a short search)
  static constexpr double kCellRadii = 2;            // a cell's edge: this many median radii (or more)
  static constexpr double kCellsPerPiece = 128;      // at most this many cells per piece (+ kExtraCells)
  static constexpr double kExtraCells = 4096;
  static constexpr double kMaxCells = 1 << 19;           // in all (a few tens of MB at most)
  static constexpr std::uint64_t kCellRange = 1u << 21;  // cells per axis (21 bits of the key each)
  static constexpr std::uint64_t kNoKey = ~std::uint64_t{0};
  enum : std::uint8_t { kUnknown, kFilling, kReady, kCrowded };
  struct Cell {
    std::atomic<std::uint8_t> state{kUnknown};
    std::uint8_t count = 0;
    std::uint32_t slot[kCellPieces] = {};
  };
  double cellSize = 0;
  Vec3 cellOrigin = Vec3::Zero();
  std::vector<std::uint64_t> cellKeys;   // open addressing: kNoKey where free
  std::vector<std::uint32_t> cellOfKey;  // per entry of cellKeys: its cell
  std::unique_ptr<Cell[]> cells;

  std::uint32_t build(std::uint32_t first, std::uint32_t count, const std::vector<Vec3>& centres) {
    const auto id = static_cast<std::uint32_t>(nodes.size());
    nodes.emplace_back();
    geom::BBox box, centreBox;
    for (std::uint32_t i = first; i < first + count; ++i) {
      box.add(boxes[order[i]]);
      centreBox.add(centres[order[i]]);
    }
    nodes[id].box = box;
    if (count <= kLeafSize) {
      nodes[id].first = first;
      nodes[id].count = count;
      return id;
    }
    // Median split along the longest axis of the centres' box: balanced, so the depth is
    // log2(n / kLeafSize) whatever the layout (a tree's pieces are far from uniform in space).
    int axis = 0;
    centreBox.extent().maxCoeff(&axis);
    const std::uint32_t half = count / 2;
    std::nth_element(order.begin() + first, order.begin() + first + half, order.begin() + first + count,
                     [&](std::uint32_t a, std::uint32_t b) { return centres[a][axis] < centres[b][axis]; });
    const std::uint32_t left = build(first, half, centres);
    const std::uint32_t right = build(first + half, count - half, centres);
    nodes[id].left = left;
    nodes[id].right = right;
    return id;
  }

  /// The squared distance from p to `box`, 0 inside it. Its root (rootBound) is a lower bound of
  /// the signed distance from p to anything inside the box; -inf inside (a piece there may hold p).
  static double squaredBoxDistance(const Vec3& p, const geom::BBox& box) {
    const Vec3 below = (box.min - p).cwiseMax(0.0);
    const Vec3 above = (p - box.max).cwiseMax(0.0);
    return below.squaredNorm() + above.squaredNorm();
  }
  static double rootBound(double d2) { return d2 > 0 ? std::sqrt(d2) : -kInf; }
  /// rootBound(d2) >= v, mostly without the root: where d2 lies clearly above or below v² the
  /// answer is plain; near v² (or at extreme magnitudes) the rounded root decides, as it would.
  static bool boundAtLeast(double d2, double v) {
    if (!(d2 > 0)) return false;
    if (v <= 0) return true;
    if (v > 1e-100 && v < 1e100) {
      const double v2 = v * v;
      if (d2 >= v2 * (1 + 1e-12)) return true;
      if (d2 < v2 * (1 - 1e-12)) return false;
    }
    return std::sqrt(d2) >= v;
  }
  /// rootBound(a) < rootBound(b), the same way.
  static bool boundBelow(double a, double b) {
    if (!(b > 0)) return false;
    if (!(a > 0)) return true;
    if (a >= b) return false;
    if (b > 1e-200 && a < b * (1 - 1e-12)) return true;
    return std::sqrt(a) < std::sqrt(b);
  }
  /// Whether the piece in `slot` lies more than `limit` + `tol` from p (outside its box by that
  /// much), so its signed distance exceeds `limit` whatever the rounding (`tol`: far above it) and
  /// it need not be measured.
  bool pieceBeyond(const Vec3& p, std::uint32_t slot, double limit, double tol) const {
    const geom::BBox& box = slotBox[slot];
    const Vec3 below = (box.min - p).cwiseMax(0.0);
    const Vec3 above = (p - box.max).cwiseMax(0.0);
    return std::sqrt(below.squaredNorm() + above.squaredNorm()) > std::max(limit, 0.0) + tol;
  }
  /// Pushes the children of inner node `n` that `keep` accepts by their squared distances, the
  /// nearer on top (searched first, so it tightens the bound for the other). A child refused now
  /// would be skipped when popped too: the bound only tightens.
  template <class Keep>
  void pushChildren(const Node& n, const Vec3& p, Pending* stack, int& top, Keep keep) const {
    const Pending left{n.left, squaredBoxDistance(p, nodes[n.left].box)};
    const Pending right{n.right, squaredBoxDistance(p, nodes[n.right].box)};
    const bool leftFirst = boundBelow(left.bound, right.bound);
    const Pending& first = leftFirst ? left : right;
    const Pending& second = leftFirst ? right : left;
    if (keep(second.bound)) stack[top++] = second;
    if (keep(first.bound)) stack[top++] = first;
  }
  /// The rounding allowance of pieceBeyond near p.
  static double tolerance(const Vec3& p) { return 1e-9 * (1 + p.cwiseAbs().maxCoeff()); }

  /// The search through the hierarchy: the smallest of the pieces' signed distances and, in
  /// `piece`, the first piece in the search's order that gives it.
  double search(const Vec3& p, std::int64_t* piece) const {
    double best = kInf;
    std::int64_t bestPiece = -1;
    if (nodes.empty()) {
      if (piece) *piece = -1;
      return best;
    }
    // Each node with its squared distance, computed once when its parent orders its children.
    Pending stack[128];
    const double tol = tolerance(p);
    int top = 0;
    stack[top++] = {0, squaredBoxDistance(p, nodes[0].box)};
    while (top > 0) {
      const auto [id, bound] = stack[--top];
      const Node& n = nodes[id];
      if (boundAtLeast(bound, best)) continue;
      if (n.count > 0) {
        for (std::uint32_t i = n.first; i < n.first + n.count; ++i) {
          if (pieceBeyond(p, i, best, tol)) continue;  // it would not be below `best`
          const double d = frames[i].signedDistance(p);
          if (d < best) {
            best = d;
            bestPiece = slotPiece[i];
          }
        }
        continue;
      }
      // Nearer child last, so it is searched first and tightens `best` for the other.
      pushChildren(n, p, stack, top, [best](double bound) { return !boundAtLeast(bound, best); });
    }
    if (piece) *piece = bestPiece;
    return best;
  }

  // ---- the cells ------------------------------------------------------------------------------
  // Most queries come in crowds about the model's surface (a cloud's points, many per piece).
  // Cubic cells about the pieces (their boxes grown by a cell) remember, once a point in them is
  // asked about, the pieces that can be nearest to any point in them (collect at the cell's
  // centre, reach its half-diagonal: CylinderModelIndex::nearPieces), nearest first; a query there
  // measures those few pieces only, skipping those whose box lies beyond the best so far. Its
  // answer is the search's: the smallest of those pieces' values is the smallest of all (the same
  // function, to the bit), and where one piece gives it the search names that piece too (it names
  // the first in its order that gives the smallest value); where two give it, or the cell has more
  // than kCellPieces pieces, the search answers. Filling is lock-free: the thread that claims an
  // unknown cell fills it, others meanwhile search.

  static std::uint64_t mix(std::uint64_t k) {  // splitmix64's finaliser
    k ^= k >> 30;
    k *= 0xbf58476d1ce4e5b9ull;
    k ^= k >> 27;
    k *= 0x94d049bb133111ebull;
    return k ^ (k >> 31);
  }
  /// The key of the cell holding p; false outside the grid (or for a NaN).
  bool cellKey(const Vec3& p, std::uint64_t& key) const {
    const Vec3 g = (p - cellOrigin) / cellSize;
    if (!(g.minCoeff() >= 0) || !(g.maxCoeff() < static_cast<double>(kCellRange))) return false;
    key = (static_cast<std::uint64_t>(g.x()) << 42) | (static_cast<std::uint64_t>(g.y()) << 21) |
          static_cast<std::uint64_t>(g.z());
    return true;
  }
  Cell* findCell(std::uint64_t key) const {
    const std::uint64_t mask = cellKeys.size() - 1;
    for (std::uint64_t h = mix(key) & mask;; h = (h + 1) & mask) {
      if (cellKeys[h] == key) return &cells[cellOfKey[h]];
      if (cellKeys[h] == kNoKey) return nullptr;
    }
  }
  void insertCell(std::uint64_t key, std::uint32_t& count) {
    const std::uint64_t mask = cellKeys.size() - 1;
    for (std::uint64_t h = mix(key) & mask;; h = (h + 1) & mask) {
      if (cellKeys[h] == key) return;
      if (cellKeys[h] == kNoKey) {
        cellKeys[h] = key;
        cellOfKey[h] = count++;
        return;
      }
    }
  }
  /// The range of cells a piece's box, grown by a cell, covers (per axis, first and last).
  void cellRange(const geom::BBox& box, std::array<std::uint64_t, 3>& lo, std::array<std::uint64_t, 3>& hi) const {
    for (int a = 0; a < 3; ++a) {
      lo[a] = static_cast<std::uint64_t>(std::max(0.0, std::floor((box.min[a] - cellOrigin[a]) / cellSize) - 1));
      hi[a] = static_cast<std::uint64_t>(std::floor((box.max[a] - cellOrigin[a]) / cellSize) + 1);
    }
  }
  /// Sets up the cells: their size (kCellRadii times the pieces' median radius, doubled until the
  /// pieces' grown boxes cover at most kCellsPerPiece cells each on average, kMaxCells in all) and
  /// their keys; none are filled.
  void buildCells() {
    const std::size_t n = frames.size();
    if (n < kMinCellPieces) return;
    std::vector<double> radius(n);
    for (std::size_t i = 0; i < n; ++i) radius[i] = std::max(frames[i].r0, frames[i].r1);
    std::nth_element(radius.begin(), radius.begin() + static_cast<std::ptrdiff_t>(n / 2), radius.end());
    const geom::BBox& all = nodes[0].box;
    cellSize = std::max(kCellRadii * radius[n / 2], 1e-6 * all.diagonal());
    if (!(cellSize > 0)) return;
    const double cap = std::min(kCellsPerPiece * static_cast<double>(n) + kExtraCells, kMaxCells);
    double covered = 0;  // cells the grown boxes cover, counting overlaps: at least the cells set up
    for (int attempt = 0;; ++attempt, cellSize *= 2) {
      if (attempt == 60) return;
      cellOrigin = all.min - Vec3::Constant(2 * cellSize);
      if (!((all.max - cellOrigin).maxCoeff() / cellSize + 2 < static_cast<double>(kCellRange))) continue;
      covered = 0;
      std::array<std::uint64_t, 3> lo{}, hi{};
      for (const geom::BBox& box : slotBox) {
        cellRange(box, lo, hi);
        covered += static_cast<double>(hi[0] - lo[0] + 1) * static_cast<double>(hi[1] - lo[1] + 1) *
                   static_cast<double>(hi[2] - lo[2] + 1);
      }
      if (covered <= cap) break;
    }
    std::size_t tableSize = 1024;
    while (static_cast<double>(tableSize) < 2 * covered) tableSize *= 2;
    cellKeys.assign(tableSize, kNoKey);
    cellOfKey.assign(tableSize, 0);
    std::uint32_t count = 0;
    std::array<std::uint64_t, 3> lo{}, hi{};
    for (const geom::BBox& box : slotBox) {
      cellRange(box, lo, hi);
      for (std::uint64_t x = lo[0]; x <= hi[0]; ++x)
        for (std::uint64_t y = lo[1]; y <= hi[1]; ++y)
          for (std::uint64_t z = lo[2]; z <= hi[2]; ++z) insertCell((x << 42) | (y << 21) | z, count);
    }
    cells = std::make_unique<Cell[]>(count);
  }
  /// Fills a cell claimed by this thread (state kFilling) and publishes it.
  void fillCell(Cell& cell, std::uint64_t key) const {
    const Vec3 index(static_cast<double>(key >> 42), static_cast<double>((key >> 21) & (kCellRange - 1)),
                     static_cast<double>(key & (kCellRange - 1)));
    const Vec3 centre = cellOrigin + (index + Vec3::Constant(0.5)) * cellSize;
    // Reach: the half-diagonal, and room for the rounding of a point's cell and of the distances.
    const double reach = 0.5 * std::sqrt(3.0) * cellSize * (1 + 1e-6) + tolerance(centre);
    std::vector<NearPiece> near;
    collect(centre, 2 * reach, near);
    if (near.empty() || near.size() > kCellPieces) {
      cell.state.store(kCrowded, std::memory_order_release);
      return;
    }
    // Nearest at the centre first: it likely sets a bound that lets the others be skipped.
    std::sort(near.begin(), near.end(), [](const NearPiece& a, const NearPiece& b) { return a.distance < b.distance; });
    cell.count = static_cast<std::uint8_t>(near.size());
    for (std::size_t j = 0; j < near.size(); ++j) cell.slot[j] = near[j].slot;
    cell.state.store(kReady, std::memory_order_release);
  }
  /// The query through p's cell: true with the answer when the cell gives it (see above).
  bool cellAnswer(const Vec3& p, double& best, std::int64_t* piece) const {
    std::uint64_t key = 0;
    if (!cells || !cellKey(p, key)) return false;
    Cell* cell = findCell(key);
    if (!cell) return false;
    std::uint8_t state = cell->state.load(std::memory_order_acquire);
    if (state == kUnknown && cell->state.compare_exchange_strong(state, kFilling, std::memory_order_acq_rel)) {
      fillCell(*cell, key);
      state = cell->state.load(std::memory_order_acquire);
    }
    if (state != kReady) return false;
    best = kInf;
    std::uint32_t bestSlot = 0;
    bool tie = false;
    const double tol = tolerance(p);
    for (std::uint8_t j = 0; j < cell->count; ++j) {
      const std::uint32_t i = cell->slot[j];
      if (pieceBeyond(p, i, best, tol)) continue;  // above `best`: neither the smallest nor a tie
      const double d = frames[i].signedDistance(p);
      if (d < best) {
        best = d;
        bestSlot = i;
        tie = false;
      } else if (d == best) {
        tie = true;
      }
    }
    if (tie || !(best < kInf)) return false;
    if (piece) *piece = slotPiece[bestSlot];
    return true;
  }

  double query(const Vec3& p, std::int64_t* piece) const {
    double best = kInf;
    if (cellAnswer(p, best, piece)) return best;
    return search(p, piece);
  }

  /// search(), also collecting the pieces within max(best, 0) + slack (the bound shrinks as `best`
  /// does; a box is skipped only when beyond it, so `best` is still the exact minimum).
  double collect(const Vec3& p, double slack, std::vector<NearPiece>& near) const {
    near.clear();
    double best = kInf;
    if (nodes.empty()) return best;
    Pending stack[128];
    const double tol = tolerance(p);
    int top = 0;
    stack[top++] = {0, squaredBoxDistance(p, nodes[0].box)};
    while (top > 0) {
      const auto [id, bound] = stack[--top];
      const Node& n = nodes[id];
      if (rootBound(bound) > std::max(best, 0.0) + slack) continue;
      if (n.count > 0) {
        for (std::uint32_t i = n.first; i < n.first + n.count; ++i) {
          if (pieceBeyond(p, i, std::max(best, 0.0) + slack, tol)) continue;  // neither kept nor below `best`
          const double d = frames[i].signedDistance(p);
          best = std::min(best, d);
          if (d <= std::max(best, 0.0) + slack) near.push_back({i, slotPiece[i], d});
        }
        continue;
      }
      const double limit = std::max(best, 0.0) + slack;
      pushChildren(n, p, stack, top, [limit](double bound) { return rootBound(bound) <= limit; });
    }
    // Entries taken under an earlier, looser bound.
    const double bound = std::max(best, 0.0) + slack;
    std::size_t kept = 0;
    for (std::size_t j = 0; j < near.size(); ++j)
      if (near[j].distance <= bound) near[kept++] = near[j];
    near.resize(kept);
    return best;
  }
};

CylinderModelIndex::CylinderModelIndex(const geom::CylinderModel& model, bool cells) : impl_(std::make_unique<Impl>()) {
  for (std::size_t i = 0; i < model.cylinders.size(); ++i) {
    const geom::ModelCylinder& c = model.cylinders[i];
    if (!c.start.allFinite() || !c.end.allFinite())
      throw OptionsError("cylinder model: piece " + std::to_string(i) + " has a non-finite end point");
    if (!std::isfinite(c.startRadius) || !std::isfinite(c.endRadius) || c.startRadius < 0 || c.endRadius < 0)
      throw OptionsError("cylinder model: piece " + std::to_string(i) + " has radii " + std::to_string(c.startRadius) +
                         ", " + std::to_string(c.endRadius) + ", expected finite values >= 0");
    if (c.parent < -1 || c.parent >= static_cast<std::int64_t>(model.size()))
      throw OptionsError("cylinder model: piece " + std::to_string(i) + " has parent " + std::to_string(c.parent) +
                         " of " + std::to_string(model.size()) + " pieces");
  }
  const std::vector<std::array<bool, 2>> open = jointCaps(model);
  for (std::size_t i = 0; i < model.size(); ++i) {
    const geom::ModelCylinder& c = model.cylinders[i];
    if (!(c.length() > 0)) continue;
    impl_->pieces.push_back(c);
    impl_->open.push_back(open[i]);
    impl_->modelIndex.push_back(static_cast<std::int64_t>(i));
    impl_->boxes.push_back(c.bounds());
  }
  const auto n = static_cast<std::uint32_t>(impl_->pieces.size());
  if (n == 0) return;
  std::vector<Vec3> centres(n);
  for (std::uint32_t i = 0; i < n; ++i) centres[i] = impl_->boxes[i].centre();
  impl_->order.resize(n);
  std::iota(impl_->order.begin(), impl_->order.end(), 0u);
  impl_->nodes.reserve(2 * (n / Impl::kLeafSize + 1));
  impl_->build(0, n, centres);
  impl_->frames.reserve(n);
  for (const std::uint32_t k : impl_->order) {
    impl_->frames.emplace_back(impl_->pieces[k], impl_->open[k][0], impl_->open[k][1]);
    impl_->slotPiece.push_back(impl_->modelIndex[k]);
    impl_->slotBox.push_back(impl_->boxes[k]);
  }
  if (cells) impl_->buildCells();
}

CylinderModelIndex::~CylinderModelIndex() = default;
CylinderModelIndex::CylinderModelIndex(CylinderModelIndex&&) noexcept = default;
CylinderModelIndex& CylinderModelIndex::operator=(CylinderModelIndex&&) noexcept = default;

double CylinderModelIndex::signedDistance(const Vec3& p, std::int64_t* piece) const { return impl_->query(p, piece); }

std::size_t CylinderModelIndex::size() const { return impl_->pieces.size(); }

double CylinderModelIndex::nearPieces(const Vec3& p, double reach, std::vector<NearPiece>& near) const {
  return impl_->collect(p, 2 * std::max(reach, 0.0), near);
}

double CylinderModelIndex::signedDistanceAmong(const Vec3& p, const std::vector<NearPiece>& near, std::int64_t* piece,
                                               bool* tied) const {
  double best = kInf;
  std::int64_t bestPiece = -1;
  bool tie = false;
  for (const NearPiece& c : near) {
    const double d = impl_->frames[c.slot].signedDistance(p);
    if (d < best) {
      best = d;
      bestPiece = c.piece;
      tie = false;
    } else if (d == best) {
      tie = true;
    }
  }
  if (piece) *piece = bestPiece;
  if (tied) *tied = tie;
  return best;
}

}  // namespace treesketch::compare
