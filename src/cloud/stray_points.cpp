// Stray points set aside before modelling (see stray_points.h). The filters follow the field's
// practice (TreeQSM's filtering: small components of the cover sets and points with too few
// neighbours; CloudCompare's and PCL's radius outlier removal); the distances here are multiples
// of the cloud's own spacing, measured on a grid as the skeleton's voxel graph measures it.
#include "treesketch/cloud/stray_points.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>
#include <unordered_map>
#include <unordered_set>
#include <utility>

#include "treesketch/util/error.h"
#include "treesketch/util/union_find.h"

namespace treesketch::cloud {

namespace {

struct Cell {
  std::int64_t x = 0, y = 0, z = 0;
  bool operator==(const Cell& o) const { return x == o.x && y == o.y && z == o.z; }
};

struct CellHash {
  std::size_t operator()(const Cell& c) const {
    std::uint64_t h = static_cast<std::uint64_t>(c.x) * 0x9E3779B97F4A7C15ULL;
    h ^= static_cast<std::uint64_t>(c.y) * 0xC2B2AE3D27D4EB4FULL + (h << 6) + (h >> 2);
    h ^= static_cast<std::uint64_t>(c.z) * 0x165667B19E3779F9ULL + (h << 6) + (h >> 2);
    return static_cast<std::size_t>(h);
  }
};

/// Cell coordinates beyond this are treated as out of the grid (a point astronomically far, or
/// not finite): such a point is far from the tree by any measure.
constexpr double kMaxCellCoordinate = 4.0e18;

/// The cell of `p` in a grid of side `size` from `origin`; false when it does not fit.
bool cellOf(const geom::Vec3& p, const geom::Vec3& origin, double size, Cell* out) {
  double c[3];
  for (int k = 0; k < 3; ++k) {
    c[k] = std::floor((p[k] - origin[k]) / size);
    if (!(std::fabs(c[k]) < kMaxCellCoordinate)) return false;
  }
  *out = {static_cast<std::int64_t>(c[0]), static_cast<std::int64_t>(c[1]), static_cast<std::int64_t>(c[2])};
  return true;
}

/// The box of the [q, 1 − q] quantiles of each coordinate, over at most ~100k points taken at a
/// fixed stride (deterministic).
geom::BBox coreBox(const geom::PointCloud& cloud, double q) {
  const std::size_t n = cloud.size();
  const std::size_t stride = std::max<std::size_t>(1, n / 100000);
  geom::BBox box;
  std::vector<double> v;
  v.reserve(n / stride + 1);
  for (int k = 0; k < 3; ++k) {
    v.clear();
    for (std::size_t i = 0; i < n; i += stride)
      if (std::isfinite(cloud.positions[i][k])) v.push_back(cloud.positions[i][k]);
    if (v.empty()) return {};
    const auto lo = static_cast<std::size_t>(q * static_cast<double>(v.size() - 1));
    const std::size_t hi = v.size() - 1 - lo;
    std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(lo), v.end());
    box.min[k] = v[lo];
    std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(hi), v.end());
    box.max[k] = v[hi];
  }
  return box;
}

/// Point spacing from occupancy inside `core`: a surface sampled every s puts about (c/s)² points
/// in an occupied cell of side c.
double measureSpacing(const geom::PointCloud& cloud, const geom::BBox& core, double cellsPerDiagonal) {
  const double c = core.diagonal() / cellsPerDiagonal;
  std::unordered_map<Cell, std::uint32_t, CellHash> count;
  std::size_t inside = 0;
  for (const geom::Vec3& p : cloud.positions) {
    if (!((p.array() >= core.min.array()).all() && (p.array() <= core.max.array()).all())) continue;
    Cell cell;
    if (!cellOf(p, core.min, c, &cell)) continue;
    ++count[cell];
    ++inside;
  }
  if (count.empty()) return c;
  const double perCell = static_cast<double>(inside) / static_cast<double>(count.size());
  return c / std::sqrt(std::max(perCell, 1.0));
}

/// The grid of linking cells: each point's cell (or -1 off the grid) and the cells' components.
struct LinkGrid {
  std::vector<std::int32_t> pointCell;  ///< per point: its cell, -1 when off the grid
  std::vector<Cell> cells;
  std::vector<std::uint32_t> cellComponent;  ///< per cell: its component (dense labels)
  std::vector<std::size_t> componentPoints;  ///< per component: its point count
};

LinkGrid linkCells(const geom::PointCloud& cloud, const geom::Vec3& origin, double link) {
  LinkGrid g;
  std::unordered_map<Cell, std::int32_t, CellHash> index;
  g.pointCell.resize(cloud.size(), -1);
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    Cell cell;
    if (!cellOf(cloud.positions[i], origin, link, &cell)) continue;
    auto [it, added] = index.emplace(cell, static_cast<std::int32_t>(g.cells.size()));
    if (added) g.cells.push_back(cell);
    g.pointCell[i] = it->second;
  }
  util::UnionFind sets(g.cells.size());
  for (std::size_t a = 0; a < g.cells.size(); ++a)
    for (int dx = -1; dx <= 1; ++dx)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dz = -1; dz <= 1; ++dz) {
          const Cell& c = g.cells[a];
          auto it = index.find({c.x + dx, c.y + dy, c.z + dz});
          if (it != index.end()) sets.unite(static_cast<std::uint32_t>(a), static_cast<std::uint32_t>(it->second));
        }
  std::unordered_map<std::uint32_t, std::uint32_t> label;
  g.cellComponent.resize(g.cells.size());
  for (std::size_t a = 0; a < g.cells.size(); ++a) {
    auto [it, added] =
        label.emplace(sets.find(static_cast<std::uint32_t>(a)), static_cast<std::uint32_t>(label.size()));
    g.cellComponent[a] = it->second;
  }
  g.componentPoints.assign(label.size(), 0);
  for (std::int32_t c : g.pointCell)
    if (c >= 0) ++g.componentPoints[g.cellComponent[static_cast<std::size_t>(c)]];
  return g;
}

/// The coarse cell (side nearLinks linking cells) holding linking cell `c`.
Cell coarseOf(const Cell& c, double nearLinks) {
  auto f = [&](std::int64_t v) { return static_cast<std::int64_t>(std::floor(static_cast<double>(v) / nearLinks)); };
  return {f(c.x), f(c.y), f(c.z)};
}

/// Per component: 2 = the bulk (the largest and those with bulkShare of the points), 1 = within
/// nearLinks linking cells of the bulk, 0 = farther.
std::vector<char> componentPlaces(const LinkGrid& g, std::size_t points, const StrayPointOptions& o) {
  const std::size_t n = g.componentPoints.size();
  std::vector<char> place(n, 0);
  const auto largest = static_cast<std::size_t>(std::max_element(g.componentPoints.begin(), g.componentPoints.end()) -
                                                g.componentPoints.begin());
  for (std::size_t k = 0; k < n; ++k)
    if (k == largest || static_cast<double>(g.componentPoints[k]) >= o.bulkShare * static_cast<double>(points))
      place[k] = 2;
  std::unordered_set<Cell, CellHash> bulkCoarse;
  for (std::size_t a = 0; a < g.cells.size(); ++a)
    if (place[g.cellComponent[a]] == 2) bulkCoarse.insert(coarseOf(g.cells[a], o.nearLinks));
  for (std::size_t a = 0; a < g.cells.size(); ++a) {
    const std::uint32_t k = g.cellComponent[a];
    if (place[k]) continue;
    const Cell c = coarseOf(g.cells[a], o.nearLinks);
    for (int dx = -1; dx <= 1 && !place[k]; ++dx)
      for (int dy = -1; dy <= 1 && !place[k]; ++dy)
        for (int dz = -1; dz <= 1 && !place[k]; ++dz)
          if (bulkCoarse.count({c.x + dx, c.y + dy, c.z + dz})) place[k] = 1;
  }
  return place;
}

void checkOptions(const StrayPointOptions& o) {
  if (!(o.coreQuantile >= 0 && o.coreQuantile < 0.5) || !(o.spacingCellsPerDiagonal >= 1) || !(o.linkSpacings > 0) ||
      !(o.bulkShare > 0 && o.bulkShare <= 1) || !(o.nearLinks >= 1) || !(o.maxShare >= 0 && o.maxShare <= 1) ||
      o.minComponentPoints < 1 || !std::isfinite(o.spacingCellsPerDiagonal) || !std::isfinite(o.linkSpacings) ||
      !std::isfinite(o.nearLinks))
    throw OptionsError(
        "stray points: options out of range (coreQuantile in [0, 0.5), spacingCellsPerDiagonal >= 1, "
        "linkSpacings > 0, bulkShare in (0, 1], nearLinks >= 1, minComponentPoints >= 1, maxShare in [0, 1])");
}

}  // namespace

StrayPoints findStrayPoints(const geom::PointCloud& cloud, const StrayPointOptions& o) {
  checkOptions(o);
  StrayPoints out;
  if (!o.enabled || cloud.size() < 16) return out;
  const geom::BBox core = coreBox(cloud, o.coreQuantile);
  if (!(core.diagonal() > 0) || !std::isfinite(core.diagonal())) return out;
  out.spacing = measureSpacing(cloud, core, o.spacingCellsPerDiagonal);
  out.linkDistance = o.linkSpacings * out.spacing;
  if (!(out.linkDistance > 0)) return out;
  const LinkGrid g = linkCells(cloud, core.min, out.linkDistance);
  out.components = g.componentPoints.size();
  if (g.componentPoints.empty()) return out;
  const std::vector<char> place = componentPlaces(g, cloud.size(), o);
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    const std::int32_t cell = g.pointCell[i];
    StrayReason why = StrayReason::Far;  // off the grid: astronomically far
    if (cell >= 0) {
      const std::uint32_t k = g.cellComponent[static_cast<std::size_t>(cell)];
      const bool small = g.componentPoints[k] < static_cast<std::size_t>(o.minComponentPoints);
      if (place[k] == 2 || (place[k] == 1 && !small)) continue;
      why = place[k] == 1 ? StrayReason::Isolated : StrayReason::Far;
    }
    out.setAside.push_back(static_cast<std::uint32_t>(i));
    out.reasons.push_back(why);
    ++(why == StrayReason::Far ? out.far : out.isolated);
  }
  if (static_cast<double>(out.count()) > o.maxShare * static_cast<double>(cloud.size())) {
    out.setAside.clear();
    out.reasons.clear();
    out.far = out.isolated = 0;
    out.tooSparse = true;
  }
  return out;
}

geom::PointCloud selectPoints(const geom::PointCloud& cloud, const std::vector<std::uint32_t>& indices) {
  geom::PointCloud out;
  out.up = cloud.up;
  auto pick = [&](const auto& from, auto& to) {
    if (from.size() != cloud.size()) return;
    to.reserve(indices.size());
    for (std::uint32_t i : indices) to.push_back(from[i]);
  };
  pick(cloud.positions, out.positions);
  pick(cloud.station, out.station);
  pick(cloud.meshId, out.meshId);
  pick(cloud.scanner, out.scanner);
  pick(cloud.intensity, out.intensity);
  pick(cloud.color, out.color);
  pick(cloud.classification, out.classification);
  return out;
}

geom::PointCloud keptPoints(const geom::PointCloud& cloud, const StrayPoints& strays) {
  if (strays.empty()) return cloud;
  std::vector<std::uint32_t> keep;
  keep.reserve(cloud.size() - strays.count());
  std::size_t s = 0;
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    if (s < strays.setAside.size() && strays.setAside[s] == i) {
      ++s;
      continue;
    }
    keep.push_back(static_cast<std::uint32_t>(i));
  }
  return selectPoints(cloud, keep);
}

std::vector<std::uint32_t> findMarkedNoise(const geom::PointCloud& cloud, const MarkedNoiseOptions& options) {
  std::vector<std::uint32_t> out;
  if (!options.enabled || cloud.classification.size() != cloud.size()) return out;
  for (std::size_t i = 0; i < cloud.size(); ++i)
    if (cloud.classification[i] == kLowNoiseClass || cloud.classification[i] == kHighNoiseClass)
      out.push_back(static_cast<std::uint32_t>(i));
  return out;
}

std::vector<std::uint32_t> findRepeatedPoints(const geom::PointCloud& cloud) {
  // Sorted by a hash of the position's bits (16-byte keys, not the positions themselves: a third
  // of the time of sorting indices by coordinates), then equal positions looked for in each run of
  // equal hashes, which is one point long but for repeats and rare collisions.
  const auto bits = [](double v) {
    std::uint64_t b = 0;
    v += 0.0;  // -0.0 and 0.0 are one position
    std::memcpy(&b, &v, sizeof b);
    return b;
  };
  const auto mix = [](std::uint64_t h) {  // a 64-bit finaliser (MurmurHash3's constants)
    h ^= h >> 33;
    h *= 0xff51afd7ed558ccdULL;
    h ^= h >> 33;
    h *= 0xc4ceb9fe1a85ec53ULL;
    return h ^ (h >> 33);
  };
  std::vector<std::pair<std::uint64_t, std::uint32_t>> keys(cloud.size());
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    const geom::Vec3& p = cloud.positions[i];
    keys[i] = {mix(bits(p.x()) ^ mix(bits(p.y()) ^ mix(bits(p.z())))), static_cast<std::uint32_t>(i)};
  }
  std::sort(keys.begin(), keys.end());
  std::vector<std::uint32_t> out;
  for (std::size_t a = 0, b = 0; a < keys.size(); a = b) {
    for (b = a + 1; b < keys.size() && keys[b].first == keys[a].first;) ++b;
    for (std::size_t k = a + 1; k < b; ++k)  // indices increase within the run
      for (std::size_t j = a; j < k; ++j)
        if (cloud.positions[keys[k].second] == cloud.positions[keys[j].second]) {
          out.push_back(keys[k].second);
          break;
        }
  }
  std::sort(out.begin(), out.end());
  return out;
}

void addSetAside(StrayPoints& strays, const std::vector<std::uint32_t>& added, StrayReason reason) {
  if (added.empty()) return;
  std::size_t& counted = reason == StrayReason::Ground        ? strays.ground
                         : reason == StrayReason::MarkedNoise ? strays.markedNoise
                         : reason == StrayReason::Repeated    ? strays.repeated
                         : reason == StrayReason::Far         ? strays.far
                                                              : strays.isolated;
  std::vector<std::uint32_t> points;
  std::vector<StrayReason> reasons;
  points.reserve(strays.setAside.size() + added.size());
  reasons.reserve(points.capacity());
  std::size_t a = 0, b = 0;
  while (a < strays.setAside.size() || b < added.size()) {
    const bool takeStray = b == added.size() || (a < strays.setAside.size() && strays.setAside[a] <= added[b]);
    if (takeStray) {
      if (b < added.size() && added[b] == strays.setAside[a]) ++b;
      points.push_back(strays.setAside[a]);
      reasons.push_back(strays.reasons[a++]);
    } else {
      points.push_back(added[b++]);
      reasons.push_back(reason);
      ++counted;
    }
  }
  strays.setAside = std::move(points);
  strays.reasons = std::move(reasons);
}

void addGround(StrayPoints& strays, const std::vector<std::uint32_t>& ground) {
  addSetAside(strays, ground, StrayReason::Ground);
}

std::vector<std::uint32_t> setAsideFor(const StrayPoints& strays, StrayReason reason) {
  std::vector<std::uint32_t> out;
  for (std::size_t k = 0; k < strays.setAside.size() && k < strays.reasons.size(); ++k)
    if (strays.reasons[k] == reason) out.push_back(strays.setAside[k]);
  return out;
}

double measurePointSpacing(const geom::PointCloud& cloud, const StrayPointOptions& options) {
  if (cloud.empty()) return 0.0;
  const geom::BBox core = coreBox(cloud, options.coreQuantile);
  if (!(core.diagonal() > 0)) return 0.0;
  return measureSpacing(cloud, core, options.spacingCellsPerDiagonal);
}

std::string strayPointsLine(const StrayPoints& s) {
  if (s.tooSparse && s.empty()) return "no stray point set aside (the cloud is too sparse for the rule)";
  if (s.empty()) return "no stray point set aside";
  char buf[320];
  if (s.ground > 0 || s.markedNoise > 0 || s.repeated > 0) {
    char noise[80] = "", repeated[80] = "";
    if (s.markedNoise > 0) std::snprintf(noise, sizeof noise, "%zu marked as noise by the file, ", s.markedNoise);
    if (s.repeated > 0)
      std::snprintf(repeated, sizeof repeated, "%zu repeating an earlier point's position, ", s.repeated);
    std::snprintf(
        buf, sizeof buf,
        "%zu point%s set aside (%s%s%zu on the ground, %zu far from the tree, %zu isolated; linking distance %.3g)",
        s.count(), s.count() == 1 ? "" : "s", noise, repeated, s.ground, s.far, s.isolated, s.linkDistance);
  } else {
    std::snprintf(buf, sizeof buf,
                  "%zu stray point%s set aside (%zu far from the tree, %zu isolated; linking distance %.3g)", s.count(),
                  s.count() == 1 ? "" : "s", s.far, s.isolated, s.linkDistance);
  }
  return buf;
}

}  // namespace treesketch::cloud
