#include "treesketch/gen/skeleton.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "treesketch/util/error.h"

namespace treesketch::gen {
namespace {

using geom::Vec3;

/// A vertical trunk of 5 sections (0..4 m) with a horizontal child at section 2 (length 1 m).
Skeleton smallTree() {
  Skeleton s;
  SkeletonBranch trunk;
  for (int i = 0; i < 5; ++i) trunk.sections.push_back({Vec3(0, i, 0), 0.2 - 0.02 * i, Vec3(0, 1, 0)});
  SkeletonBranch child;
  child.id = 1;
  child.parent = 0;
  child.parentSection = 2;
  child.level = 1;
  for (int i = 0; i < 3; ++i) child.sections.push_back({Vec3(0.5 * i, 2, 0), 0.05, Vec3(1, 0, 0)});
  s.branches = {trunk, child};
  return s;
}

TEST(Skeleton, LengthsCountsAndBounds) {
  Skeleton s = smallTree();
  EXPECT_DOUBLE_EQ(branchLength(s.branches[0]), 4.0);
  EXPECT_DOUBLE_EQ(branchLength(s.branches[1]), 1.0);
  EXPECT_DOUBLE_EQ(totalLength(s), 5.0);
  EXPECT_EQ(s.sectionCount(), 8u);
  EXPECT_EQ(s.maxLevel(), 1);
  geom::BBox box = bounds(s);
  EXPECT_NEAR(box.min.y(), -0.2, 1e-12);
  EXPECT_NEAR(box.max.x(), 1.05, 1e-12);
  EXPECT_TRUE(bounds(Skeleton{}).empty());
  EXPECT_EQ(totalLength(Skeleton{}), 0.0);
  EXPECT_EQ(Skeleton{}.maxLevel(), -1);
}

TEST(Skeleton, WoodVolumeOfACylinder) {
  Skeleton s;
  SkeletonBranch b;
  b.sections = {{Vec3(0, 0, 0), 0.5, Vec3(0, 1, 0)}, {Vec3(0, 2, 0), 0.5, Vec3(0, 1, 0)}};
  s.branches = {b};
  EXPECT_NEAR(woodVolume(s), std::numbers::pi * 0.25 * 2, 1e-12);
}

TEST(Skeleton, NearestSectionAndAxisDistance) {
  Skeleton s = smallTree();
  NearestSection n = nearestSection(s, Vec3(0.9, 2.1, 0));
  EXPECT_EQ(n.branch, 1);
  EXPECT_EQ(n.section, 2);
  EXPECT_NEAR(n.distance, std::hypot(0.1, 0.1), 1e-12);
  n = nearestSection(s, Vec3(0.1, 3.2, 0));
  EXPECT_EQ(n.branch, 0);
  EXPECT_EQ(n.section, 3);
  EXPECT_EQ(nearestSection(Skeleton{}, Vec3::Zero()).branch, -1);
  EXPECT_NEAR(distanceToSectionAxis(s.branches[0].sections[1], Vec3(3, 17, 4)), 5.0, 1e-12);
}

TEST(Skeleton, ProblemsAreFound) {
  EXPECT_EQ(findSkeletonProblem(smallTree()), "");
  EXPECT_EQ(findSkeletonProblem(Skeleton{}), "");
  auto expectProblem = [](Skeleton s, const std::string& fragment) {
    std::string p = findSkeletonProblem(s);
    EXPECT_NE(p.find(fragment), std::string::npos) << p;
  };
  Skeleton s = smallTree();
  s.branches[1].id = 5;
  expectProblem(s, "id");
  s = smallTree();
  s.branches[1].parent = 1;
  expectProblem(s, "does not come before");
  s = smallTree();
  s.branches[1].parentSection = 5;
  expectProblem(s, "out of range");
  s = smallTree();
  s.branches[1].sections.resize(1);
  expectProblem(s, ">= 2");
  s = smallTree();
  s.branches[0].sections[1].radius = 0;
  expectProblem(s, "radius");
  s = smallTree();
  s.branches[0].sections[1].centre.x() = std::nan("");
  expectProblem(s, "not finite");
  s = smallTree();
  s.branches[0].sections[1].axis = Vec3(0, 0, 0);
  expectProblem(s, "unit");
  s = smallTree();
  s.branches[0].parentSection = 0;
  expectProblem(s, "root");
}

TEST(Skeleton, UpAxisConversionIsARotationAndRoundTrips) {
  Skeleton s = smallTree();
  Skeleton z = s;
  convertUpAxis(z, geom::UpAxis::Z);
  EXPECT_EQ(z.up, geom::UpAxis::Z);
  // The trunk now grows along +Z; lengths are preserved.
  EXPECT_EQ(z.branches[0].sections[4].centre, Vec3(0, 0, 4));
  EXPECT_EQ(z.branches[0].sections[0].axis, Vec3(0, 0, 1));
  EXPECT_DOUBLE_EQ(totalLength(z), totalLength(s));
  // Right-handed: x cross y = z is kept.
  Vec3 ex = convertUpAxis(Vec3(1, 0, 0), geom::UpAxis::Y, geom::UpAxis::Z);
  Vec3 ey = convertUpAxis(Vec3(0, 1, 0), geom::UpAxis::Y, geom::UpAxis::Z);
  Vec3 ez = convertUpAxis(Vec3(0, 0, 1), geom::UpAxis::Y, geom::UpAxis::Z);
  EXPECT_EQ(ex.cross(ey), ez);
  convertUpAxis(z, geom::UpAxis::Y);
  for (std::size_t b = 0; b < s.branches.size(); ++b)
    for (std::size_t i = 0; i < s.branches[b].sections.size(); ++i) {
      EXPECT_EQ(z.branches[b].sections[i].centre, s.branches[b].sections[i].centre);
      EXPECT_EQ(z.branches[b].sections[i].axis, s.branches[b].sections[i].axis);
    }
}

TEST(Skeleton, RefineKeepsOriginalSectionsAndRemapsParents) {
  Skeleton s = smallTree();
  Skeleton r = refineSkeleton(s, 3);
  ASSERT_EQ(r.branches.size(), 2u);
  EXPECT_EQ(r.branches[0].sections.size(), 13u);  // 4 segments * 3 + 1
  EXPECT_EQ(r.branches[1].sections.size(), 7u);
  EXPECT_EQ(r.branches[1].parentSection, 6);
  EXPECT_EQ(r.branches[1].sections[0].centre, r.branches[0].sections[6].centre);
  for (int i = 0; i < 5; ++i) EXPECT_EQ(r.branches[0].sections[3 * i].centre, s.branches[0].sections[i].centre);
  // A straight trunk stays straight; radii are interpolated linearly.
  for (const Section& q : r.branches[0].sections) {
    EXPECT_NEAR(q.centre.x(), 0.0, 1e-12);
    EXPECT_NEAR((q.axis - Vec3(0, 1, 0)).norm(), 0.0, 1e-12);
    EXPECT_NEAR(q.radius, 0.2 - 0.02 * q.centre.y(), 1e-12);
  }
  EXPECT_EQ(findSkeletonProblem(r), "");
  EXPECT_NEAR(totalLength(r), totalLength(s), 1e-12);
  Skeleton same = refineSkeleton(s, 1);
  EXPECT_EQ(same.sectionCount(), s.sectionCount());
  EXPECT_THROW(refineSkeleton(s, 0), OptionsError);
}

TEST(Skeleton, RefineFollowsACurve) {
  // Sections on a quarter circle of radius 1: refined points stay close to the circle.
  Skeleton s;
  SkeletonBranch b;
  const int n = 7;
  for (int i = 0; i < n; ++i) {
    double a = 0.5 * std::numbers::pi * i / (n - 1);
    b.sections.push_back({Vec3(std::cos(a), std::sin(a), 0), 0.01, Vec3(-std::sin(a), std::cos(a), 0)});
  }
  s.branches = {b};
  Skeleton r = refineSkeleton(s, 4);
  for (std::size_t i = 4; i + 4 < r.branches[0].sections.size(); ++i) {  // away from the one-sided ends
    const Section& q = r.branches[0].sections[i];
    EXPECT_NEAR(q.centre.norm(), 1.0, 2e-3);
    EXPECT_NEAR(q.axis.dot(q.centre.normalized()), 0.0, 2e-2);
  }
}

}  // namespace
}  // namespace treesketch::gen
