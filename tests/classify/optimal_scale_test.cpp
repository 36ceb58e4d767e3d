// Features at each point's own best neighbourhood size: a thick limb, flat to its nearest points,
// chooses a neighbourhood that reaches around it and is a line there; a flat disc stays a plane
// and chooses no larger size; switched off, the features are absent.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "treesketch/classify/features.h"
#include "treesketch/util/error.h"

namespace treesketch::classify {
namespace {

constexpr int kLimb = 1500, kDisc = 4000;

/// A vertical cylinder of radius 1.5 cm and height 2 m (a thick limb's bark, kLimb points), then a
/// flat disc of radius 1 m beside it (kDisc points).
geom::PointCloud cylinderAndDisc(unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  geom::PointCloud c;
  for (int i = 0; i < kLimb; ++i) {
    const double a = 2 * M_PI * u(rng);
    c.positions.emplace_back(0.015 * std::cos(a), 2.0 * u(rng), 0.015 * std::sin(a));
  }
  for (int i = 0; i < kDisc; ++i) {
    const double a = 2 * M_PI * u(rng), r = std::sqrt(u(rng));
    c.positions.emplace_back(3.0 + r * std::cos(a), 1.0, r * std::sin(a));
  }
  return c;
}

int column(const FeatureTable& t, const std::string& name) {
  for (int k = 0; k < t.count; ++k)
    if (t.names[k] == name) return k;
  ADD_FAILURE() << "no feature " << name;
  return 0;
}

double meanOf(const FeatureTable& t, int col, std::size_t from, std::size_t to) {
  double s = 0;
  for (std::size_t i = from; i < to; ++i) s += t.row(i)[col];
  return s / static_cast<double>(to - from);
}

TEST(OptimalScale, ThickLimbChoosesALargerSizeThanAFlatDiscAndIsALineThere) {
  FeatureOptions o;
  o.optimalScaleFeatures = true;
  o.coreSpacings = 0;  // every point a core
  o.minSpacingHeightFraction = 0;
  const FeatureTable t = computeFeatures(cylinderAndDisc(7), geom::UpAxis::Y, o);
  const std::size_t n = kLimb + kDisc;
  ASSERT_EQ(t.points(), n);
  const int scale = column(t, "opt_scale"), lin = column(t, "opt_linearity"), pla = column(t, "opt_planarity"),
            sca = column(t, "opt_scattering"), axis = column(t, "opt_axis_up"), nup = column(t, "opt_normal_up"),
            linK8 = column(t, "linearity_k8");
  // Away from the cylinder's ends (a fifth of its length each side), where every size fits.
  double limbScale = 0, limbLin = 0, limbAxis = 0, limbLinK8 = 0, m = 0;
  for (std::size_t i = 0; i < kLimb; ++i) {
    if (t.heights[i] < 0.4 || t.heights[i] > 1.6) continue;
    limbScale += t.row(i)[scale];
    limbLin += t.row(i)[lin];
    limbAxis += t.row(i)[axis];
    limbLinK8 += t.row(i)[linK8];
    ++m;
  }
  const double discScale = meanOf(t, scale, kLimb, n);
  // The limb's largest neighbourhood reaches around it (a line along its axis, which is up); its
  // 8 nearest are a patch of bark, no line.
  EXPECT_GT(limbScale / m, 2.5);  // candidates 10, 20, 40, 80 are scales 0..3
  EXPECT_GT(limbLin / m, 0.7);
  EXPECT_GT(limbAxis / m, 0.9);
  EXPECT_LT(limbLinK8 / m, limbLin / m - 0.2);
  // The disc is a plane at every size (its normal up) and chooses smaller sizes.
  EXPECT_LT(discScale, limbScale / m - 1.5);
  EXPECT_GT(meanOf(t, pla, kLimb, n), 5 * meanOf(t, sca, kLimb, n));
  EXPECT_GT(meanOf(t, nup, kLimb, n), 0.95);
}

TEST(OptimalScale, OffLeavesNoColumnsAndBadCandidatesAreRefused) {
  FeatureOptions o;
  o.optimalScaleFeatures = false;
  for (const auto& name : featureNames(o)) EXPECT_EQ(name.rfind("opt_", 0), std::string::npos) << name;
  o.optimalScaleFeatures = true;
  o.optimalScales = {20, 10};
  EXPECT_THROW(computeFeatures(cylinderAndDisc(1), geom::UpAxis::Y, o), OptionsError);
  o.optimalScales = {};
  EXPECT_THROW(computeFeatures(cylinderAndDisc(1), geom::UpAxis::Y, o), OptionsError);
}

TEST(OptimalScale, ACloudSmallerThanTheLargestCandidateUsesWhatItHas) {
  geom::PointCloud c;
  for (int i = 0; i < 40; ++i) c.positions.emplace_back(0.0, 0.01 * i, 0.0005 * (i % 3));  // a short stick
  FeatureOptions o;
  o.optimalScaleFeatures = true;
  o.coreSpacings = 0;
  const FeatureTable t = computeFeatures(c, geom::UpAxis::Y, o);
  const int lin = column(t, "opt_linearity");
  for (std::size_t i = 0; i < t.points(); ++i) {
    EXPECT_TRUE(std::isfinite(t.row(i)[lin]));
    EXPECT_GT(t.row(i)[lin], 0.9);
  }
}

}  // namespace
}  // namespace treesketch::classify
