#include "skeleton/surface_bound.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "synthetic_tree.h"

using namespace treesketch;
using geom::Vec3;

namespace {

/// A trunk along y (0 to 2) and a side branch from its middle, as model nodes every 0.1.
std::vector<skeleton::SkeletonNode> trunkAndBranch(double trunkRadius, double branchRadius) {
  std::vector<skeleton::SkeletonNode> nodes;
  for (int k = 0; k <= 20; ++k) {
    skeleton::SkeletonNode n;
    n.position = Vec3(0, 0.1 * k, 0);
    n.radius = trunkRadius;
    n.parent = k - 1;
    n.branchOrder = 0;
    nodes.push_back(n);
  }
  for (int k = 1; k <= 10; ++k) {
    skeleton::SkeletonNode n;
    n.position = Vec3(0.1 * k, 1.0, 0);
    n.radius = branchRadius;
    n.parent = k == 1 ? 10 : static_cast<std::int32_t>(nodes.size()) - 1;
    n.branchOrder = 1;
    nodes.push_back(n);
  }
  for (std::size_t i = 0; i < nodes.size(); ++i)
    if (nodes[i].parent >= 0) nodes[nodes[i].parent].children.push_back(static_cast<std::int32_t>(i));
  return nodes;
}

const std::vector<test::Cyl> kTree = {{Vec3(0, 0, 0), Vec3(0, 2, 0), 0.10, -1}, {Vec3(0, 1, 0), Vec3(1, 1, 0), 0.02, 0}};
constexpr double kNoise = 0.002;

}  // namespace

TEST(SurfaceBound, TubesOnTheirPointsKeepTheirRadii) {
  // The model is the truth: its points lie on its surface with the noise. Measured radii (a circle
  // of their own) do not move; inferred ones go to their points' median, within its sampling error.
  const geom::PointCloud cloud = test::sampleCylinders(kTree, 0.01, kNoise, 3);
  auto model = trunkAndBranch(0.10, 0.02);
  const std::vector<double> own(model.size(), kNoise);
  const auto stats = skeleton::detail::boundRadiiBySurface(model, cloud, kNoise, 0.02, 5, own);
  EXPECT_GT(stats.nodesWithEvidence, 25u);
  EXPECT_EQ(stats.nodesThinned, 0u);
  for (std::size_t i = 0; i < model.size(); ++i) EXPECT_DOUBLE_EQ(model[i].radius, i <= 20 ? 0.10 : 0.02) << i;
  auto inferred = trunkAndBranch(0.10, 0.02);
  skeleton::detail::boundRadiiBySurface(inferred, cloud, kNoise, 0.02, 5);
  for (std::size_t i = 0; i < inferred.size(); ++i) {
    const double truth = i <= 20 ? 0.10 : 0.02;
    EXPECT_LE(inferred[i].radius, truth) << i;
    EXPECT_GT(inferred[i].radius, truth - kNoise) << i;
  }
}

TEST(SurfaceBound, AnInferredRadiusIsHeldToItsPointsAMeasuredOneKeepsTheMediansAllowance) {
  // The branch's tubes are 4 % thicker than the wood (0.0208 against 0.02) on a scan whose noise
  // reads 1 cm: within the allowance for the median's sampling error, so a radius resting on its
  // own circle keeps it; the same radius inferred (the pipe model's guess) comes down to what its
  // points show.
  const double noise = 0.01;
  const geom::PointCloud cloud = test::sampleCylinders(kTree, 0.01, kNoise, 11);
  std::vector<double> own(trunkAndBranch(0.1, 0.02).size(), 0.0);
  for (std::size_t i = 21; i < own.size(); ++i) own[i] = kNoise;
  auto measured = trunkAndBranch(0.10, 0.0208);
  skeleton::detail::boundRadiiBySurface(measured, cloud, noise, 0.02, 5, own);
  auto inferred = trunkAndBranch(0.10, 0.0208);
  skeleton::detail::boundRadiiBySurface(inferred, cloud, noise, 0.02, 5);
  for (std::size_t i = 22; i < measured.size() - 1; ++i) {
    EXPECT_DOUBLE_EQ(measured[i].radius, 0.0208) << i;
    EXPECT_LT(inferred[i].radius, 0.0203) << i;
    EXPECT_GT(inferred[i].radius, 0.0195) << i;
  }
}

TEST(SurfaceBound, ABranchThreeTimesTooThickComesBackToItsPoints) {
  // The side branch's tube is three times the wood its points show (a fit to a shell of noise);
  // the trunk is right. The branch comes back to within the margin of its surface, the trunk stays.
  const geom::PointCloud cloud = test::sampleCylinders(kTree, 0.01, kNoise, 4);
  auto model = trunkAndBranch(0.10, 0.06);
  std::vector<double> own(model.size(), 0.0);
  for (std::size_t i = 0; i <= 20; ++i) own[i] = kNoise;  // the trunk's circles: measured
  const auto stats = skeleton::detail::boundRadiiBySurface(model, cloud, kNoise, 0.02, 5, own);
  EXPECT_GE(stats.nodesThinned, 8u);
  for (std::size_t i = 0; i <= 20; ++i) EXPECT_DOUBLE_EQ(model[i].radius, 0.10) << i;
  for (std::size_t i = 22; i < model.size(); ++i) {
    EXPECT_LT(model[i].radius, 0.02 + 4 * kNoise + 1e-9) << i;
    EXPECT_GT(model[i].radius, 0.02 - 2 * kNoise) << i;
  }
}

TEST(SurfaceBound, AStemOfFewLongSegmentsIsNotThinnedToTheLimbAboveIt) {
  // A stem of radius 0.2 with nodes a metre apart, sparsely scanned, and above its last node a
  // limb of radius 0.06 that the stem's branch runs on into (as a stem tracked into a limb at a
  // fork does), densely scanned. Pooled with the limb's many points, the stem's nodes read the
  // limb's radius; on their own points they keep theirs, and the limb keeps its own.
  const std::vector<test::Cyl> stem = {{Vec3(0, 0, 0), Vec3(0, 2, 0), 0.2, -1}};
  const std::vector<test::Cyl> limb = {{Vec3(0, 2, 0), Vec3(0, 3, 0), 0.06, -1}};
  geom::PointCloud cloud = test::sampleCylinders(stem, 0.04, kNoise, 5);
  const geom::PointCloud limbPoints = test::sampleCylinders(limb, 0.004, kNoise, 6);
  cloud.positions.insert(cloud.positions.end(), limbPoints.positions.begin(), limbPoints.positions.end());
  std::vector<skeleton::SkeletonNode> model;
  for (int k = 0; k <= 12; ++k) {
    skeleton::SkeletonNode n;
    n.position = Vec3(0, k <= 2 ? 1.0 * k : 2.0 + 0.1 * (k - 2), 0);
    n.radius = k <= 2 ? 0.2 : 0.06;
    n.parent = k - 1;
    n.stem = true;
    model.push_back(n);
  }
  for (std::size_t i = 1; i < model.size(); ++i) model[model[i].parent].children.push_back(static_cast<std::int32_t>(i));
  const std::vector<double> own(model.size(), kNoise);
  skeleton::detail::boundRadiiBySurface(model, cloud, kNoise, 0.02, 5, own);
  EXPECT_DOUBLE_EQ(model[0].radius, 0.2);
  EXPECT_DOUBLE_EQ(model[1].radius, 0.2);
  for (std::size_t i = 4; i < model.size(); ++i) EXPECT_DOUBLE_EQ(model[i].radius, 0.06) << i;
}

TEST(SurfaceBound, ABranchStartsNoThickerThanItsParent) {
  const geom::PointCloud cloud;  // no points: only the fork's cap acts
  auto model = trunkAndBranch(0.05, 0.08);
  skeleton::detail::boundRadiiBySurface(model, test::sampleCylinders(kTree, 0.5, 0, 1), kNoise, 0.02, 5);
  EXPECT_DOUBLE_EQ(model[21].radius, 0.05);
}

/// Fits of circles of radius 0.1 in the planes z = k, each with 300 points about its circle
/// (Gaussian radial noise sigma[k]) and 60 more from a neighbouring branch; the fits' own RMS
/// says 1 mm, as a RANSAC band truncating the residuals would.
void noisyFits(const std::vector<double>& sigma, geom::PointCloud& cloud, std::vector<fit::NodeResult>& fits) {
  std::mt19937 rng(7);
  std::normal_distribution<double> gauss(0.0, 1.0);
  std::uniform_real_distribution<double> angle(0.0, 6.283185307179586);
  fits.assign(sigma.size(), {});
  for (std::size_t k = 0; k < sigma.size(); ++k) {
    fit::NodeResult& f = fits[k];
    f.status = fit::NodeStatus::Fitted;
    f.centre = Vec3(0, 0, static_cast<double>(k));
    f.normal = Vec3::UnitZ();
    f.radius = 0.1;
    f.rms = 0.001;
    for (int j = 0; j < 360; ++j) {
      const double a = angle(rng);
      const double r = j < 300 ? 0.1 + sigma[k] * gauss(rng) : 0.25 + 0.02 * gauss(rng);
      f.testIndices.push_back(static_cast<std::uint32_t>(cloud.size()));
      cloud.positions.push_back(f.centre + Vec3(r * std::cos(a), r * std::sin(a), 0.01 * gauss(rng)));
    }
  }
}

TEST(SurfaceBound, TheNoiseIsMeasuredOverAllTheTestPointsNotTheTruncatedInliers) {
  geom::PointCloud cloud;
  std::vector<fit::NodeResult> fits;
  noisyFits({0.002, 0.003, 0.1, 0.004, 0.005}, cloud, fits);
  // The accepted fits' noises are 2, 3, 4 and 5 mm: their lower quartile is 3 mm; the
  // neighbour's points and the fits' own 1 mm RMS do not decide it.
  const double noise = skeleton::detail::measuredNoise(fits, {1, 1, 0, 1, 1}, cloud, -1);
  EXPECT_NEAR(noise, 0.003, 0.001);
  EXPECT_GT(noise, 3 * fits[0].rms);
  EXPECT_DOUBLE_EQ(skeleton::detail::measuredNoise(fits, {1, 0, 0, 0, 1}, cloud, -1), -1);  // too few fits
}

TEST(SurfaceBound, TheStemsPointsGiveTheScansNoise) {
  // Points 4 mm (Gaussian, radial) about a trunk of radius 0.1 and a branch: the trunk's points
  // spread by the noise about its surface, whatever its radius in the model.
  const geom::PointCloud cloud = test::sampleCylinders(kTree, 0.01, 0.004, 5);
  auto model = trunkAndBranch(0.12, 0.02);  // the model's trunk a little thick: the spread is the same
  for (std::size_t i = 0; i <= 20; ++i) model[i].stem = true;
  EXPECT_NEAR(skeleton::detail::stemNoise(model, cloud, 0.02), 0.004, 0.001);
  for (auto& n : model) n.stem = false;  // no tracked stem: not measured here
  EXPECT_LT(skeleton::detail::stemNoise(model, cloud, 0.02), 0);
}

TEST(SurfaceBound, AnInferredBranchThinnerThanItsPointsIsRaisedAMeasuredOneIsNot) {
  // The side branch (radius 0.02) got an inferred radius of 0.005 (the pipe law at a thin tip):
  // its points lie 1.5 cm outside that tube. It is raised to within the margin of its surface,
  // and no further; the same branch with a circle of its own keeps its radius.
  const geom::PointCloud cloud = test::sampleCylinders(kTree, 0.01, kNoise, 6);
  auto inferred = trunkAndBranch(0.10, 0.005);
  std::vector<double> trunkOwn(inferred.size(), 0.0);
  for (std::size_t i = 0; i <= 20; ++i) trunkOwn[i] = kNoise;  // the trunk's circles: measured
  const auto stats = skeleton::detail::boundRadiiBySurface(inferred, cloud, kNoise, 0.02, 5, trunkOwn);
  EXPECT_GE(stats.nodesThickened, 8u);
  for (std::size_t i = 0; i <= 20; ++i) EXPECT_DOUBLE_EQ(inferred[i].radius, 0.10) << i;
  for (std::size_t i = 22; i < inferred.size(); ++i) {
    EXPECT_GT(inferred[i].radius, 0.02 - 3 * kNoise) << i;
    EXPECT_LE(inferred[i].radius, 0.02) << i;
  }
  auto measured = trunkAndBranch(0.10, 0.005);
  std::vector<double> own(measured.size(), 0.0);
  for (std::size_t i = 21; i < own.size(); ++i) own[i] = kNoise;  // fitted: their own residual
  EXPECT_EQ(skeleton::detail::boundRadiiBySurface(measured, cloud, kNoise, 0.02, 5, own).nodesThickened, 0u);
  for (std::size_t i = 21; i < measured.size(); ++i) EXPECT_DOUBLE_EQ(measured[i].radius, 0.005) << i;
}

TEST(SurfaceBound, WhereThePointsResolveAnInferredBranchItIsRaisedToTheRadiusTheyShow) {
  // The same branch (radius 0.02, ten noises) inferred at 0.005. Without the scanner's noise the
  // raise stops a noise and a quartile short of its surface; with it, the points' median resolves
  // the section and the raise goes to the radius it shows.
  const geom::PointCloud cloud = test::sampleCylinders(kTree, 0.01, kNoise, 6);
  std::vector<double> trunkOwn(trunkAndBranch(0.10, 0.005).size(), 0.0);
  for (std::size_t i = 0; i <= 20; ++i) trunkOwn[i] = kNoise;
  auto quartile = trunkAndBranch(0.10, 0.005);
  skeleton::detail::boundRadiiBySurface(quartile, cloud, kNoise, 0.02, 5, trunkOwn);
  auto resolved = trunkAndBranch(0.10, 0.005);
  skeleton::detail::boundRadiiBySurface(resolved, cloud, kNoise, 0.02, 5, trunkOwn, kNoise);
  for (std::size_t i = 22; i < resolved.size(); ++i) {
    EXPECT_NEAR(resolved[i].radius, 0.02, 0.5 * kNoise) << i;
    EXPECT_LT(quartile[i].radius, 0.02 - 0.5 * kNoise) << i;
  }
  // Pieces made mostly of flat patches (a leaf-on scan's leaves) show the foliage, not the wood:
  // their points' median does not raise them.
  auto leafy = trunkAndBranch(0.10, 0.005);
  for (std::size_t i = 21; i < leafy.size(); ++i) leafy[i].flatFraction = 0.9f;
  skeleton::detail::boundRadiiBySurface(leafy, cloud, kNoise, 0.02, 5, trunkOwn, kNoise, 0.5);
  for (std::size_t i = 22; i < leafy.size(); ++i) EXPECT_DOUBLE_EQ(leafy[i].radius, quartile[i].radius) << i;
}

TEST(SurfaceBound, ATwigThinnerThanTheNoiseIsNotRaisedByTheNoise) {
  // A twig of 1 mm under 8 mm of noise: its points are a blob about the line, not a surface, whose
  // distances' lower quartile (here 0.3 noise; 0.76 noise for noise in the plane) is under the
  // raise's margin of one noise.
  const std::vector<test::Cyl> twig = {{Vec3(0, 0, 0), Vec3(0, 2, 0), 0.10, -1}, {Vec3(0, 1, 0), Vec3(1, 1, 0), 0.001, 0}};
  const double noise = 0.008;
  const geom::PointCloud cloud = test::sampleCylinders(twig, 0.003, noise, 7);
  auto model = trunkAndBranch(0.10, 0.001);
  const auto stats = skeleton::detail::boundRadiiBySurface(model, cloud, noise, 0.02, 5);
  EXPECT_GE(stats.nodesWithEvidence, 25u);
  EXPECT_EQ(stats.nodesThickened, 0u);
  for (std::size_t i = 21; i < model.size(); ++i) EXPECT_DOUBLE_EQ(model[i].radius, 0.001) << i;
  // Nor with the scanner's noise known: the blob's median is under the noises a section needs.
  auto known = trunkAndBranch(0.10, 0.001);
  skeleton::detail::boundRadiiBySurface(known, cloud, noise, 0.02, 5, {}, noise);
  for (std::size_t i = 21; i < known.size(); ++i) EXPECT_DOUBLE_EQ(known[i].radius, 0.001) << i;
}

TEST(SurfaceBound, ATubesSpreadIsItsPointsNoiseAboutTheAxis) {
  // Points with 2 mm and 6 mm of radial noise about the trunk and the branch: each node's spread
  // is its own surface's noise, whatever the model's radius; a node without points has none.
  const std::vector<test::Cyl> trunk = {kTree[0]};
  const std::vector<test::Cyl> branch = {kTree[1]};
  geom::PointCloud cloud = test::sampleCylinders(trunk, 0.01, 0.002, 8);
  const geom::PointCloud twig = test::sampleCylinders(branch, 0.004, 0.006, 9);
  cloud.positions.insert(cloud.positions.end(), twig.positions.begin(), twig.positions.end());
  const auto model = trunkAndBranch(0.09, 0.01);
  const std::vector<double> spread = skeleton::detail::surfaceSpreads(model, cloud, 0.002, 0.02, 5);
  for (std::size_t i = 2; i <= 18; ++i) EXPECT_NEAR(spread[i], 0.002, 0.0008) << i;
  for (std::size_t i = 23; i < model.size() - 1; ++i) EXPECT_NEAR(spread[i], 0.006, 0.002) << i;
  auto far = model;
  for (auto& n : far) n.position += Vec3(5, 0, 0);  // no point near any tube
  for (double s : skeleton::detail::surfaceSpreads(far, cloud, 0.002, 0.02, 5)) EXPECT_TRUE(std::isnan(s));
}

TEST(SurfaceBound, WithoutCirclesTheTubesOwnPointsGiveTheNoise) {
  // A trunk with 4 mm of radial noise and a branch with 12 mm (a neighbour's points beside it):
  // the cleanest surfaces give the scan's noise, whatever the half voxel standing in for it, and
  // whatever the model's radii.
  const std::vector<test::Cyl> trunk = {kTree[0]};
  const std::vector<test::Cyl> branch = {kTree[1]};
  geom::PointCloud cloud = test::sampleCylinders(trunk, 0.01, 0.004, 10);
  const geom::PointCloud twig = test::sampleCylinders(branch, 0.004, 0.012, 11);
  cloud.positions.insert(cloud.positions.end(), twig.positions.begin(), twig.positions.end());
  const auto model = trunkAndBranch(0.11, 0.03);
  EXPECT_NEAR(skeleton::detail::spreadNoise(model, cloud, 0.01, 0.02, 5), 0.004, 0.0015);
  EXPECT_NEAR(skeleton::detail::spreadNoise(model, cloud, 0.03, 0.02, 5), 0.004, 0.0015);
  auto far = model;
  for (auto& n : far) n.position += Vec3(5, 0, 0);  // no point near any tube: nothing measured
  EXPECT_LT(skeleton::detail::spreadNoise(far, cloud, 0.01, 0.02, 5), 0);
}

namespace {

/// A branch along y (0 to 2) whose cross-section is a regular polygon of `sides` corners on a
/// circle of radius `circumradius`: points spread evenly over its flat faces (noise along each
/// face's normal), as a scan of the generator's flat-sided branches sees them.
geom::PointCloud polygonalBranch(int sides, double circumradius, double noise, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> uni(0.0, 1.0);
  std::normal_distribution<double> gauss(0.0, 1.0);
  const double step = 2 * M_PI / sides;
  geom::PointCloud cloud;
  for (int i = 0; i < 20000; ++i) {
    const int face = static_cast<int>(uni(rng) * sides) % sides;
    const Vec3 a(circumradius * std::cos(face * step), 0, circumradius * std::sin(face * step));
    const Vec3 b(circumradius * std::cos((face + 1) * step), 0, circumradius * std::sin((face + 1) * step));
    const Vec3 normal = Vec3(0.5 * (a + b)).normalized();
    cloud.positions.push_back(a + uni(rng) * (b - a) + noise * gauss(rng) * normal + Vec3(0, 2 * uni(rng), 0));
  }
  return cloud;
}

}  // namespace

TEST(SurfaceBound, AFlatSidedBranchKeepsTheRadiusOfItsArea) {
  // A branch of three or four flat sides modelled at the radius of the circle with its area: the
  // points on its faces' middles lie inside that circle (a square's inradius is 0.89 of it, a
  // triangle's 0.78), but half its perimeter lies outside, so its radius stays (within 2 %).
  for (const int sides : {3, 4}) {
    const double circumradius = 0.1;
    const double areaRadius = circumradius * std::sqrt(sides / (2 * M_PI) * std::sin(2 * M_PI / sides));
    std::vector<skeleton::SkeletonNode> model = test::uprightChain(21, 0.1, areaRadius);
    const geom::PointCloud cloud = polygonalBranch(sides, circumradius, 0.0005, 10 + sides);
    const auto stats = skeleton::detail::boundRadiiBySurface(model, cloud, 0.001, 0.02, 5);
    EXPECT_GE(stats.nodesWithEvidence, 20u) << sides;
    for (std::size_t i = 1; i + 1 < model.size(); ++i) {
      EXPECT_GT(model[i].radius, 0.98 * areaRadius) << sides << " sides, node " << i;
      EXPECT_LE(model[i].radius, areaRadius) << sides << " sides, node " << i;
    }
  }
}

TEST(SurfaceBound, ATubeBesideItsBranchKeepsNoMoreThanTheBranchsSection) {
  // The side branch (radius 0.02) is modelled 3 cm off its axis, as a circle fitted round it from
  // the wrong centre (radius 0.05). Its points' distances to that axis have their median at 3.6 cm
  // — a tube that wide would hold twice the branch's wood — but one convex section about an axis
  // has at most a few of its points that deep inside: the tube comes back to the branch's size.
  const geom::PointCloud cloud = test::sampleCylinders(kTree, 0.004, kNoise, 11);
  auto model = trunkAndBranch(0.10, 0.05);
  for (std::size_t i = 21; i < model.size(); ++i) model[i].position += Vec3(0, 0, 0.03);
  skeleton::detail::boundRadiiBySurface(model, cloud, kNoise, 0.02, 5);
  for (std::size_t i = 23; i + 1 < model.size(); ++i) {
    EXPECT_LT(model[i].radius, 0.03) << i;
    EXPECT_GT(model[i].radius, 0.015) << i;
  }
}
