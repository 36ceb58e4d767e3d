// The ground under a tree (see ground.h).
#include "treesketch/cloud/ground.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>
#include <unordered_map>

#include "treesketch/cloud/stray_points.h"
#include "treesketch/util/error.h"
#include "treesketch/util/union_find.h"

namespace treesketch::cloud {
namespace {

/// ASPRS classification code for ground.
constexpr std::uint8_t kGroundClass = 2;
/// A cloud whose terrain would leave fewer points than this is a surface, not a tree standing on
/// the ground: nothing is set aside. (A share would not do: a terrestrial scan of a small tree
/// from stations on open ground can hold 200 points of terrain for each of the tree's.)
constexpr std::size_t kMinTreePoints = 64;
/// The cloud's bottom: the height quantile below which a few points may lie under the terrain
/// (noise, a mis-registered return).
constexpr double kBottomQuantile = 0.001;
/// A point more than this many column sides from any column is off the grid.
constexpr double kMaxColumnCoordinate = 4.0e18;

struct Key {
  std::int64_t i = 0, j = 0;
  bool operator==(const Key& o) const { return i == o.i && j == o.j; }
};
struct KeyHash {
  std::size_t operator()(const Key& k) const {
    std::uint64_t h = static_cast<std::uint64_t>(k.i) * 0x9E3779B97F4A7C15ULL;
    h ^= static_cast<std::uint64_t>(k.j) * 0xC2B2AE3D27D4EB4FULL + (h << 6) + (h >> 2);
    return static_cast<std::size_t>(h);
  }
};

/// Horizontal coordinates (across `up`) and height of a point.
struct Across {
  double u, v, h;
};
Across across(const geom::Vec3& p, geom::UpAxis up) {
  return up == geom::UpAxis::Y ? Across{p.x(), p.z(), p.y()} : Across{p.x(), p.y(), p.z()};
}

/// A column of the grid: its points, and the plane h = a + b (u − u0) + c (v − v0) of its lowest
/// points when it is terrain.
struct Column {
  Key key;
  std::vector<std::uint32_t> points;
  double u0 = 0, v0 = 0;  ///< its centre
  double a = 0, b = 0, c = 0, roughness = 0;
  bool terrain = false;
  double at(double u, double v) const { return a + b * (u - u0) + c * (v - v0); }
};

void checkOptions(const GroundOptions& o) {
  if (!(o.columnSpacings > 0) || o.subColumns < 2 || !(o.minFilledShare > 0 && o.minFilledShare <= 1) ||
      !(o.maxSlopeDeg > 0 && o.maxSlopeDeg < 90) || !(o.maxRoughnessColumns > 0) || o.minColumns < 1 ||
      !(o.heightSpacings >= 0))
    throw OptionsError(
        "ground: options out of range (columnSpacings > 0, subColumns >= 2, minFilledShare in (0, 1], maxSlopeDeg "
        "in (0, 90), maxRoughnessColumns > 0, minColumns >= 1, heightSpacings >= 0)");
}

/// Whether `col`'s lowest points fill it and lie on a plane that is not steep; sets its plane.
void fitTerrain(Column& col, const std::vector<Across>& at, double side, const GroundOptions& o) {
  const int n = o.subColumns;
  std::vector<double> lowest(static_cast<std::size_t>(n * n), std::numeric_limits<double>::infinity());
  std::vector<std::uint32_t> which(lowest.size(), 0);
  const double sub = side / n;
  for (std::uint32_t p : col.points) {
    const int si = std::clamp(static_cast<int>(std::floor((at[p].u - (col.u0 - 0.5 * side)) / sub)), 0, n - 1);
    const int sj = std::clamp(static_cast<int>(std::floor((at[p].v - (col.v0 - 0.5 * side)) / sub)), 0, n - 1);
    const std::size_t k = static_cast<std::size_t>(si * n + sj);
    if (at[p].h < lowest[k]) {
      lowest[k] = at[p].h;
      which[k] = p;
    }
  }
  // A sub-column where the scanner missed the terrain (a gap between scan lines, a shadow) has its
  // lowest point on whatever stands above: only the lowest points within the steepest slope's rise
  // of the column's lowest are the terrain's.
  const double bottom = *std::min_element(lowest.begin(), lowest.end());
  const double rise = side * std::tan(o.maxSlopeDeg * M_PI / 180.0);
  for (double& h : lowest)
    if (h > bottom + rise) h = std::numeric_limits<double>::infinity();
  Eigen::Matrix3d ata = Eigen::Matrix3d::Zero();
  Eigen::Vector3d atb = Eigen::Vector3d::Zero();
  int filled = 0;
  for (std::size_t k = 0; k < lowest.size(); ++k) {
    if (!std::isfinite(lowest[k])) continue;
    ++filled;
    const Eigen::Vector3d row(1.0, at[which[k]].u - col.u0, at[which[k]].v - col.v0);
    ata += row * row.transpose();
    atb += row * lowest[k];
  }
  if (filled < o.minFilledShare * n * n || filled < 3) return;
  const Eigen::Vector3d x = ata.ldlt().solve(atb);
  if (!x.allFinite()) return;
  col.a = x[0];
  col.b = x[1];
  col.c = x[2];
  double ss = 0;
  for (std::size_t k = 0; k < lowest.size(); ++k)
    if (std::isfinite(lowest[k])) {
      const double r = lowest[k] - col.at(at[which[k]].u, at[which[k]].v);
      ss += r * r;
    }
  col.roughness = std::sqrt(ss / filled);
  const double slope = std::atan(std::hypot(col.b, col.c)) * 180.0 / M_PI;
  col.terrain = slope <= o.maxSlopeDeg && col.roughness <= o.maxRoughnessColumns * side;
}

/// The cloud's points in columns of side `side` (points off the grid in none).
std::vector<Column> columnsOf(const std::vector<Across>& at, double side) {
  std::unordered_map<Key, std::size_t, KeyHash> index;
  std::vector<Column> cols;
  for (std::size_t p = 0; p < at.size(); ++p) {
    const double fi = std::floor(at[p].u / side), fj = std::floor(at[p].v / side);
    if (!(std::fabs(fi) < kMaxColumnCoordinate && std::fabs(fj) < kMaxColumnCoordinate)) continue;
    const Key key{static_cast<std::int64_t>(fi), static_cast<std::int64_t>(fj)};
    auto [it, added] = index.emplace(key, cols.size());
    if (added) {
      Column c;
      c.key = key;
      c.u0 = (fi + 0.5) * side;
      c.v0 = (fj + 0.5) * side;
      cols.push_back(std::move(c));
    }
    cols[it->second].points.push_back(static_cast<std::uint32_t>(p));
  }
  return cols;
}

/// Terrain spans at least this share of the cloud's width across up: the surface the tree stands
/// on, not a patch at its foot (a stem's cut face seen from below, as the thesis's sphere pattern
/// sees a capped trunk, is a filled, level disc the stem's width).
constexpr double kMinWidthShare = 0.25;

/// Marks terrain only where it is wide and reaches the cloud's bottom: the terrain columns joined
/// to their neighbours (8 around, planes meeting within the steepest slope), in groups of at least
/// minColumns, as wide as kMinWidthShare of `width`, whose lowest plane lies within one column's
/// rise of `bottom`.
void keepWideTerrain(std::vector<Column>& cols, double side, double bottom, double width, const GroundOptions& o) {
  std::unordered_map<Key, std::size_t, KeyHash> index;
  for (std::size_t k = 0; k < cols.size(); ++k)
    if (cols[k].terrain) index.emplace(cols[k].key, k);
  const double rise = side * std::tan(o.maxSlopeDeg * M_PI / 180.0);
  util::UnionFind sets(cols.size());
  for (const auto& [key, k] : index)
    for (int di = -1; di <= 1; ++di)
      for (int dj = -1; dj <= 1; ++dj) {
        auto it = index.find({key.i + di, key.j + dj});
        if (it == index.end() || it->second == k) continue;
        const Column& a = cols[k];
        const Column& b = cols[it->second];
        if (std::fabs(a.at(a.u0, a.v0) - b.at(b.u0, b.v0)) <= rise + a.roughness + b.roughness)
          sets.unite(static_cast<std::uint32_t>(k), static_cast<std::uint32_t>(it->second));
      }
  struct Group {
    int columns = 0;
    double lowest = std::numeric_limits<double>::infinity();
    std::int64_t i0 = std::numeric_limits<std::int64_t>::max(), i1 = std::numeric_limits<std::int64_t>::min();
    std::int64_t j0 = i0, j1 = i1;
  };
  std::unordered_map<std::uint32_t, Group> groups;
  for (const auto& [key, k] : index) {
    Group& g = groups[sets.find(static_cast<std::uint32_t>(k))];
    ++g.columns;
    g.lowest = std::min(g.lowest, cols[k].at(cols[k].u0, cols[k].v0));
    g.i0 = std::min(g.i0, key.i);
    g.i1 = std::max(g.i1, key.i);
    g.j0 = std::min(g.j0, key.j);
    g.j1 = std::max(g.j1, key.j);
  }
  for (const auto& [key, k] : index) {
    const Group& g = groups[sets.find(static_cast<std::uint32_t>(k))];
    const double wide = side * static_cast<double>(std::max(g.i1 - g.i0, g.j1 - g.j0) + 1);
    cols[k].terrain = g.columns >= o.minColumns && wide >= kMinWidthShare * width && g.lowest <= bottom + rise;
  }
}

/// Columns searched round a column without terrain for the terrain's planes: a terrestrial
/// scan's terrain far from its stations is lines of points too far apart to fill a column, and
/// under a stem's foot it is hidden; the terrain beside them gives their height.
constexpr int kReachColumns = 4;

/// Sets `ground` for each point at most `above` over its terrain: the plane of its own column when
/// that is terrain, else the mean of the planes of the nearest terrain columns round it (the first
/// ring of columns, out to kReachColumns, that holds any).
void markGround(const std::vector<Column>& cols, const std::vector<Across>& at, double spacing, const GroundOptions& o,
                std::vector<char>& ground) {
  std::unordered_map<Key, std::size_t, KeyHash> terrain;
  for (std::size_t k = 0; k < cols.size(); ++k)
    if (cols[k].terrain) terrain.emplace(cols[k].key, k);
  std::vector<const Column*> near;
  for (const Column& c : cols) {
    near.clear();
    if (c.terrain) near.push_back(&c);
    for (int ring = 1; ring <= kReachColumns && near.empty(); ++ring)
      for (int di = -ring; di <= ring; ++di)
        for (int dj = -ring; dj <= ring; ++dj) {
          if (std::max(std::abs(di), std::abs(dj)) != ring) continue;
          auto it = terrain.find({c.key.i + di, c.key.j + dj});
          if (it != terrain.end()) near.push_back(&cols[it->second]);
        }
    if (near.empty()) continue;
    double rough = 0;
    for (const Column* t : near) rough = std::max(rough, t->roughness);
    const double above = std::max(o.heightSpacings * spacing, 3.0 * rough);
    for (std::uint32_t p : c.points) {
      double plane = 0;
      for (const Column* t : near) plane += t->at(at[p].u, at[p].v);
      if (at[p].h <= plane / static_cast<double>(near.size()) + above) ground[p] = 1;
    }
  }
}

/// The q-quantile of one coordinate of `at` (`scratch` reused between calls).
double quantileOf(const std::vector<Across>& at, double Across::*field, double q, std::vector<double>& scratch) {
  scratch.resize(at.size());
  for (std::size_t i = 0; i < at.size(); ++i) scratch[i] = at[i].*field;
  const auto k = static_cast<std::size_t>(q * static_cast<double>(scratch.size() - 1));
  std::nth_element(scratch.begin(), scratch.begin() + static_cast<std::ptrdiff_t>(k), scratch.end());
  return scratch[k];
}

}  // namespace

Ground findGround(const geom::PointCloud& cloud, geom::UpAxis up, double spacing, const GroundOptions& o) {
  checkOptions(o);
  Ground out;
  if (!o.enabled || cloud.size() < 64) return out;
  std::vector<char> ground(cloud.size(), 0);
  if (cloud.classification.size() == cloud.size())
    for (std::size_t i = 0; i < cloud.size(); ++i)
      if (cloud.classification[i] == kGroundClass) {
        ground[i] = 1;
        ++out.classified;
      }
  if (!(spacing > 0)) spacing = measurePointSpacing(cloud);
  if (spacing > 0 && std::isfinite(spacing)) {
    const double side = o.columnSpacings * spacing;
    std::vector<Across> at(cloud.size());
    for (std::size_t i = 0; i < cloud.size(); ++i) at[i] = across(cloud.positions[i], up);
    std::vector<Column> cols = columnsOf(at, side);
    for (Column& c : cols) fitTerrain(c, at, side, o);
    std::vector<double> scratch;
    auto span = [&](double Across::*field) {
      return quantileOf(at, field, 1 - kBottomQuantile, scratch) - quantileOf(at, field, kBottomQuantile, scratch);
    };
    const double width = std::max(span(&Across::u), span(&Across::v));
    keepWideTerrain(cols, side, quantileOf(at, &Across::h, kBottomQuantile, scratch), width, o);
    out.columns = static_cast<std::size_t>(std::count_if(cols.begin(), cols.end(), [](const Column& c) { return c.terrain; }));
    out.columnSize = side;
    markGround(cols, at, spacing, o, ground);
  }
  for (std::size_t i = 0; i < cloud.size(); ++i)
    if (ground[i]) out.points.push_back(static_cast<std::uint32_t>(i));
  if (cloud.size() - out.points.size() < kMinTreePoints) out = Ground{};
  return out;
}

namespace {

/// The indices 0 … n − 1 not in `out` (both increasing).
std::vector<std::uint32_t> complementOf(std::size_t n, const std::vector<std::uint32_t>& out) {
  std::vector<std::uint32_t> rest;
  rest.reserve(n - out.size());
  for (std::size_t i = 0, k = 0; i < n; ++i) {
    if (k < out.size() && out[k] == i) {
      ++k;
      continue;
    }
    rest.push_back(static_cast<std::uint32_t>(i));
  }
  return rest;
}

StrayPoints findStrayAndGround(const geom::PointCloud& cloud, geom::UpAxis up, const StrayPointOptions& strays,
                               const GroundOptions& ground) {
  const Ground g = findGround(cloud, up, 0.0, ground);
  if (g.points.empty()) return findStrayPoints(cloud, strays);
  const std::vector<std::uint32_t> rest = complementOf(cloud.size(), g.points);
  StrayPoints s = findStrayPoints(selectPoints(cloud, rest), strays);
  for (std::uint32_t& i : s.setAside) i = rest[i];
  addGround(s, g.points);
  return s;
}

}  // namespace

StrayPoints findStrayAndGroundPoints(const geom::PointCloud& cloud, geom::UpAxis up, const StrayPointOptions& strays,
                                     const GroundOptions& ground, const MarkedNoiseOptions& noise) {
  const std::vector<std::uint32_t> marked = findMarkedNoise(cloud, noise);
  const std::vector<std::uint32_t> repeated = findRepeatedPoints(cloud);
  if (marked.empty() && repeated.empty()) return findStrayAndGround(cloud, up, strays, ground);
  std::vector<std::uint32_t> out;
  std::set_union(marked.begin(), marked.end(), repeated.begin(), repeated.end(), std::back_inserter(out));
  const std::vector<std::uint32_t> rest = complementOf(cloud.size(), out);
  StrayPoints s = findStrayAndGround(selectPoints(cloud, rest), up, strays, ground);
  for (std::uint32_t& i : s.setAside) i = rest[i];
  addSetAside(s, marked, StrayReason::MarkedNoise);
  addSetAside(s, repeated, StrayReason::Repeated);
  return s;
}

}  // namespace treesketch::cloud
