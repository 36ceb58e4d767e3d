// Stems at breast height and a plot shared out among them (cloud/stems.h).
#include "treesketch/cloud/stems.h"

#include <algorithm>
#include <cstdlib>
#include <cmath>
#include <limits>
#include <queue>
#include <tuple>
#include <unordered_map>

#include "treesketch/accel/point_index.h"
#include "treesketch/cloud/stray_points.h"
#include "treesketch/fit/circle_fit.h"
#include "treesketch/util/error.h"
#include "treesketch/util/union_find.h"

namespace treesketch::cloud {
namespace {

using geom::Vec2;
using geom::Vec3;

// The terrain is read on cells of a metre (a plot's ground varies over metres, a stem's foot is
// narrower); a cell with no ground takes the nearest ring of cells with some, this many out at most.
constexpr double kTerrainCellMetres = 1.0;
constexpr int kTerrainRings = 10;
// Without ground points the terrain rises at most tan 15° from the lowest points round it; no grid
// beyond kMaxTerrainCells (a cloud that large without ground is not a tree or a plot).
constexpr double kMaxTerrainSlope = 0.268;
constexpr double kMaxTerrainCells = 4.0e6;
// A circle needs this many points on it (the circle fit's own minimum support).
constexpr int kMinCirclePoints = 8;
// A stem may lean up to this angle from the vertical between its slices (tan 20°); a limb leans more.
constexpr double kMaxLeanTan = 0.36;
// The circle's band: a centimetre of bark and scanner noise, or a point spacing when coarser.
constexpr double kBandMetres = 0.01;
// Radii of the confirming slices' circles against breast height's (a stem tapers or swells less).
constexpr double kCheckRadiusLow = 0.5, kCheckRadiusHigh = 1.6;
// The points that count round a circle: within this many radii of its centre.
constexpr double kAroundRadii = 1.5;
// Circle fits per group of points, each under kShrinkRadius of the last one's radius.
constexpr int kCircleAttempts = 4;
constexpr double kShrinkRadius = 0.75;
// Each slice is at least this many point spacings thick on either side (a few scan lines).
constexpr double kSliceSpacings = 2.0;
// Stems that join only below stump height are separate trees, as a forester fells them: at the
// foot, grass, litter and what the ground rule left join neighbouring stems.
constexpr double kStumpMetres = 0.3;
// A stem's points reach down to this height above the terrain (its foot may hide in grass).
constexpr double kReachMetres = 0.5;
// A tree reaches at least twice breast height above its terrain.
constexpr double kMinTreeHeightMetres = 2.6;
// The split's voxels, in point spacings: the 26 neighbours link points a few spacings apart.
constexpr double kVoxelSpacings = 2.0;

Vec2 across(const Vec3& p, geom::UpAxis up) { return up == geom::UpAxis::Y ? Vec2(p.x(), p.z()) : Vec2(p.x(), p.y()); }
Vec3 lift(const Vec2& g, double h, geom::UpAxis up) {
  return up == geom::UpAxis::Y ? Vec3(g.x(), h, g.y()) : Vec3(g.x(), g.y(), h);
}

// One flag per point: set for the points `indices` names.
std::vector<char> flags(const std::vector<std::uint32_t>& indices, std::size_t n) {
  std::vector<char> f(n, 0);
  for (std::uint32_t i : indices)
    if (i < n) f[i] = 1;
  return f;
}

std::int64_t key2(std::int64_t i, std::int64_t j) {
  return static_cast<std::int64_t>((static_cast<std::uint64_t>(i) << 32) ^ (static_cast<std::uint64_t>(j) & 0xffffffffULL));
}

struct Key {
  std::int64_t x, y, z;
  bool operator==(const Key&) const = default;
};
struct KeyHash {
  std::size_t operator()(const Key& k) const {
    return static_cast<std::size_t>(static_cast<std::uint64_t>(k.x) * 73856093ULL ^
                                    static_cast<std::uint64_t>(k.y) * 19349663ULL ^
                                    static_cast<std::uint64_t>(k.z) * 83492791ULL);
  }
};
Key voxelKey(const Vec3& p, double v) {
  return Key{static_cast<std::int64_t>(std::floor(p.x() / v)), static_cast<std::int64_t>(std::floor(p.y() / v)),
             static_cast<std::int64_t>(std::floor(p.z() / v))};
}

// The occupied voxels of the points `keep(i)` accepts.
struct Voxels {
  double size = 0;
  std::unordered_map<Key, std::uint32_t, KeyHash> of;
  std::vector<Key> keys;
  std::vector<std::uint32_t> pointVoxel;  ///< per point; kNone for ground
  static constexpr std::uint32_t kNone = std::numeric_limits<std::uint32_t>::max();
  Vec3 centre(std::size_t a) const {
    return Vec3((keys[a].x + 0.5) * size, (keys[a].y + 0.5) * size, (keys[a].z + 0.5) * size);
  }
};

template <class Keep>
Voxels voxelise(const geom::PointCloud& cloud, double size, Keep keep) {
  Voxels vx;
  vx.size = size;
  vx.pointVoxel.assign(cloud.size(), Voxels::kNone);
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    if (!keep(i)) continue;
    const Key k = voxelKey(cloud.positions[i], size);
    auto [it, added] = vx.of.emplace(k, static_cast<std::uint32_t>(vx.keys.size()));
    if (added) vx.keys.push_back(k);
    vx.pointVoxel[i] = it->second;
  }
  return vx;
}

// The terrain's height under a point. With ground points: their mean height in its cell, else in
// the nearest ring of cells holding ground. Without (a single tree's clip, a plot whose ground is
// too sparse to be found): the lowest point of its cell — a stem's foot, or sparse ground — but no
// higher than the lowest point of any other cell plus a slope of kMaxTerrainSlope over the distance
// between them: under a crown the lowest points are limbs' tips, and the ground runs on from the
// stem's foot.
class Terrain {
 public:
  Terrain(const geom::PointCloud& cloud, geom::UpAxis up, const std::vector<char>& isGround, double cell)
      : cell_(cell) {
    for (std::size_t i = 0; i < cloud.size(); ++i) {
      if (!isGround[i]) continue;
      auto& [sum, count] = ground_[keyOf(across(cloud.positions[i], up))];
      sum += geom::height(cloud.positions[i], up);
      ++count;
    }
    if (!ground_.empty() || cloud.empty()) return;
    // The lowest points on a dense grid over the cloud's extent, then the slope's cones.
    Vec2 lo = across(cloud.positions.front(), up), hi = lo;
    for (const Vec3& p : cloud.positions) {
      lo = lo.cwiseMin(across(p, up));
      hi = hi.cwiseMax(across(p, up));
    }
    const double nx = std::floor(hi.x() / cell) - std::floor(lo.x() / cell) + 1;
    const double ny = std::floor(hi.y() / cell) - std::floor(lo.y() / cell) + 1;
    if (!(nx * ny <= kMaxTerrainCells)) return;  // a terrain of that size has ground points, or is not a tree
    nx_ = static_cast<std::int64_t>(nx);
    ny_ = static_cast<std::int64_t>(ny);
    i0_ = static_cast<std::int64_t>(std::floor(lo.x() / cell));
    j0_ = static_cast<std::int64_t>(std::floor(lo.y() / cell));
    lowest_.assign(static_cast<std::size_t>(nx_ * ny_), std::numeric_limits<double>::infinity());
    for (const Vec3& p : cloud.positions) {
      const Vec2 g = across(p, up);
      double& l = lowest_[slot(static_cast<std::int64_t>(std::floor(g.x() / cell)) - i0_,
                               static_cast<std::int64_t>(std::floor(g.y() / cell)) - j0_)];
      l = std::min(l, geom::height(p, up));
    }
    // Chamfer passes: each cell no higher than a neighbour plus the slope over their distance.
    const double straight = kMaxTerrainSlope * cell, diagonal = straight * std::sqrt(2.0);
    for (bool changed = true; changed;) {
      changed = false;
      for (int pass = 0; pass < 2; ++pass) {
        const std::int64_t step = pass == 0 ? 1 : -1;
        for (std::int64_t jj = 0; jj < ny_; ++jj)
          for (std::int64_t ii = 0; ii < nx_; ++ii) {
            const std::int64_t i = pass == 0 ? ii : nx_ - 1 - ii, j = pass == 0 ? jj : ny_ - 1 - jj;
            double& t = lowest_[slot(i, j)];
            for (const auto& [di, dj, d] : {std::tuple{-step, std::int64_t{0}, straight}, std::tuple{-step, -step, diagonal},
                                            std::tuple{std::int64_t{0}, -step, straight}, std::tuple{step, -step, diagonal}}) {
              const std::int64_t a = i + di, b = j + dj;
              if (a < 0 || b < 0 || a >= nx_ || b >= ny_) continue;
              if (lowest_[slot(a, b)] + d < t) {
                t = lowest_[slot(a, b)] + d;
                changed = true;
              }
            }
          }
      }
    }
  }
  bool fromGround() const { return !ground_.empty(); }
  double at(const Vec2& g) const {
    const auto i = static_cast<std::int64_t>(std::floor(g.x() / cell_));
    const auto j = static_cast<std::int64_t>(std::floor(g.y() / cell_));
    if (ground_.empty()) {
      if (lowest_.empty() || i < i0_ || j < j0_ || i - i0_ >= nx_ || j - j0_ >= ny_)
        return std::numeric_limits<double>::quiet_NaN();
      return lowest_[slot(i - i0_, j - j0_)];
    }
    for (int ring = 0; ring <= kTerrainRings; ++ring) {
      double sum = 0;
      std::size_t count = 0;
      for (int di = -ring; di <= ring; ++di)
        for (int dj = -ring; dj <= ring; ++dj) {
          if (std::max(std::abs(di), std::abs(dj)) != ring) continue;
          const auto it = ground_.find(key2(i + di, j + dj));
          if (it == ground_.end()) continue;
          sum += it->second.first / static_cast<double>(it->second.second);
          ++count;
        }
      if (count > 0) return sum / static_cast<double>(count);
    }
    return std::numeric_limits<double>::quiet_NaN();  // no ground within kTerrainRings cells: no stem here
  }

 private:
  std::int64_t keyOf(const Vec2& g) const {
    return key2(static_cast<std::int64_t>(std::floor(g.x() / cell_)), static_cast<std::int64_t>(std::floor(g.y() / cell_)));
  }
  std::size_t slot(std::int64_t i, std::int64_t j) const { return static_cast<std::size_t>(j * nx_ + i); }
  double cell_;
  std::unordered_map<std::int64_t, std::pair<double, std::size_t>> ground_;
  std::vector<double> lowest_;
  std::int64_t nx_ = 0, ny_ = 0, i0_ = 0, j0_ = 0;
};

void checkOptions(const StemOptions& o) {
  auto positive = [](double v, const char* name) {
    if (!(v > 0) || !std::isfinite(v)) throw OptionsError(std::string("stems: ") + name + " must be > 0");
  };
  positive(o.unitMetres, "unitMetres");
  positive(o.breastHeight, "breastHeight");
  positive(o.sliceHalfWidth, "sliceHalfWidth");
  positive(o.checkOffset, "checkOffset");
  positive(o.minDiameter, "minDiameter");
  positive(o.linkSpacings, "linkSpacings");
  if (!(o.maxDiameter > o.minDiameter) || !std::isfinite(o.maxDiameter))
    throw OptionsError("stems: maxDiameter must be finite and above minDiameter");
  if (!(o.minOnCircleShare >= 0 && o.minOnCircleShare <= 1))
    throw OptionsError("stems: minOnCircleShare must be in [0, 1]");
  if (o.checkOffset <= o.sliceHalfWidth)
    throw OptionsError("stems: checkOffset must exceed sliceHalfWidth (the slices would overlap)");
}

// Groups of 2D points linked within `link` (a grid of cells of that side, 3 × 3 neighbours).
std::vector<std::vector<std::uint32_t>> linkedGroups(const std::vector<Vec2>& pts, double link) {
  std::unordered_map<std::int64_t, std::vector<std::uint32_t>> grid;
  auto cellOf = [&](const Vec2& g) {
    return std::pair{static_cast<std::int64_t>(std::floor(g.x() / link)), static_cast<std::int64_t>(std::floor(g.y() / link))};
  };
  for (std::uint32_t i = 0; i < pts.size(); ++i) {
    const auto [a, b] = cellOf(pts[i]);
    grid[key2(a, b)].push_back(i);
  }
  util::UnionFind uf(pts.size());
  const double link2 = link * link;
  for (std::uint32_t i = 0; i < pts.size(); ++i) {
    const auto [a, b] = cellOf(pts[i]);
    for (int da = -1; da <= 1; ++da)
      for (int db = -1; db <= 1; ++db) {
        const auto it = grid.find(key2(a + da, b + db));
        if (it == grid.end()) continue;
        for (std::uint32_t j : it->second)
          if (j > i && (pts[i] - pts[j]).squaredNorm() <= link2) uf.unite(i, j);
      }
  }
  std::unordered_map<std::uint32_t, std::size_t> slot;
  std::vector<std::vector<std::uint32_t>> groups;
  for (std::uint32_t i = 0; i < pts.size(); ++i) {
    const std::uint32_t r = uf.find(i);
    auto [it, added] = slot.emplace(r, groups.size());
    if (added) groups.emplace_back();
    groups[it->second].push_back(i);
  }
  return groups;
}

// The points within kAroundRadii radii of a circle's centre.
std::size_t pointsAround(const std::vector<Vec2>& pts, const Vec2& centre, double radius, double band) {
  std::size_t around = 0;
  const double aroundRadius = kAroundRadii * radius + band;
  for (const Vec2& p : pts) around += (p - centre).squaredNorm() <= aroundRadius * aroundRadius;
  return around;
}

// A circle in `pts` near `centre` with a radius in [rLow, rHigh], its centre within `reach`.
bool confirmed(const std::vector<Vec2>& pts, const Vec2& centre, double radius, double reach, double band,
               double minShare, std::uint64_t seed) {
  std::vector<Vec2> near;
  const double window = radius * kCheckRadiusHigh + band + reach;
  for (const Vec2& p : pts)
    if ((p - centre).squaredNorm() <= window * window) near.push_back(p);
  if (near.size() < static_cast<std::size_t>(kMinCirclePoints)) return false;
  fit::CircleFitOptions c;
  c.inlierThreshold = band;
  c.minInliers = kMinCirclePoints;
  c.minRadius = kCheckRadiusLow * radius;
  c.maxRadius = kCheckRadiusHigh * radius + band;
  c.seed = seed;
  const fit::CircleFitResult r = fit::fitCircleRansac(near, c);
  if (!r.ok || (r.centre - centre).norm() > reach) return false;
  return static_cast<double>(r.inliers.size()) >= minShare * static_cast<double>(pointsAround(near, r.centre, r.radius, band));
}

// Stems whose points join below breast height are one tree (forked below it, or a low limb taken
// for a stem): the points from stump height to the top of the breast-height slice (`height`: above
// the terrain, NaN for ground), on voxels of side `voxel` joined to their 26 neighbours.
void groupIntoTrees(const geom::PointCloud& cloud, geom::UpAxis up, const std::vector<double>& height, double top,
                    double half, double band, double voxel, double u, Stems& out) {
  const double floor = kStumpMetres / u;
  const Voxels vx = voxelise(cloud, voxel, [&](std::size_t i) { return height[i] <= top && height[i] >= floor; });
  const std::vector<Key>& keys = vx.keys;
  const std::vector<std::uint32_t>& pointVoxel = vx.pointVoxel;
  util::UnionFind pieces(keys.size());
  for (std::uint32_t a = 0; a < keys.size(); ++a)
    for (int dx = -1; dx <= 1; ++dx)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dz = -1; dz <= 1; ++dz) {
          const auto it = vx.of.find(Key{keys[a].x + dx, keys[a].y + dy, keys[a].z + dz});
          if (it != vx.of.end() && it->second > a) pieces.unite(a, it->second);
        }
  // How low each piece reaches.
  std::vector<double> lowest(keys.size(), std::numeric_limits<double>::infinity());
  for (std::size_t i = 0; i < cloud.size(); ++i)
    if (pointVoxel[i] != Voxels::kNone) {
      double& l = lowest[pieces.find(pointVoxel[i])];
      l = std::min(l, height[i]);
    }
  // Each stem's pieces: those of the points of its slice on or inside its circle. A stem stands on
  // the ground: one whose pieces end above kReachMetres is a limb hanging through breast height.
  util::UnionFind trees(out.stems.size());
  std::unordered_map<std::uint32_t, std::uint32_t> stemOfPiece;
  std::vector<double> reach(out.stems.size(), std::numeric_limits<double>::infinity());
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    if (pointVoxel[i] == Voxels::kNone || height[i] < top - 2 * half) continue;
    const Vec2 g = across(cloud.positions[i], up);
    for (std::uint32_t s = 0; s < out.stems.size(); ++s) {
      const Stem& st = out.stems[s];
      if ((g - across(st.centre, up)).norm() > 0.5 * st.diameter / u + band) continue;
      const std::uint32_t piece = pieces.find(pointVoxel[i]);
      reach[s] = std::min(reach[s], lowest[piece]);
      const auto [it, added] = stemOfPiece.emplace(piece, s);
      if (!added) trees.unite(it->second, s);
    }
  }
  std::vector<Stem> standing;
  std::unordered_map<std::uint32_t, std::int32_t> treeOf;
  for (std::uint32_t s = 0; s < out.stems.size(); ++s) {
    if (!(reach[s] <= kReachMetres / u)) continue;
    const auto [it, added] = treeOf.emplace(trees.find(s), static_cast<std::int32_t>(treeOf.size()));
    standing.push_back(out.stems[s]);
    standing.back().tree = it->second;
  }
  out.stems = std::move(standing);
  out.trees = treeOf.size();
}

// A tree stands above its stem: the points the split gives a stem's tree reach at least
// kMinTreeHeightMetres above its terrain (a limb whose tip rests on the ground, a stump with a
// sprout, do not).
void keepTreesWithCrowns(const geom::PointCloud& cloud, geom::UpAxis up, const std::vector<std::uint32_t>& ground,
                         const StemOptions& o, Stems& out) {
  const std::vector<std::int32_t> label = splitByTree(cloud, up, out, ground, o);
  std::vector<double> top(out.trees, -std::numeric_limits<double>::infinity());
  for (std::size_t i = 0; i < cloud.size(); ++i)
    if (label[i] >= 0) top[static_cast<std::size_t>(label[i])] = std::max(top[static_cast<std::size_t>(label[i])], geom::height(cloud.positions[i], up));
  std::vector<double> terrain(out.trees, std::numeric_limits<double>::infinity());
  for (const Stem& s : out.stems) terrain[static_cast<std::size_t>(s.tree)] = std::min(terrain[static_cast<std::size_t>(s.tree)], s.terrain);
  std::vector<std::int32_t> renumber(out.trees, -1);
  std::int32_t kept = 0;
  for (std::size_t t = 0; t < out.trees; ++t)
    if (top[t] - terrain[t] >= kMinTreeHeightMetres / o.unitMetres) renumber[t] = kept++;
  std::vector<Stem> stems;
  for (Stem s : out.stems)
    if (renumber[static_cast<std::size_t>(s.tree)] >= 0) {
      s.tree = renumber[static_cast<std::size_t>(s.tree)];
      stems.push_back(s);
    }
  out.stems = std::move(stems);
  out.trees = static_cast<std::size_t>(kept);
}

// The three slices of the points that are not ground, across the up axis, and every point's
// height above the terrain (NaN for ground and where the terrain is unknown).
struct Slices {
  std::vector<Vec2> main, below, above;
  std::vector<double> mainTerrain;  ///< the terrain under each point of `main`
  std::vector<double> height;       ///< per point of the cloud
};

Slices slice(const geom::PointCloud& cloud, geom::UpAxis up, const std::vector<char>& isGround, const Terrain& terrain,
             double bh, double half, double off) {
  Slices sl;
  sl.height.assign(cloud.size(), std::numeric_limits<double>::quiet_NaN());
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    if (isGround[i]) continue;
    const Vec2 g = across(cloud.positions[i], up);
    const double t = terrain.at(g);
    const double h = geom::height(cloud.positions[i], up) - t;
    sl.height[i] = h;
    if (std::abs(h - bh) <= half) {
      sl.main.push_back(g);
      sl.mainTerrain.push_back(t);
    } else if (std::abs(h - (bh - off)) <= half) {
      sl.below.push_back(g);
    } else if (std::abs(h - (bh + off)) <= half) {
      sl.above.push_back(g);
    }
  }
  return sl;
}

// A stem's circle in `pts` (one group of the breast-height slice), confirmed by the slices below
// and above it; false when there is none.
//
// It shows in the slice below or above; in both where the terrain is the lowest points' (no ground:
// a limb low in a crown could stand on its own leaves). The circle with the most points on it may
// run along a limb leaving the stem: when the slices do not show it, the next try looks under three
// quarters of its radius. A centimetre's band first (an arc in a wide band fits circles of many
// radii), then a point spacing's (a sparse or noisy scan).
bool stemCircle(const std::vector<Vec2>& pts, const Slices& sl, double narrowBand, double wideBand, double off,
                bool either, const StemOptions& o, std::uint64_t& seed, fit::CircleFitResult& r) {
  const double u = o.unitMetres;
  for (const double band : {narrowBand, wideBand}) {
    fit::CircleFitOptions c;
    c.inlierThreshold = band;
    c.minInliers = kMinCirclePoints;
    c.minRadius = 0.5 * o.minDiameter / u;
    c.maxRadius = 0.5 * o.maxDiameter / u;
    for (int attempt = 0; attempt < kCircleAttempts && c.maxRadius > c.minRadius; ++attempt) {
      c.seed = seed++;
      r = fit::fitCircleRansac(pts, c);
      if (!r.ok) break;
      c.maxRadius = kShrinkRadius * r.radius;
      // Most of the points round the circle lie on it: bark, with nothing inside (a limb crossing
      // the slice obliquely is a filled blob). Points farther out are a limb leaving the stem.
      const std::size_t around = pointsAround(pts, r.centre, r.radius, band);
      if (static_cast<double>(r.inliers.size()) < o.minOnCircleShare * static_cast<double>(around)) continue;
      const double reach = kMaxLeanTan * off + band;
      const bool low = confirmed(sl.below, r.centre, r.radius, reach, band, o.minOnCircleShare, seed);
      const bool high = confirmed(sl.above, r.centre, r.radius, reach, band, o.minOnCircleShare, seed);
      if (either ? (low || high) : (low && high)) return true;
    }
    if (wideBand <= narrowBand) break;
  }
  return false;
}

}  // namespace

Stems findStems(const geom::PointCloud& cloud, geom::UpAxis up, const std::vector<std::uint32_t>& ground,
                double spacing, const StemOptions& o) {
  checkOptions(o);
  Stems out;
  if (cloud.size() < static_cast<std::size_t>(kMinCirclePoints)) return out;
  if (!(spacing > 0)) spacing = measurePointSpacing(cloud);
  if (!(spacing > 0)) return out;
  out.spacing = spacing;
  const double u = o.unitMetres;
  const std::vector<char> isGround = flags(ground, cloud.size());
  const Terrain terrain(cloud, up, isGround, kTerrainCellMetres / u);
  out.terrainFromGround = terrain.fromGround();
  const double bh = o.breastHeight / u, off = o.checkOffset / u;
  // A slice holds a few scan lines: at least two point spacings each side.
  const double half = std::min(std::max(o.sliceHalfWidth / u, kSliceSpacings * spacing), 0.5 * off);
  const Slices sl = slice(cloud, up, isGround, terrain, bh, half, off);

  const double narrowBand = kBandMetres / u, wideBand = std::max(narrowBand, spacing);
  std::vector<Stem> found;
  std::uint64_t seed = 1;
  for (const std::vector<std::uint32_t>& group : linkedGroups(sl.main, o.linkSpacings * spacing)) {
    std::vector<Vec2> pts;
    double t = 0;
    for (std::uint32_t i : group) {
      pts.push_back(sl.main[i]);
      t += sl.mainTerrain[i] / static_cast<double>(group.size());
    }
    // A group may hold several stems (a fork, trees touching): once a stem is found its points
    // leave the group and the rest is searched again.
    fit::CircleFitResult r;
    while (pts.size() >= static_cast<std::size_t>(kMinCirclePoints) &&
           stemCircle(pts, sl, narrowBand, wideBand, off, out.terrainFromGround, o, seed, r)) {
      Stem s;
      s.terrain = t;
      s.centre = lift(r.centre, t + bh, up);
      s.diameter = 2 * r.radius * u;
      s.rms = r.rms * u;
      s.points = r.inliers.size();
      found.push_back(s);
      const double gone = r.radius + 2 * wideBand;
      std::erase_if(pts, [&](const Vec2& q) { return (q - r.centre).squaredNorm() <= gone * gone; });
    }
  }
  // Overlapping circles are arcs of one stem: the one with the most points on it stays.
  std::sort(found.begin(), found.end(), [](const Stem& a, const Stem& b) { return a.points > b.points; });
  for (const Stem& s : found) {
    const bool overlaps = std::any_of(out.stems.begin(), out.stems.end(), [&](const Stem& k) {
      return (across(k.centre, up) - across(s.centre, up)).norm() < 0.5 * (k.diameter + s.diameter) / u;
    });
    if (!overlaps) out.stems.push_back(s);
  }
  std::sort(out.stems.begin(), out.stems.end(), [](const Stem& a, const Stem& b) { return a.diameter > b.diameter; });
  groupIntoTrees(cloud, up, sl.height, bh + half, half, wideBand, kVoxelSpacings * spacing, u, out);
  if (out.trees > 1) keepTreesWithCrowns(cloud, up, ground, o, out);
  return out;
}

namespace {

using Queue = std::priority_queue<std::pair<double, std::uint32_t>, std::vector<std::pair<double, std::uint32_t>>,
                                  std::greater<>>;

// The sources: each stem's voxels at breast height, on or inside its circle, labelled with its
// tree. The stems sit on a grid of cells as wide as the widest, so each point looks at 3 × 3 cells.
void seedStems(const geom::PointCloud& cloud, geom::UpAxis up, const Stems& stems, const StemOptions& o, double band,
               const Voxels& vx, std::vector<double>& dist, std::vector<std::int32_t>& label, Queue& queue) {
  const double u = o.unitMetres, half = o.sliceHalfWidth / u;
  double widest = 0;
  for (const Stem& st : stems.stems) widest = std::max(widest, 0.5 * st.diameter / u + band);
  std::unordered_map<std::int64_t, std::vector<std::uint32_t>> stemCells;
  auto cellOf = [&](const Vec2& g) {
    return std::pair{static_cast<std::int64_t>(std::floor(g.x() / widest)), static_cast<std::int64_t>(std::floor(g.y() / widest))};
  };
  for (std::uint32_t s = 0; s < stems.stems.size(); ++s) {
    const auto [a, b] = cellOf(across(stems.stems[s].centre, up));
    stemCells[key2(a, b)].push_back(s);
  }
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    if (vx.pointVoxel[i] == Voxels::kNone) continue;
    const Vec3& p = cloud.positions[i];
    const Vec2 g = across(p, up);
    const auto [a, b] = cellOf(g);
    for (int da = -1; da <= 1; ++da)
      for (int db = -1; db <= 1; ++db) {
        const auto it = stemCells.find(key2(a + da, b + db));
        if (it == stemCells.end()) continue;
        for (std::uint32_t s : it->second) {
          const Stem& st = stems.stems[s];
          if (std::abs(geom::height(p, up) - geom::height(st.centre, up)) > half) continue;
          if ((g - across(st.centre, up)).norm() > 0.5 * st.diameter / u + band) continue;
          const std::uint32_t v = vx.pointVoxel[i];
          if (dist[v] > 0) {
            dist[v] = 0;
            label[v] = st.tree;
            queue.emplace(0.0, v);
          }
        }
      }
  }
}

// Shortest paths over the voxels' 26 neighbours from the sources: each voxel takes the label of
// the nearest. Voxels no path reached take the label of the nearest voxel one reached.
void spreadLabels(const Voxels& vx, std::vector<double>& dist, std::vector<std::int32_t>& label, Queue& queue) {
  while (!queue.empty()) {
    const auto [d, a] = queue.top();
    queue.pop();
    if (d > dist[a]) continue;
    const Key k = vx.keys[a];
    for (int dx = -1; dx <= 1; ++dx)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dz = -1; dz <= 1; ++dz) {
          if (dx == 0 && dy == 0 && dz == 0) continue;
          const auto it = vx.of.find(Key{k.x + dx, k.y + dy, k.z + dz});
          if (it == vx.of.end()) continue;
          const double nd = d + vx.size * std::sqrt(static_cast<double>(dx * dx + dy * dy + dz * dz));
          if (nd < dist[it->second]) {
            dist[it->second] = nd;
            label[it->second] = label[a];
            queue.emplace(nd, it->second);
          }
        }
  }
  std::vector<Vec3> reachedCentre;
  std::vector<std::int32_t> reachedLabel;
  for (std::size_t a = 0; a < vx.keys.size(); ++a)
    if (label[a] >= 0) {
      reachedCentre.push_back(vx.centre(a));
      reachedLabel.push_back(label[a]);
    }
  if (reachedCentre.empty()) return;
  const accel::PointIndex index(reachedCentre);
  for (std::size_t a = 0; a < vx.keys.size(); ++a)
    if (label[a] < 0)
      if (const auto nb = index.nearest(vx.centre(a))) label[a] = reachedLabel[nb->index];
}

}  // namespace

std::vector<std::int32_t> splitByTree(const geom::PointCloud& cloud, geom::UpAxis up, const Stems& stems,
                                      const std::vector<std::uint32_t>& ground, const StemOptions& o) {
  checkOptions(o);
  std::vector<std::int32_t> label(cloud.size(), -1);
  if (stems.stems.empty() || cloud.empty()) return label;
  const double spacing = stems.spacing > 0 ? stems.spacing : measurePointSpacing(cloud);
  if (!(spacing > 0)) return label;
  const std::vector<char> isGround = flags(ground, cloud.size());
  const Voxels vx = voxelise(cloud, kVoxelSpacings * spacing, [&](std::size_t i) { return !isGround[i]; });
  std::vector<double> dist(vx.keys.size(), std::numeric_limits<double>::infinity());
  std::vector<std::int32_t> voxelLabel(vx.keys.size(), -1);
  Queue queue;
  seedStems(cloud, up, stems, o, std::max(kBandMetres / o.unitMetres, spacing), vx, dist, voxelLabel, queue);
  spreadLabels(vx, dist, voxelLabel, queue);
  for (std::size_t i = 0; i < cloud.size(); ++i)
    if (vx.pointVoxel[i] != Voxels::kNone) label[i] = voxelLabel[vx.pointVoxel[i]];
  return label;
}

}  // namespace treesketch::cloud
