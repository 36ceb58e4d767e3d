// The automatic model with stray points added to real scans (../shared/data/real; skipped without
// it): 1, 10 and 100 points at 20 m to 1,000 km from the tree leave the model's volume within 2 %,
// and the result counts the points set aside.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "test_support.h"
#include "treesketch/io/point_cloud_io.h"
#include "treesketch/model/tree_model.h"
#include "treesketch/skeleton/skeleton_sketch.h"

namespace treesketch::model {
namespace {

double modelVolume(const geom::PointCloud& cloud, skeleton::AutoSkeletonResult* out = nullptr) {
  const skeleton::AutoSkeletonOptions o = skeleton::autoSkeletonPreset(skeleton::Foliage::LeafOff, geom::UpAxis::Z);
  skeleton::AutoSkeletonResult r = skeleton::autoSkeletonSketch(cloud, o);
  double v = 0;
  for (const geom::ModelCylinder& c : fromAutoSkeleton(r, geom::UpAxis::Z).cylinders.cylinders) v += c.volume();
  if (out) *out = std::move(r);
  return v;
}

/// `count` points in random directions from the cloud's centre, at distances from the edge of its
/// bounding sphere spread evenly on a log scale from `nearest` to `farthest` metres.
geom::PointCloud withStrays(geom::PointCloud cloud, int count, double nearest, double farthest, std::uint32_t seed) {
  const geom::BBox box = cloud.bounds();
  const geom::Vec3 centre = 0.5 * (box.min + box.max);
  std::mt19937 rng(seed);
  std::normal_distribution<double> g;
  for (int k = 0; k < count; ++k) {
    geom::Vec3 dir(g(rng), g(rng), g(rng));
    dir.normalize();
    const double t = count == 1 ? 0.0 : static_cast<double>(k) / (count - 1);
    const double d = nearest * std::pow(farthest / nearest, t);
    cloud.positions.push_back(centre + dir * (0.5 * box.diagonal() + d));
  }
  return cloud;
}

TEST(StrayPointsOnRealScans, TheModelIsTheSameWithAHundredStrayPoints) {
  const auto real = test::sharedDataDir() / "real";
  if (!std::filesystem::exists(real)) GTEST_SKIP() << "no " << real;
  struct Strays {
    int count;
    double nearest, farthest;
  };
  for (const char* file : {"rtwig_cloud.txt", "adtree_tree1.xyz", "adtree_tree7.xyz"}) {
    const geom::PointCloud clean = io::readPointCloud(real / file);
    skeleton::AutoSkeletonResult base;
    const double v0 = modelVolume(clean, &base);
    ASSERT_GT(v0, 0) << file;
    const std::size_t cleanSetAside = base.strays.count();
    EXPECT_LE(cleanSetAside, clean.size() / 1000) << file << ": a clean cloud loses almost no point";
    std::uint32_t seed = 1;
    for (const Strays& s : {Strays{1, 20, 20}, Strays{1, 1e6, 1e6}, Strays{10, 20, 1e6}, Strays{100, 20, 1e6}}) {
      const geom::PointCloud cloud = withStrays(clean, s.count, s.nearest, s.farthest, seed++);
      skeleton::AutoSkeletonResult r;
      const double v = modelVolume(cloud, &r);
      EXPECT_NEAR(v, v0, 0.02 * v0) << file << ": " << s.count << " strays at " << s.nearest << "-" << s.farthest
                                    << " m";
      EXPECT_EQ(r.strays.count(), cleanSetAside + static_cast<std::size_t>(s.count))
          << file << ": " << cloud::strayPointsLine(r.strays);
      // the added points are among those set aside
      std::size_t added = 0;
      for (std::uint32_t i : r.strays.setAside) added += i >= clean.size();
      EXPECT_EQ(added, static_cast<std::size_t>(s.count)) << file;
    }
  }
}

}  // namespace
}  // namespace treesketch::model
