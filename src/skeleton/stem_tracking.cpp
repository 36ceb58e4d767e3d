#include "skeleton/stem_tracking.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numbers>
#include <utility>

#include "skeleton/node_tree.h"
#include "treesketch/fit/circle_fit.h"

namespace treesketch::skeleton::detail {
namespace {

using geom::Vec2;
using geom::Vec3;

// The base slab: this many voxels above the tree's lowest voxel.
constexpr double kBaseSlabVoxels = 6.0;
// The base circle is looked for within this many times the root region's width (plus voxels) of
// its centroid: the lowest voxels may all lie on one side of the stem.
constexpr double kBaseSearchSpreads = 4.0, kBaseSearchVoxels = 10.0;
// Base slabs tried, one above the other.
constexpr int kBaseTries = 3;
// A slab is one radius tall (at least kMinSlabVoxels voxels) and the next one a radius further.
constexpr double kSlabRadii = 1.0;
constexpr double kMinSlabVoxels = 3.0;
constexpr double kStepRadii = 1.0;
// A slab with too few voxels for a circle is made twice as tall, up to this many times (8 radii
// at most: a stem is straight over that length, and a sparsely scanned one needs it).
constexpr int kMaxSlabDoublings = 3;
// Candidates: within this many radii (plus a voxel) of the predicted axis.
constexpr double kSearchRadii = 1.6;
// Inlier band of the circle: 15 % of the candidate circle's radius (a stem's cross-section is a
// polygon in a mesh, 13 % inside its circle's radius at six sides, and bark is rough), at least
// half a voxel (the voxel centroids' own scatter about the surface).
constexpr double kBandRadii = 0.15;
constexpr double kMinBandVoxels = 0.5;
// A slab is a stem's cross-section when its circle holds this share of the candidates (a fork's
// two limbs, or foliage, leave far fewer on any one circle)...
constexpr double kMinInlierShare = 0.6;
// ...at least this many voxels...
constexpr int kMinVoxels = 6;
// ...with at most this share of them well inside it (deeper than the band: a stem is hollow in a
// scan; the bases of a bush's stems, or a real scan's base with its roots, are not)...
constexpr double kMaxInsideShare = 0.2;
// ...around at least this much of the circle (one station sees a little more than half a stem)...
constexpr double kMinArcDegrees = 150.0;
// ...with a radius within these factors of the last one, its centre within half a radius (plus a
// voxel) of the predicted axis.
constexpr double kMinRadiusRatio = 0.6, kMaxRadiusRatio = 1.2;
constexpr double kMaxCentreMoveRadii = 0.5;
// The base's ring must be at least this many voxels in radius: a thinner stem's level sets are a
// voxel or two across and hold no ring to break.
constexpr double kMinStemRadiusVoxels = 2.0;
// The axis runs through the last this many centres; a stem leaning more than kMaxLeanDeg from the
// up axis is a limb, not the stem, and tracking stops.
constexpr int kAxisSamples = 4;
constexpr double kMaxLeanDeg = 45.0;
// One slab may fail (an occlusion, a branch's base): the tracker steps over it; two stop it.
constexpr int kMaxMisses = 1;
// The tube holds voxels within this many radii plus a voxel of the axis.
constexpr double kTubeRadii = 1.0;
// When no stem is found from the root region, it may stand beside it: a conifer's lowest
// branches reach the ground beside its foot and lower than it. The stem is then looked for where
// the tree is most continuously vertical: the block of 3×3 voxel columns (a stem up to 1.5 voxels
// in radius lies in one; a thicker one's wall does) occupied over the longest run of heights, runs
// bridging gaps of this many layers (an occlusion). A stem rises through the crown; a branch
// leaves a column within a few layers. The run must be at least one base slab tall...
constexpr int kColumnGapLayers = 1;
// ...it must start where a stem's foot is, within the base slabs above the tree's lowest point (a
// stem stands on the ground; a column starting higher is a limb or a bush's stem rising from the
// crown: bush_2_s6644's sphere scan, whose column starts half way up, took one for its stem and
// doubled its backward error)...
// ...and the root region's own blocks must rise less than this share of it: it is then no stem's
// foot (branch tips on the ground), where a bush's other stems, or the foot of a stem too thin to
// show a ring from the root region, rise about as far (spruce 0.14; bush, thin stems 0.62-1.0).
constexpr double kMaxRootRunShare = 0.5;
// There the stem's rings may be as small as this many voxels in radius (the smallest whose voxel
// centroids circle an empty centre), where kMinStemRadiusVoxels holds from the root region: with
// its foot in the root region a thinner stem's level sets are its cross-sections, centred on its
// axis (tracking such stems from the root region measured worse: docs/notes/leaf_on_skeleton.md);
// beside it, the level sets near the stem's foot are not its cross-sections, however thin it is.
constexpr double kMinColumnRingVoxels = 1.0;
// A whorl: where a slab is no cross-section because branches leave the stem in it (a conifer's
// whorl; in leaf, the context pass's wood beside its stem), a stem found beside the root region
// (the conifer's case) is looked for again in the slab's first surface seen from the predicted
// axis (firstSurfaceSeen), in at least this many sectors (a sector about one voxel wide at the
// stem's radius; eight at 1.5 voxels). From the root region the tracker does not: there a broadleaf
// tree's crown base is where it must stop (adtree_tree7 tracked past its fork: DBH 8.3 -> 12.4 cm).
constexpr int kMinSectors = 8;

struct Frame {
  Vec3 u, w;
};

Frame frameFor(const Vec3& d) {
  const Vec3 a = std::abs(d.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY();
  const Vec3 u = d.cross(a).normalized();
  return {u, d.cross(u)};
}

// The share of the circle its inliers cover, degrees: 360 minus the widest gap between them.
double coveredDegrees(const std::vector<Vec2>& pts, const fit::CircleFitResult& r) {
  std::vector<double> angle;
  for (std::uint32_t i : r.inliers) angle.push_back(std::atan2(pts[i].y() - r.centre.y(), pts[i].x() - r.centre.x()));
  if (angle.size() < 2) return 0;
  std::sort(angle.begin(), angle.end());
  double gap = angle.front() + 2 * std::numbers::pi - angle.back();
  for (std::size_t k = 1; k < angle.size(); ++k) gap = std::max(gap, angle[k] - angle[k - 1]);
  return 360.0 - gap * 180.0 / std::numbers::pi;
}

// The voxels of a slab (plane coordinates about the predicted axis) that are the first surface
// seen from the axis: in each angular sector about one voxel wide at `radius`, those within the
// fit's inlier band of the sector's nearest voxel. A stem's branches leave it outward, so behind
// its bark in their sectors; another limb or foliage is the first surface of its own sectors.
std::vector<Vec2> firstSurfaceSeen(const std::vector<Vec2>& pts, double radius, double voxel) {
  const int sectors = std::max(kMinSectors, static_cast<int>(std::ceil(2 * std::numbers::pi * radius / voxel)));
  const double band = std::max(kMinBandVoxels * voxel, kBandRadii * radius);
  auto sectorOf = [&](const Vec2& q) {
    const double a = std::atan2(q.y(), q.x()) + std::numbers::pi;
    return std::min(sectors - 1, static_cast<int>(a / (2 * std::numbers::pi) * sectors));
  };
  std::vector<double> nearest(sectors, std::numeric_limits<double>::infinity());
  for (const Vec2& q : pts) nearest[sectorOf(q)] = std::min(nearest[sectorOf(q)], q.norm());
  std::vector<Vec2> kept;
  for (const Vec2& q : pts)
    if (q.norm() <= nearest[sectorOf(q)] + band) kept.push_back(q);
  return kept;
}

// A circle through the voxels of the slab |(p - c)·d| ≤ halfHeight within `search` of the axis
// (c, d); false when the slab is not a stem's cross-section (see the constants).
enum class Slab { TooFew, NoStem, Stem };

Slab fitSlab(const VoxelGraph& g, const Vec3& c, const Vec3& d, double halfHeight, double search, double minRadius,
             double maxRadius, StemSample& out, bool firstSurface = false) {
  const Frame f = frameFor(d);
  std::vector<Vec2> pts;
  for (const Vec3& p : g.positions) {
    const Vec3 q = p - c;
    const double t = q.dot(d);
    if (std::abs(t) > halfHeight) continue;
    const Vec3 radial = q - t * d;
    if (radial.squaredNorm() > search * search) continue;
    pts.emplace_back(radial.dot(f.u), radial.dot(f.w));
  }
  if (firstSurface) pts = firstSurfaceSeen(pts, 0.5 * (minRadius + maxRadius), g.voxelSize);
  if (static_cast<int>(pts.size()) < kMinVoxels) return Slab::TooFew;
  fit::CircleFitOptions o;
  o.inlierThreshold = kMinBandVoxels * g.voxelSize;
  o.inlierThresholdRelative = kBandRadii;
  o.minInliers = kMinVoxels;
  o.minInlierFraction = kMinInlierShare;
  o.minArcDegrees = 0;  // the fit's own arc test counts well-filled bins: a sparse slab has none
  o.minRadius = minRadius;
  o.maxRadius = maxRadius;
  o.inputFinite = true;
  const fit::CircleFitResult r = fit::fitCircleRansac(pts, o);
  if (!r.ok || coveredDegrees(pts, r) < kMinArcDegrees) return Slab::NoStem;
  // A stem's cross-section is empty inside; a circle through a ring of stems (a bush's base) or
  // around a stem and its neighbours' near sides has voxels well inside it.
  const double band = std::max(o.inlierThreshold, o.inlierThresholdRelative * r.radius);
  std::size_t inside = 0;
  for (const Vec2& q : pts) inside += (q - r.centre).norm() < r.radius - band ? 1 : 0;
  if (static_cast<double>(inside) > kMaxInsideShare * static_cast<double>(pts.size())) return Slab::NoStem;
  out.centre = c + r.centre.x() * f.u + r.centre.y() * f.w;
  out.radius = r.radius;
  return Slab::Stem;
}

}  // namespace

namespace {

/// The stem followed up from `base` slab by slab (see the constants); the samples, `base` first.
std::vector<StemSample> followStem(const VoxelGraph& g, const StemSample& base, const Vec3& up, bool throughWhorls) {
  const double voxel = g.voxelSize;
  std::vector<StemSample> stem{base};
  Vec3 axis = up, centre = base.centre;
  double radius = base.radius;
  const double maxLeanCos = std::cos(kMaxLeanDeg * std::numbers::pi / 180.0);
  int misses = 0;
  const std::size_t cap = g.size();  // more steps than voxels: no stem is that long
  while (stem.size() < cap) {
    const Vec3 predicted = centre + std::max(kStepRadii * radius, 2 * voxel) * axis;
    StemSample next;
    Slab slab = Slab::TooFew;
    double half = 0;
    for (int k = 0; k <= kMaxSlabDoublings && slab == Slab::TooFew; ++k) {
      half = 0.5 * std::max(kSlabRadii * radius, kMinSlabVoxels * voxel) * std::ldexp(1.0, k);
      slab = fitSlab(g, predicted, axis, half, kSearchRadii * radius + voxel, kMinRadiusRatio * radius,
                     kMaxRadiusRatio * radius, next);
    }
    if (slab == Slab::NoStem && throughWhorls)
      slab = fitSlab(g, predicted, axis, half, kSearchRadii * radius + voxel, kMinRadiusRatio * radius,
                     kMaxRadiusRatio * radius, next, true);
    // Through whorls the centre's allowance beyond half a radius is the centroids' own scatter
    // (half a voxel), not a whole voxel: a stem a voxel thick has a limb's near side a voxel off,
    // and with a voxel the spruce's track walked into a limb above 7.5 m (notes/leaf_on_skeleton.md).
    const double slack = throughWhorls ? kMinBandVoxels * voxel : voxel;
    const bool ok = slab == Slab::Stem && (next.centre - predicted).norm() <= kMaxCentreMoveRadii * radius + slack;
    if (!ok) {
      if (++misses > kMaxMisses) break;
      centre = predicted;
      continue;
    }
    misses = 0;
    stem.push_back(next);
    centre = next.centre;
    radius = next.radius;
    const std::size_t from = stem.size() > kAxisSamples ? stem.size() - kAxisSamples : 0;
    const Vec3 d = safeNormalized(stem.back().centre - stem[from].centre, axis);
    if (d.dot(up) < maxLeanCos) break;
    axis = d;
  }
  return stem;
}

// A 3×3 block of voxel columns (indices along the frame's u and w) and its longest run of
// occupied layers (layer 0: the tree's lowest voxel).
struct Column {
  long iu = 0, iw = 0;
  int first = 0, layers = 0;
};

std::pair<long, long> columnOf(const Vec3& p, const Frame& f, double voxel) {
  return {static_cast<long>(std::floor(p.dot(f.u) / voxel)), static_cast<long>(std::floor(p.dot(f.w) / voxel))};
}

// The longest run in sorted, unique layers, gaps of kColumnGapLayers bridged: {first, length}.
std::pair<int, int> longestRun(const std::vector<int>& layers) {
  std::pair<int, int> best{0, 0};
  std::size_t start = 0;
  for (std::size_t k = 1; k <= layers.size(); ++k) {
    if (k < layers.size() && layers[k] - layers[k - 1] <= kColumnGapLayers + 1) continue;
    const int length = layers[k - 1] - layers[start] + 1;
    if (length > best.second) best = {layers[start], length};
    start = k;
  }
  return best;
}

// Each occupied voxel column's layers, sorted, each once.
using ColumnLayers = std::map<std::pair<long, long>, std::vector<int>>;

ColumnLayers columnLayers(const VoxelGraph& g, double lowest, const Frame& f, geom::UpAxis upAxis) {
  ColumnLayers layersOf;
  for (const Vec3& p : g.positions)
    layersOf[columnOf(p, f, g.voxelSize)].push_back(
        static_cast<int>(std::floor((geom::height(p, upAxis) - lowest) / g.voxelSize)));
  for (auto& entry : layersOf) {
    std::vector<int>& layers = entry.second;
    std::sort(layers.begin(), layers.end());
    layers.erase(std::unique(layers.begin(), layers.end()), layers.end());
  }
  return layersOf;
}

// The block of columns around `key` and its longest run.
Column blockRun(const ColumnLayers& layersOf, const std::pair<long, long>& key) {
  std::vector<int> block;
  for (long du = -1; du <= 1; ++du)
    for (long dw = -1; dw <= 1; ++dw) {
      const auto it = layersOf.find({key.first + du, key.second + dw});
      if (it != layersOf.end()) block.insert(block.end(), it->second.begin(), it->second.end());
    }
  std::sort(block.begin(), block.end());
  block.erase(std::unique(block.begin(), block.end()), block.end());
  const auto [first, length] = longestRun(block);
  return {key.first, key.second, first, length};
}

// The block of columns with the longest run (ties: the first in index order). A run bridging
// single gaps over n occupied layers is at most 2n - 1 long: blocks holding too few layers to
// beat the block of the fullest column, or the best so far, are not merged.
Column longestColumn(const ColumnLayers& layersOf) {
  auto fullest = layersOf.begin();
  for (auto it = layersOf.begin(); it != layersOf.end(); ++it)
    if (it->second.size() > fullest->second.size()) fullest = it;
  const int floor = fullest == layersOf.end() ? 0 : blockRun(layersOf, fullest->first).layers;
  Column best;
  for (const auto& entry : layersOf) {
    std::size_t held = 0;
    for (long du = -1; du <= 1; ++du)
      for (long dw = -1; dw <= 1; ++dw) {
        const auto it = layersOf.find({entry.first.first + du, entry.first.second + dw});
        if (it != layersOf.end()) held += it->second.size();
      }
    const auto bound = static_cast<int>(2 * held) - 1;
    if (bound < floor || bound <= best.layers) continue;
    const Column c = blockRun(layersOf, entry.first);
    if (c.layers > best.layers) best = c;
  }
  return best;
}

// The stem's cross-section in the slab of `column` from `bottom` (one base slab tall, doubled
// while too few voxels): circles of radius about rho, doubled from the smallest ring, looked for
// within rho's search of the block's voxels' centroid in the slab, as followStem looks.
bool columnBase(const VoxelGraph& g, const Column& column, const Frame& f, double bottom, geom::UpAxis upAxis,
                double maxSearch, StemSample& base) {
  const double voxel = g.voxelSize;
  const Vec3 up = geom::upVector(upAxis);
  for (int k = 0; k <= kMaxSlabDoublings; ++k) {
    const double half = 0.5 * kBaseSlabVoxels * voxel * std::ldexp(1.0, k);
    Vec3 sum = Vec3::Zero();
    int count = 0;
    for (const Vec3& p : g.positions) {
      const auto [iu, iw] = columnOf(p, f, voxel);
      const double h = geom::height(p, upAxis) - bottom;
      if (std::abs(iu - column.iu) > 1 || std::abs(iw - column.iw) > 1 || h < 0 || h > 2 * half) continue;
      sum += p;
      ++count;
    }
    if (count == 0) continue;
    const Vec3 centroid = sum / count;
    const Vec3 centre = centroid + (bottom + half - geom::height(centroid, upAxis)) * up;
    bool tooFew = true;
    for (double rho = kMinColumnRingVoxels * voxel; kSearchRadii * rho + voxel <= maxSearch; rho *= 2) {
      const Slab slab =
          fitSlab(g, centre, up, half, kSearchRadii * rho + voxel,
                  std::max(kMinColumnRingVoxels * voxel, kMinRadiusRatio * rho), kMaxRadiusRatio * rho, base);
      if (slab == Slab::Stem) return true;
      tooFew = tooFew && slab == Slab::TooFew;
    }
    if (!tooFew) return false;
  }
  return false;
}

// The stem found where the tree is most continuously vertical (see kColumnGapLayers) and followed
// from there down and up, when the root region is beside it; the samples, lowest first, or none.
std::vector<StemSample> stemFromColumn(const VoxelGraph& g, const std::vector<std::uint32_t>& root, double lowest,
                                       geom::UpAxis upAxis, double maxSearch) {
  const double voxel = g.voxelSize;
  const Vec3 up = geom::upVector(upAxis);
  const Frame f = frameFor(up);
  const ColumnLayers layersOf = columnLayers(g, lowest, f, upAxis);
  const Column column = longestColumn(layersOf);
  if (column.layers < kBaseSlabVoxels || column.first > kBaseTries * kBaseSlabVoxels) return {};
  int rootRun = 0;  // the root region's own rise (see kMaxRootRunShare)
  for (std::uint32_t v : root)
    rootRun = std::max(rootRun, blockRun(layersOf, columnOf(g.positions[v], f, voxel)).layers);
  if (rootRun >= kMaxRootRunShare * column.layers) return {};
  for (int j = 0; j < kBaseTries; ++j) {
    StemSample base;
    const double bottom = lowest + (column.first + j * kBaseSlabVoxels) * voxel;
    if (!columnBase(g, column, f, bottom, upAxis, maxSearch, base)) continue;
    std::vector<StemSample> below = followStem(g, base, -up, true);
    const std::vector<StemSample> above = followStem(g, base, up, true);
    // No stem under the tree's lowest voxel: a slab there is empty until, its height doubled, it
    // reaches what lies on the ground round the foot (a conifer's dead branches). The samples stop
    // there; trackStem carries the stem down to the lowest voxel along its first segment.
    while (below.size() > 1 && geom::height(below.back().centre, upAxis) < lowest) below.pop_back();
    std::vector<StemSample> stem(below.rbegin(), below.rend() - 1);
    stem.insert(stem.end(), above.begin(), above.end());
    if (stem.size() >= 3) return stem;
  }
  return {};
}

}  // namespace

std::vector<StemSample> trackStem(const VoxelGraph& g, const std::vector<std::uint32_t>& root, geom::UpAxis upAxis,
                                  bool* besideRoot) {
  if (besideRoot) *besideRoot = false;
  if (root.empty() || g.size() == 0 || !(g.voxelSize > 0)) return {};
  const double voxel = g.voxelSize;
  const Vec3 up = geom::upVector(upAxis);
  // The base: the root region's centroid, raised to the middle of the base slab.
  double lowest = std::numeric_limits<double>::infinity();
  Vec3 mean = Vec3::Zero();
  for (std::uint32_t v : root) {
    lowest = std::min(lowest, geom::height(g.positions[v], upAxis));
    mean += g.positions[v];
  }
  mean /= static_cast<double>(root.size());
  double spread = 0;
  for (std::uint32_t v : root) {
    const Vec3 q = g.positions[v] - mean;
    spread = std::max(spread, (q - q.dot(up) * up).norm());
  }
  // The lowest slab may hold a closed mesh's end cap, or roots, or the ground's last points, or a
  // root flare much wider than the stem above it (a palm's swollen base): a base the stem cannot
  // be followed from gives way to the slab above it.
  std::vector<StemSample> stem;
  for (int j = 0; j < kBaseTries && stem.size() < 3; ++j) {
    StemSample base;
    Slab found = Slab::TooFew;
    for (int k = 0; k <= kMaxSlabDoublings && found == Slab::TooFew; ++k) {
      const double half = 0.5 * kBaseSlabVoxels * voxel * std::ldexp(1.0, k);
      const double bottom = lowest + j * kBaseSlabVoxels * voxel;
      const Vec3 centre = mean + (bottom + half - geom::height(mean, upAxis)) * up;
      const double search = kBaseSearchSpreads * spread + kBaseSearchVoxels * voxel;
      found = fitSlab(g, centre, up, half, search, kMinStemRadiusVoxels * voxel, search, base);
    }
    stem = found == Slab::Stem ? followStem(g, base, up, false) : std::vector<StemSample>{};
  }
  // No stem from the root region: it may lie beside the stem's foot (see kColumnGapLayers).
  const bool fromColumn = stem.size() < 3;
  if (fromColumn)
    stem = stemFromColumn(g, root, lowest, upAxis, kBaseSearchSpreads * spread + kBaseSearchVoxels * voxel);
  if (stem.size() < 3) return {};
  // The stem reaches down to the tree's lowest voxel, along its first segment: the lowest slabs
  // may have been skipped (see kBaseTries) or made tall.
  const double maxLeanCos = std::cos(kMaxLeanDeg * std::numbers::pi / 180.0);
  const Vec3 firstAxis = safeNormalized(stem[1].centre - stem[0].centre, up);
  const double drop = geom::height(stem[0].centre, upAxis) - lowest;
  if (drop > 0 && firstAxis.dot(up) > maxLeanCos)
    stem.insert(stem.begin(), StemSample{stem[0].centre - drop / firstAxis.dot(up) * firstAxis, stem[0].radius});
  // A stem found from the column with the root region at its foot after all is one the root
  // region did not show as a ring: thinner than kMinStemRadiusVoxels, left to the level sets.
  if (fromColumn && rootOnStem(g, stem, root)) return {};
  if (besideRoot) *besideRoot = fromColumn;
  return stem;
}

std::vector<StemSample> trackedStem(const GeodesicLevels& levels) {
  std::vector<StemSample> stem;
  for (std::size_t k = 0; k < levels.stemCentres.size() && k < levels.stemRadii.size(); ++k)
    stem.push_back({levels.stemCentres[k], levels.stemRadii[k]});
  return stem;
}

bool rootOnStem(const VoxelGraph& g, const std::vector<StemSample>& stem, const std::vector<std::uint32_t>& root) {
  std::size_t in = 0;
  for (std::uint32_t v : root) in += inStemTube(stem, g.voxelSize, g.positions[v]) ? 1 : 0;
  return 2 * in > root.size();
}

std::vector<std::uint32_t> stemFoot(const VoxelGraph& g, const std::vector<StemSample>& stem,
                                    const std::vector<char>& reachable, geom::UpAxis up, double height) {
  std::vector<std::uint32_t> tube;
  double lowest = std::numeric_limits<double>::infinity();
  for (std::size_t v = 0; v < g.size(); ++v)
    if (reachable[v] && inStemTube(stem, g.voxelSize, g.positions[v])) {
      tube.push_back(static_cast<std::uint32_t>(v));
      lowest = std::min(lowest, geom::height(g.positions[v], up));
    }
  std::vector<std::uint32_t> foot;
  for (std::uint32_t v : tube)
    if (geom::height(g.positions[v], up) <= lowest + height) foot.push_back(v);
  return foot;
}

StemSample stemAt(const std::vector<StemSample>& stem, const Vec3& p) {
  StemSample best = stem.front();
  double bestDistance = (p - best.centre).squaredNorm();
  for (std::size_t k = 0; k + 1 < stem.size(); ++k) {
    const Vec3 a = stem[k].centre, ab = stem[k + 1].centre - a;
    const double len2 = ab.squaredNorm();
    // Past the first and last samples the end segments go on straight (the tube reaches there).
    const double lo = k == 0 ? -std::numeric_limits<double>::infinity() : 0.0;
    const double hi = k + 2 == stem.size() ? std::numeric_limits<double>::infinity() : 1.0;
    const double t = len2 > 0 ? std::clamp((p - a).dot(ab) / len2, lo, hi) : 0.0;
    const Vec3 q = a + t * ab;
    const double d = (p - q).squaredNorm();
    if (d < bestDistance) {
      bestDistance = d;
      const double tr = std::clamp(t, 0.0, 1.0);
      best = {q, stem[k].radius + tr * (stem[k + 1].radius - stem[k].radius)};
    }
  }
  return best;
}

bool inStemTube(const std::vector<StemSample>& stem, double voxel, const Vec3& p) {
  for (std::size_t k = 0; k + 1 < stem.size(); ++k) {
    const Vec3 a = stem[k].centre, b = stem[k + 1].centre, ab = b - a;
    const double len2 = ab.squaredNorm();
    if (!(len2 > 0)) continue;
    // The first and last segments reach half a slab past their samples.
    const double len = std::sqrt(len2);
    const double lo = k == 0 ? -0.5 * std::max(kBaseSlabVoxels * voxel, stem[k].radius) / len : 0.0;
    const double hi =
        k + 2 == stem.size() ? 1.0 + 0.5 * std::max(kMinSlabVoxels * voxel, stem[k + 1].radius) / len : 1.0;
    const double t = (p - a).dot(ab) / len2;
    if (t < lo || t > hi) continue;
    const double tc = std::clamp(t, 0.0, 1.0);
    const double r = stem[k].radius + tc * (stem[k + 1].radius - stem[k].radius);
    if ((p - (a + t * ab)).norm() <= kTubeRadii * r + voxel) return true;
  }
  return false;
}

std::vector<char> stemTube(const VoxelGraph& g, const std::vector<StemSample>& stem) {
  std::vector<char> in(g.size(), 0);
  if (stem.size() < 2) return in;
  for (std::size_t v = 0; v < g.size(); ++v) in[v] = inStemTube(stem, g.voxelSize, g.positions[v]) ? 1 : 0;
  return in;
}

}  // namespace treesketch::skeleton::detail
