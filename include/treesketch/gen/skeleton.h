// Tree skeletons: branches as polylines of circular cross-sections {centre, radius, unit axis},
// linked into a hierarchy (each branch starts at a section of its parent). The generator's ground
// truth and the shape the reconstruction is compared against. Metres, world frame.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "treesketch/geom/types.h"

namespace treesketch::gen {

/// One circular cross-section of a branch.
struct Section {
  geom::Vec3 centre = geom::Vec3::Zero();  ///< world, m
  double radius = 0;                       ///< m, > 0
  geom::Vec3 axis = geom::Vec3::UnitY();   ///< unit growth direction; the ring lies in the plane normal to it
};

struct SkeletonBranch {
  int id = 0;             ///< index of this branch in Skeleton::branches
  int parent = -1;        ///< parent branch id; -1 for the trunk (a root)
  int parentSection = -1; ///< index of the parent's section where this branch starts; -1 for a root
  int level = 0;          ///< 0 = trunk, 1 = first-order branch, ...
  std::vector<Section> sections;  ///< base to tip, at least 2
};

struct Skeleton {
  geom::UpAxis up = geom::UpAxis::Y;
  std::vector<SkeletonBranch> branches;  ///< ordered so that a parent comes before its children

  /// Number of sections over all branches.
  std::size_t sectionCount() const;
  /// Highest branch level (-1 when empty).
  int maxLevel() const;
};

/// Length of a branch's centre polyline, m (0 for fewer than 2 sections).
double branchLength(const SkeletonBranch& branch);
/// Sum of all branch lengths, m (0 for an empty skeleton).
double totalLength(const Skeleton& skeleton);
/// Bounding box of the swept tubes (every section's centre padded by its radius); empty box for an
/// empty skeleton.
geom::BBox bounds(const Skeleton& skeleton);
/// Volume of a conical frustum of circular ends of radii r0 and r1 (m) a `length` (m) apart, m^3:
/// pi·length·(r0² + r0·r1 + r1²)/3.
double frustumVolume(double length, double r0, double r1);
/// Volume of one branch's tube as the frustums between consecutive sections, m^3 (0 for fewer than
/// 2 sections).
double branchWoodVolume(const SkeletonBranch& branch);
/// Volume of the tubes as a sum of conical frustums, m^3 (joint overlaps counted twice).
double woodVolume(const Skeleton& skeleton);

/// Where a point is nearest to the skeleton's sections.
struct NearestSection {
  int branch = -1;        ///< branch id, -1 when the skeleton is empty
  int section = -1;       ///< section index in that branch
  double distance = 0;    ///< distance from the point to the section's centre, m
};
/// The section whose centre is nearest to `p` (brute force over all sections; ties go to the
/// lowest branch id, then section index). Returns branch = -1 for an empty skeleton.
NearestSection nearestSection(const Skeleton& skeleton, const geom::Vec3& p);

/// Distance from `p` to the line through `s.centre` along `s.axis`, m.
double distanceToSectionAxis(const Section& s, const geom::Vec3& p);

/// Empty string when the skeleton is well formed; otherwise the first problem found, naming the
/// branch and section (ids not consecutive, parent not earlier, parentSection out of range, fewer
/// than 2 sections, radius not positive and finite, axis not unit length within 1e-6, NaN).
std::string findSkeletonProblem(const Skeleton& skeleton);

/// Rotates a Y-up skeleton into the Z-up frame, or back: (x, y, z) -> (x, -z, y) for Y->Z,
/// (x, y, z) -> (x, z, -y) for Z->Y. Exact (a permutation with a sign flip). Does nothing when
/// `to` equals skeleton.up.
void convertUpAxis(Skeleton& skeleton, geom::UpAxis to);
/// The same rotation applied to one point or direction.
geom::Vec3 convertUpAxis(const geom::Vec3& p, geom::UpAxis from, geom::UpAxis to);

/// Refines every branch by `factor` (>= 1): each polyline segment becomes `factor` segments on a
/// Catmull–Rom curve through the original centres, radii interpolated linearly, axes the curve's
/// tangent. Original sections are kept (section i becomes i * factor) and parentSection indices
/// are remapped, so children still start at a section of their parent. factor 1 returns a copy.
/// Throws OptionsError for factor < 1.
Skeleton refineSkeleton(const Skeleton& skeleton, int factor);

}  // namespace treesketch::gen
