// Size and precision of a tree's cloud (see scale_check.h).
#include "treesketch/cloud/scale_check.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

namespace treesketch::cloud {

namespace {

/// The bounds of the points not set aside (`setAside` increasing).
geom::BBox keptBounds(const geom::PointCloud& cloud, const std::vector<std::uint32_t>& setAside) {
  geom::BBox box;
  std::size_t s = 0;
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    if (s < setAside.size() && setAside[s] == i) {
      ++s;
      continue;
    }
    box.add(cloud.positions[i]);
  }
  return box;
}

std::string figure(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.4g", v);
  return buf;
}

}  // namespace

ScaleCheck checkScale(const geom::PointCloud& cloud, const StrayPoints& strays, double unitMetres,
                      const ScaleCheckOptions& o) {
  ScaleCheck c;
  const geom::BBox box = keptBounds(cloud, strays.setAside);
  if (box.empty()) return c;
  c.extentMetres = box.extent().maxCoeff() * unitMetres;
  c.offset = std::max(box.min.cwiseAbs().maxCoeff(), box.max.cwiseAbs().maxCoeff());
  c.doubleStep = std::nextafter(c.offset, std::numeric_limits<double>::infinity()) - c.offset;
  const auto f = static_cast<float>(std::min(c.offset, static_cast<double>(std::numeric_limits<float>::max())));
  c.floatStep = static_cast<double>(std::nextafter(f, std::numeric_limits<float>::infinity()) - f);
  c.spacing = strays.spacing;
  if (std::isfinite(c.extentMetres) && c.extentMetres > o.maxTreeMetres) {
    c.implausibleSize = true;
    c.warnings.push_back("the cloud is " + figure(c.extentMetres) +
                         " m across (its largest extent, strays aside): implausible for one tree in metres; if its "
                         "units are not metres, give --units-metres (millimetres: 0.001, centimetres: 0.01, feet: "
                         "0.3048)");
  }
  if (c.spacing > 0 && c.doubleStep * o.minSpacingSteps > c.spacing) {
    c.precisionLost = true;
    c.warnings.push_back("the coordinates reach " + figure(c.offset) + ", where doubles step by " +
                         figure(c.doubleStep) + " (floats by " + figure(c.floatStep) + "), too coarse for the " +
                         figure(c.spacing) +
                         " point spacing: the points have lost their shape; recentre the cloud (subtract a point near "
                         "the tree, e.g. CloudCompare's global shift or PDAL's filters.transformation) and export it "
                         "again");
  } else if (c.offset > o.maxTestedOffset) {
    c.beyondTestedOffset = true;
    c.warnings.push_back("the coordinates reach " + figure(c.offset) + ", past the " + figure(o.maxTestedOffset) +
                         " from the origin up to which the automatic model was measured to be the recentred cloud's "
                         "(a real scan's volume moved by 1.6 % at 1e11, 16 % at 1e12); recentre the cloud (subtract a point near the "
                         "tree, e.g. CloudCompare's global shift or PDAL's filters.transformation) and export it again");
  }
  return c;
}

}  // namespace treesketch::cloud
