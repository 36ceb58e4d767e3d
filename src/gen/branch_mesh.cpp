#include "treesketch/gen/branch_mesh.h"

#include <cmath>
#include <numbers>

#include "treesketch/util/error.h"

namespace treesketch::gen {

using geom::Vec3;

namespace {

/// The minimal rotation taking unit vector a to unit vector b, applied to x (Rodrigues).
Vec3 rotateMinimal(const Vec3& a, const Vec3& b, const Vec3& x) {
  Vec3 v = a.cross(b);
  double c = a.dot(b);
  if (c < -1.0 + 1e-12) return x;  // opposite axes: no unique rotation; the caller re-projects
  return x + v.cross(x) + v.cross(v.cross(x)) / (1.0 + c);
}

/// Parallel-transported ring frames (u along each section's plane); first u from anyPerpendicular.
std::vector<Vec3> ringFrames(const SkeletonBranch& branch) {
  std::vector<Vec3> u(branch.sections.size());
  Vec3 current = geom::anyPerpendicular(branch.sections[0].axis);
  for (std::size_t i = 0; i < branch.sections.size(); ++i) {
    const Vec3& axis = branch.sections[i].axis;
    if (i > 0) current = rotateMinimal(branch.sections[i - 1].axis, axis, current);
    current -= current.dot(axis) * axis;  // remove drift
    double norm = current.norm();
    current = norm > 1e-9 ? Vec3(current / norm) : geom::anyPerpendicular(axis);
    u[i] = current;
  }
  return u;
}

int segmentsFor(const BranchMeshOptions& options, int level) {
  if (options.segmentsPerLevel.empty()) throw OptionsError("branch mesh: segmentsPerLevel is empty");
  std::size_t i = std::min<std::size_t>(static_cast<std::size_t>(std::max(level, 0)), options.segmentsPerLevel.size() - 1);
  return options.segmentsPerLevel[i];
}

}  // namespace

BranchMesh buildBranchMesh(const Skeleton& skeleton, const BranchMeshOptions& options) {
  for (int s : options.segmentsPerLevel)
    if (s < 3) throw OptionsError("branch mesh: segments per ring must be >= 3, got " + std::to_string(s));
  if (std::string problem = findSkeletonProblem(skeleton); !problem.empty())
    throw OptionsError("branch mesh: malformed skeleton: " + problem);

  BranchMesh out;
  auto& verts = out.mesh.vertices;
  auto& tris = out.mesh.triangles;
  for (const SkeletonBranch& b : skeleton.branches) {
    const int n = segmentsFor(options, b.level);
    const std::vector<Vec3> u = ringFrames(b);
    const auto base = static_cast<std::uint32_t>(verts.size());
    out.branchFirstTriangle.push_back(static_cast<std::uint32_t>(tris.size()));
    out.branchRingVertices.push_back(n);
    for (std::size_t i = 0; i < b.sections.size(); ++i) {
      const Section& s = b.sections[i];
      const Vec3 v = s.axis.cross(u[i]);
      for (int j = 0; j < n; ++j) {
        double angle = 2.0 * std::numbers::pi * j / n;
        verts.push_back(s.centre + s.radius * (std::cos(angle) * u[i] + std::sin(angle) * v));
        out.vertexBranch.push_back(b.id);
        out.vertexSection.push_back(static_cast<std::int32_t>(i));
      }
    }
    auto idx = [&](std::size_t ring, int j) { return base + static_cast<std::uint32_t>(ring * n + (j % n)); };
    if (b.parent < 0)  // base cap, facing against the axis
      for (int j = 1; j + 1 < n; ++j) tris.push_back({idx(0, 0), idx(0, j + 1), idx(0, j)});
    for (std::size_t i = 0; i + 1 < b.sections.size(); ++i)
      for (int j = 0; j < n; ++j) {
        tris.push_back({idx(i, j), idx(i, j + 1), idx(i + 1, j + 1)});
        tris.push_back({idx(i, j), idx(i + 1, j + 1), idx(i + 1, j)});
      }
    const std::size_t last = b.sections.size() - 1;  // tip cap, facing along the axis
    for (int j = 1; j + 1 < n; ++j) tris.push_back({idx(last, 0), idx(last, j), idx(last, j + 1)});
    out.branchTriangleCount.push_back(static_cast<std::uint32_t>(tris.size()) - out.branchFirstTriangle.back());
  }
  return out;
}

double inscribedPolygonShare(int sides) {
  if (sides < 3) throw OptionsError("a polygon needs at least 3 sides, got " + std::to_string(sides));
  const double angle = 2.0 * std::numbers::pi / sides;
  return sides * std::sin(angle) / (2.0 * std::numbers::pi);
}

double branchMeshVolume(const Skeleton& skeleton, const BranchMesh& mesh) {
  if (mesh.branchRingVertices.size() != skeleton.branches.size())
    throw OptionsError("branch mesh volume: the mesh has ring counts for " +
                       std::to_string(mesh.branchRingVertices.size()) + " branches, the skeleton has " +
                       std::to_string(skeleton.branches.size()));
  double volume = 0;
  for (std::size_t i = 0; i < skeleton.branches.size(); ++i)
    volume += inscribedPolygonShare(mesh.branchRingVertices[i]) * branchWoodVolume(skeleton.branches[i]);
  return volume;
}

}  // namespace treesketch::gen
