#include "treesketch/viewer/point_colors.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <iterator>
#include <cmath>
#include <limits>

#include "treesketch/compare/model_fit.h"
#include "treesketch/render/color_map.h"

namespace treesketch::viewer {

using geom::Vec3;

double distanceToCircle(const Vec3& p, const Circle3& circle) {
  Vec3 d = p - circle.centre;
  double h = d.dot(circle.normal);
  double radial = (d - h * circle.normal).norm();
  double dr = radial - circle.radius;
  return std::sqrt(h * h + dr * dr);
}

std::vector<Rgb> circleDistanceColors(const geom::PointCloud& cloud, const std::vector<Circle3>& circles,
                                      double maxDistance) {
  std::vector<Rgb> colors(cloud.size(), render::viridis(1.0));
  if (circles.empty() || cloud.empty()) return colors;
  double scale = maxDistance > 0 ? 1.0 / maxDistance : 1.0;
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, cloud.size(), 8192), [&](const auto& r) {
    for (std::size_t i = r.begin(); i < r.end(); ++i) {
      double best = std::numeric_limits<double>::infinity();
      for (const Circle3& c : circles) best = std::min(best, distanceToCircle(cloud.positions[i], c));
      colors[i] = render::viridis(best * scale);
    }
  });
  return colors;
}

void DistanceColorGrid::build(const geom::PointCloud& cloud, double maxDistance) {
  cloud_ = &cloud;
  size_ = cloud.size();
  maxDistance_ = maxDistance;
  const geom::BBox box = cloud.bounds();
  origin_ = box.empty() ? Vec3::Zero() : box.min;
  const Vec3 ext = box.extent();
  // Cells maxDistance wide, but at most ~2M cells (a tiny scale on a large cloud).
  cell_ = std::max(maxDistance, 1e-12);
  auto cellsFor = [&](double c) {
    double n = 1;
    for (int k = 0; k < 3; ++k) n *= std::floor(ext[k] / c) + 1;
    return n;
  };
  while (cellsFor(cell_) > 2e6) cell_ *= 1.5;
  std::size_t cells = 1;
  for (int k = 0; k < 3; ++k) {
    dims_[k] = static_cast<int>(std::floor(ext[k] / cell_)) + 1;
    cells *= static_cast<std::size_t>(dims_[k]);
  }
  std::vector<std::uint32_t> cellOf(size_);
  start_.assign(cells + 1, 0);
  for (std::size_t i = 0; i < size_; ++i) {
    std::size_t c = 0;
    for (int k = 2; k >= 0; --k) {
      int v = std::clamp(static_cast<int>(std::floor((cloud.positions[i][k] - origin_[k]) / cell_)), 0, dims_[k] - 1);
      c = c * static_cast<std::size_t>(dims_[k]) + static_cast<std::size_t>(v);
    }
    cellOf[i] = static_cast<std::uint32_t>(c);
    ++start_[c + 1];
  }
  for (std::size_t c = 0; c < cells; ++c) start_[c + 1] += start_[c];
  points_.resize(size_);
  std::vector<std::uint32_t> fill(start_.begin(), start_.end() - 1);
  for (std::size_t i = 0; i < size_; ++i) points_[fill[cellOf[i]]++] = static_cast<std::uint32_t>(i);
  best_.assign(size_, std::numeric_limits<double>::infinity());
  touched_.clear();
  surfaceKept_ = false;  // the kept surface colours were another cloud's
  surfacePieces_.clear();
  surface_.clear();
  cellMarked_.assign(cells, 0);
  markedCells_.clear();
}

void DistanceColorGrid::colors(const std::vector<Circle3>& circles, std::vector<Rgb>& out) {
  out.assign(size_, render::viridis(1.0));
  if (!cloud_ || circles.empty() || size_ == 0) return;
  const double scale = maxDistance_ > 0 ? 1.0 / maxDistance_ : 1.0;
  for (const Circle3& c : circles) {
    if (!c.centre.allFinite() || !std::isfinite(c.radius)) continue;
    // The circle's box grown by maxDistance: any point nearer than that lies inside.
    const Vec3 n = c.normal.normalized();
    Vec3 half;
    for (int k = 0; k < 3; ++k)
      half[k] =
          (n.allFinite() ? c.radius * std::sqrt(std::max(0.0, 1.0 - n[k] * n[k])) : std::abs(c.radius)) + maxDistance_;
    int lo[3], hi[3];
    for (int k = 0; k < 3; ++k) {
      lo[k] = std::clamp(static_cast<int>(std::floor((c.centre[k] - half[k] - origin_[k]) / cell_)), 0, dims_[k] - 1);
      hi[k] = std::clamp(static_cast<int>(std::floor((c.centre[k] + half[k] - origin_[k]) / cell_)), 0, dims_[k] - 1);
      if (c.centre[k] + half[k] < origin_[k] || c.centre[k] - half[k] > origin_[k] + cell_ * dims_[k])
        lo[k] = 1, hi[k] = 0;
    }
    for (int z = lo[2]; z <= hi[2]; ++z)
      for (int y = lo[1]; y <= hi[1]; ++y)
        for (int x = lo[0]; x <= hi[0]; ++x) {
          const std::size_t cell = (static_cast<std::size_t>(z) * dims_[1] + static_cast<std::size_t>(y)) * dims_[0] +
                                   static_cast<std::size_t>(x);
          for (std::uint32_t j = start_[cell]; j < start_[cell + 1]; ++j) {
            const std::uint32_t i = points_[j];
            const double d = distanceToCircle(cloud_->positions[i], c);
            if (d < best_[i]) {
              if (best_[i] == std::numeric_limits<double>::infinity()) touched_.push_back(i);
              best_[i] = d;
            }
          }
        }
  }
  for (std::uint32_t i : touched_) {
    out[i] = render::viridis(best_[i] * scale);
    best_[i] = std::numeric_limits<double>::infinity();  // ready for the next call
  }
  touched_.clear();
}

std::vector<Rgb> plainColors(const geom::PointCloud& cloud, const Rgb& color) {
  return std::vector<Rgb>(cloud.size(), color);
}

namespace {

/// The pieces of `model` that have a surface (non-zero length, as CylinderModelIndex keeps them),
/// each with its open caps, sorted.
std::vector<std::array<double, 10>> surfacePieces(const geom::CylinderModel& model) {
  const std::vector<std::array<bool, 2>> open = compare::jointCaps(model);
  std::vector<std::array<double, 10>> keys;
  keys.reserve(model.size());
  for (std::size_t i = 0; i < model.size(); ++i) {
    const geom::ModelCylinder& c = model.cylinders[i];
    if (!(c.length() > 0)) continue;
    keys.push_back({c.start.x(), c.start.y(), c.start.z(), c.end.x(), c.end.y(), c.end.z(), c.startRadius,
                    c.endRadius, open[i][0] ? 1.0 : 0.0, open[i][1] ? 1.0 : 0.0});
  }
  std::sort(keys.begin(), keys.end());
  return keys;
}

/// Changed pieces up to which each point is tested against their boxes (a few per edit).
constexpr std::size_t kMaxBoxesPerPoint = 16;

geom::BBox pieceBounds(const std::array<double, 10>& k) {
  geom::ModelCylinder c;
  c.start = Vec3(k[0], k[1], k[2]);
  c.end = Vec3(k[3], k[4], k[5]);
  c.startRadius = k[6];
  c.endRadius = k[7];
  return c.bounds();
}

}  // namespace

void DistanceColorGrid::markCellsNear(const geom::BBox& b) {
  if (!b.min.allFinite() || !b.max.allFinite()) return;
  int lo[3], hi[3];
  for (int k = 0; k < 3; ++k) {
    const double a = (b.min[k] - maxDistance_ - origin_[k]) / cell_, z = (b.max[k] + maxDistance_ - origin_[k]) / cell_;
    if (z < 0 || a > dims_[k]) return;  // the grown box misses the cloud
    lo[k] = std::clamp(static_cast<int>(std::floor(a)), 0, dims_[k] - 1);
    hi[k] = std::clamp(static_cast<int>(std::floor(z)), 0, dims_[k] - 1);
  }
  for (int z = lo[2]; z <= hi[2]; ++z)
    for (int y = lo[1]; y <= hi[1]; ++y)
      for (int x = lo[0]; x <= hi[0]; ++x) {
        const std::size_t cell =
            (static_cast<std::size_t>(z) * dims_[1] + static_cast<std::size_t>(y)) * dims_[0] + static_cast<std::size_t>(x);
        if (cellMarked_[cell] || start_[cell] == start_[cell + 1]) continue;
        cellMarked_[cell] = 1;
        markedCells_.push_back(static_cast<std::uint32_t>(cell));
      }
}

void DistanceColorGrid::measureMarkedCells(const compare::CylinderModelIndex& index,
                                           const std::vector<geom::BBox>& changed) {
  const Rgb beyond = render::viridis(1.0);
  std::atomic<std::size_t> measured{0}, decided{0};
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, markedCells_.size(), 4), [&](const auto& r) {
    std::size_t pointsHere = 0, cellsHere = 0;
    for (std::size_t m = r.begin(); m != r.end(); ++m) {
      const std::uint32_t cell = markedCells_[m];
      const std::uint32_t first = start_[cell], last = start_[cell + 1];
      // The cell as a whole: a point within `spread` of the centroid is at least d - spread from
      // the surface (outside every piece: the distance there is Euclidean). A margin of 1 % keeps
      // rounding from deciding a point the one-by-one measure would put just inside the ramp.
      Vec3 centroid = Vec3::Zero();
      for (std::uint32_t j = first; j < last; ++j) centroid += cloud_->positions[points_[j]];
      centroid /= static_cast<double>(last - first);
      double spread = 0;
      for (std::uint32_t j = first; j < last; ++j)
        spread = std::max(spread, (cloud_->positions[points_[j]] - centroid).norm());
      if (index.signedDistance(centroid) - spread >= 1.01 * maxDistance_) {
        for (std::uint32_t j = first; j < last; ++j) surface_[points_[j]] = beyond;
        ++cellsHere;
        continue;
      }
      for (std::uint32_t j = first; j < last; ++j) {
        const std::uint32_t i = points_[j];
        const Vec3& p = cloud_->positions[i];
        // Farther than maxDistance from every changed piece's box: its colour stays (the cell may
        // reach up to a cell beyond the grown boxes).
        if (!changed.empty() && std::none_of(changed.begin(), changed.end(), [&](const geom::BBox& b) {
              return (p.array() >= b.min.array()).all() && (p.array() <= b.max.array()).all();
            }))
          continue;
        const double d = std::abs(index.signedDistance(p));
        surface_[i] = render::viridis(std::min(d / maxDistance_, 1.0));  // as surfaceDistanceColors
        ++pointsHere;
      }
    }
    measured += pointsHere;
    decided += cellsHere;
  });
  lastMeasured_ = measured;
  lastCellsDecided_ = decided;
}

void DistanceColorGrid::surfaceColors(const geom::CylinderModel& model, std::vector<Rgb>& out) {
  lastMeasured_ = lastCellsDecided_ = 0;
  if (!cloud_ || size_ == 0 || !(maxDistance_ > 0)) {
    out.assign(size_, render::viridis(1.0));
    return;
  }
  const compare::CylinderModelIndex index(model);  // throws before anything kept changes
  std::vector<PieceKey> pieces = surfacePieces(model);
  if (!surfaceKept_) {  // as after an empty model: every point beyond the ramp
    surface_.assign(size_, render::viridis(1.0));
    surfacePieces_.clear();
    surfaceKept_ = true;
  }
  // The pieces in one model and not the other (as multisets): only near them can a colour change.
  std::vector<PieceKey> changed;
  std::set_symmetric_difference(surfacePieces_.begin(), surfacePieces_.end(), pieces.begin(), pieces.end(),
                                std::back_inserter(changed));
  // Each changed piece's box grown by maxDistance: the cells that reach into it are visited, and
  // in them the points inside one of these boxes are measured (all of them, when many pieces
  // changed: then testing each point against every box would cost more than it saves).
  std::vector<geom::BBox> grown;
  for (const PieceKey& k : changed) {
    geom::BBox b = pieceBounds(k);
    markCellsNear(b);
    b.min.array() -= maxDistance_;
    b.max.array() += maxDistance_;
    grown.push_back(b);
  }
  if (grown.size() > kMaxBoxesPerPoint) grown.clear();
  measureMarkedCells(index, grown);
  for (std::uint32_t cell : markedCells_) cellMarked_[cell] = 0;
  markedCells_.clear();
  surfacePieces_ = std::move(pieces);
  out = surface_;
}

std::vector<Rgb> surfaceDistanceColors(const geom::PointCloud& cloud, const geom::CylinderModel& model,
                                       double maxDistance) {
  std::vector<Rgb> out(cloud.size(), render::viridis(1.0));
  if (model.empty() || !(maxDistance > 0)) return out;
  const compare::CylinderModelIndex index(model);
  if (index.size() == 0) return out;
  geom::BBox box;
  for (const geom::ModelCylinder& c : model.cylinders) box.add(c.bounds());
  const geom::Vec3 lo = box.min.array() - maxDistance, hi = box.max.array() + maxDistance;
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, cloud.size(), 4096), [&](const auto& r) {
    for (std::size_t i = r.begin(); i != r.end(); ++i) {
      const geom::Vec3& p = cloud.positions[i];
      if ((p.array() < lo.array()).any() || (p.array() > hi.array()).any()) continue;  // beyond the ramp
      const double d = std::abs(index.signedDistance(p));
      out[i] = render::viridis(std::min(d / maxDistance, 1.0));
    }
  });
  return out;
}

}  // namespace treesketch::viewer
