#include "treesketch/viewer/point_colors.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>

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

std::vector<Rgb> plainColors(const geom::PointCloud& cloud, const Rgb& color) {
  return std::vector<Rgb>(cloud.size(), color);
}

}  // namespace treesketch::viewer
