#include "skeleton/range_noise.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>

#include "skeleton/surface_bound.h"
#include "synthetic_tree.h"

using namespace treesketch;
using geom::Vec3;

namespace {

/// A branch along y (0 to 1) with an oval section (semi-axes a along x, b along z), scanned from
/// four directions across it: each point lies on the side its ray sees, moved along that ray by a
/// Gaussian range noise `noise`. `count` points.
geom::PointCloud scanOval(double a, double b, double noise, std::size_t count, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::normal_distribution<double> gauss(0.0, noise);
  geom::PointCloud cloud;
  while (cloud.size() < count) {
    const double phi = 2 * std::numbers::pi * unit(rng);
    const double view = 2 * std::numbers::pi * (std::floor(4 * unit(rng)) / 4 + 0.1);
    const Vec3 ray(std::cos(view), 0, std::sin(view));  // towards the branch
    const Vec3 normal(std::cos(phi) / a, 0, std::sin(phi) / b);
    if (normal.dot(ray) >= 0) continue;  // the far side: this ray does not see it
    const Vec3 surface(a * std::cos(phi), unit(rng), b * std::sin(phi));
    cloud.positions.push_back(surface + gauss(rng) * ray);
  }
  return cloud;
}

/// The branch as model nodes every 0.1 along y, of radius `radius`.
std::vector<skeleton::SkeletonNode> branch(double radius) { return test::uprightChain(11, 0.1, radius); }

double medianDistanceToAxis(const geom::PointCloud& cloud) {
  std::vector<double> rho;
  for (const Vec3& p : cloud.positions) rho.push_back(std::hypot(p.x(), p.z()));
  std::nth_element(rho.begin(), rho.begin() + static_cast<std::ptrdiff_t>(rho.size() / 2), rho.end());
  return rho[rho.size() / 2];
}

}  // namespace

TEST(RangeNoise, ReadsTheScannersNoiseOnALimbAndOnATwigThinnerThanIt) {
  // 10 mm of range noise on a limb of 5 cm and on a twig of 5 mm: the reading is the scanner's
  // noise both times (the circles' residuals read a quarter to a half of it on such scans).
  const double noise = 0.01;
  for (const double radius : {0.05, 0.005}) {
    const geom::PointCloud cloud = scanOval(radius, radius, noise, 6000, 3);
    const double read = skeleton::detail::rangeNoise(branch(radius), cloud, 0.05);
    EXPECT_NEAR(read, noise, 0.25 * noise) << radius;
  }
}

TEST(RangeNoise, AnOvalStemIsNotNoise) {
  // A stem 24 × 16 cm across with 1 mm of noise: its points spread by about 2 cm about the circle
  // of their median (an oval is no circle), but neighbours along the bark agree, so the noise read
  // is the scanner's millimetre, not the oval's centimetres.
  const geom::PointCloud cloud = scanOval(0.12, 0.08, 0.001, 20000, 5);
  const auto model = branch(0.10);
  const double read = skeleton::detail::rangeNoise(model, cloud, 0.05);
  const std::vector<double> spread = skeleton::detail::surfaceSpreads(model, cloud, 0.001, 0.02, 5);
  EXPECT_GT(spread[5], 0.01);
  EXPECT_GT(read, 0.0);
  EXPECT_LT(read, 0.003);
}

TEST(RangeNoise, ATwigsMedianUnderTheNoiseGivesBackItsRadius) {
  // A twig half as thick as the noise has its points' median distance to the axis well above its
  // radius; read through the noise it comes back. A limb four noises thick keeps its median.
  const double noise = 0.01;
  const double twig = 0.005;
  const double median = medianDistanceToAxis(scanOval(twig, twig, noise, 20000, 7));
  EXPECT_GT(median, 1.4 * twig);
  EXPECT_NEAR(skeleton::detail::radiusUnderNoise(median, noise), twig, 0.2 * twig);
  const double limb = 0.04;
  const double limbMedian = medianDistanceToAxis(scanOval(limb, limb, noise, 20000, 9));
  EXPECT_NEAR(limbMedian, limb, 0.02 * limb);
  EXPECT_NEAR(skeleton::detail::radiusUnderNoise(limbMedian, noise), limbMedian, 0.02 * limb);
}

TEST(RangeNoise, TheRadiusUnderNoiseInvertsTheMedianItShows) {
  for (double x = 0.25; x <= 6.0; x += 0.25)
    EXPECT_NEAR(skeleton::detail::radiusUnderNoise(0.02 * skeleton::detail::noisyMedianOverNoise(x), 0.02), 0.02 * x,
                1e-9)
        << x;
  // A median at the blob's cannot tell a radius: a quarter of the noise, never above the median.
  EXPECT_DOUBLE_EQ(skeleton::detail::radiusUnderNoise(0.6, 1.0), 0.25);
  EXPECT_DOUBLE_EQ(skeleton::detail::radiusUnderNoise(0.1, 1.0), 0.1);
  EXPECT_DOUBLE_EQ(skeleton::detail::radiusUnderNoise(0.3, 0.0), 0.3);  // no noise: unchanged
}
