#include "treesketch/viewer/point_colors.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
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

void DistanceColorGrid::surfaceColors(const geom::CylinderModel& model, std::vector<Rgb>& out) {
  out.assign(size_, render::viridis(1.0));
  if (!cloud_ || model.empty() || size_ == 0 || !(maxDistance_ > 0)) return;
  const compare::CylinderModelIndex index(model);
  if (index.size() == 0) return;
  // The cells within maxDistance of some piece's box: only their points can be nearer than that.
  std::vector<char> near(start_.size() - 1, 0);
  for (const geom::ModelCylinder& c : model.cylinders) {
    const geom::BBox b = c.bounds();
    if (!b.min.allFinite() || !b.max.allFinite()) continue;
    int lo[3], hi[3];
    bool outside = false;
    for (int k = 0; k < 3; ++k) {
      const double a = (b.min[k] - maxDistance_ - origin_[k]) / cell_, z = (b.max[k] + maxDistance_ - origin_[k]) / cell_;
      outside |= z < 0 || a > dims_[k];
      lo[k] = std::clamp(static_cast<int>(std::floor(a)), 0, dims_[k] - 1);
      hi[k] = std::clamp(static_cast<int>(std::floor(z)), 0, dims_[k] - 1);
    }
    if (outside) continue;
    for (int z = lo[2]; z <= hi[2]; ++z)
      for (int y = lo[1]; y <= hi[1]; ++y)
        for (int x = lo[0]; x <= hi[0]; ++x)
          near[(static_cast<std::size_t>(z) * dims_[1] + static_cast<std::size_t>(y)) * dims_[0] +
               static_cast<std::size_t>(x)] = 1;
  }
  touched_.clear();
  for (std::size_t cell = 0; cell < near.size(); ++cell)
    if (near[cell]) touched_.insert(touched_.end(), points_.begin() + start_[cell], points_.begin() + start_[cell + 1]);
  const double scale = 1.0 / maxDistance_;
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, touched_.size(), 2048), [&](const auto& r) {
    for (std::size_t j = r.begin(); j != r.end(); ++j) {
      const std::uint32_t i = touched_[j];
      out[i] = render::viridis(std::min(std::abs(index.signedDistance(cloud_->positions[i])) * scale, 1.0));
    }
  });
  touched_.clear();
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
