#include "treesketch/gen/skeleton.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "treesketch/util/error.h"

namespace treesketch::gen {

using geom::Vec3;

std::size_t Skeleton::sectionCount() const {
  std::size_t n = 0;
  for (const auto& b : branches) n += b.sections.size();
  return n;
}

int Skeleton::maxLevel() const {
  int level = -1;
  for (const auto& b : branches) level = std::max(level, b.level);
  return level;
}

double branchLength(const SkeletonBranch& branch) {
  double length = 0;
  for (std::size_t i = 1; i < branch.sections.size(); ++i)
    length += (branch.sections[i].centre - branch.sections[i - 1].centre).norm();
  return length;
}

double totalLength(const Skeleton& skeleton) {
  double length = 0;
  for (const auto& b : skeleton.branches) length += branchLength(b);
  return length;
}

geom::BBox bounds(const Skeleton& skeleton) {
  geom::BBox box;
  for (const auto& b : skeleton.branches)
    for (const auto& s : b.sections) {
      box.add(s.centre - Vec3::Constant(s.radius));
      box.add(s.centre + Vec3::Constant(s.radius));
    }
  return box;
}

double frustumVolume(double length, double r0, double r1) {
  return std::numbers::pi * length * (r0 * r0 + r0 * r1 + r1 * r1) / 3.0;
}

double branchWoodVolume(const SkeletonBranch& b) {
  double volume = 0;
  for (std::size_t i = 1; i < b.sections.size(); ++i)
    volume += frustumVolume((b.sections[i].centre - b.sections[i - 1].centre).norm(), b.sections[i - 1].radius,
                            b.sections[i].radius);
  return volume;
}

double woodVolume(const Skeleton& skeleton) {
  double volume = 0;
  for (const auto& b : skeleton.branches) volume += branchWoodVolume(b);
  return volume;
}

NearestSection nearestSection(const Skeleton& skeleton, const Vec3& p) {
  NearestSection best;
  double bestSq = std::numeric_limits<double>::infinity();
  for (const auto& b : skeleton.branches)
    for (std::size_t i = 0; i < b.sections.size(); ++i) {
      double d2 = (b.sections[i].centre - p).squaredNorm();
      if (d2 < bestSq) {
        bestSq = d2;
        best.branch = b.id;
        best.section = static_cast<int>(i);
      }
    }
  if (best.branch >= 0) best.distance = std::sqrt(bestSq);
  return best;
}

double distanceToSectionAxis(const Section& s, const Vec3& p) {
  Vec3 d = p - s.centre;
  return (d - d.dot(s.axis) * s.axis).norm();
}

std::string findSkeletonProblem(const Skeleton& skeleton) {
  for (std::size_t bi = 0; bi < skeleton.branches.size(); ++bi) {
    const SkeletonBranch& b = skeleton.branches[bi];
    std::string where = "branch " + std::to_string(bi);
    if (b.id != static_cast<int>(bi)) return where + ": id is " + std::to_string(b.id) + ", expected its index";
    if (b.level < 0) return where + ": negative level";
    if (b.sections.size() < 2) return where + ": has " + std::to_string(b.sections.size()) + " sections, expected >= 2";
    if (b.parent < 0) {
      if (b.parent != -1 || b.parentSection != -1) return where + ": a root must have parent -1 and parent_section -1";
    } else {
      if (b.parent >= b.id) return where + ": parent " + std::to_string(b.parent) + " does not come before it";
      const SkeletonBranch& parent = skeleton.branches[b.parent];
      if (b.parentSection < 0 || b.parentSection >= static_cast<int>(parent.sections.size()))
        return where + ": parent_section " + std::to_string(b.parentSection) + " out of range [0, " +
               std::to_string(parent.sections.size()) + ")";
    }
    for (std::size_t si = 0; si < b.sections.size(); ++si) {
      const Section& s = b.sections[si];
      std::string at = where + " section " + std::to_string(si);
      if (!s.centre.allFinite()) return at + ": centre is not finite";
      if (!std::isfinite(s.radius) || s.radius <= 0) return at + ": radius must be positive and finite";
      if (!s.axis.allFinite() || std::abs(s.axis.norm() - 1.0) > 1e-6) return at + ": axis must be a unit vector";
    }
  }
  return {};
}

Vec3 convertUpAxis(const Vec3& p, geom::UpAxis from, geom::UpAxis to) {
  if (from == to) return p;
  if (from == geom::UpAxis::Y) return Vec3(p.x(), -p.z(), p.y());  // rotate +90 deg about X: Y -> Z
  return Vec3(p.x(), p.z(), -p.y());                               // the inverse: Z -> Y
}

void convertUpAxis(Skeleton& skeleton, geom::UpAxis to) {
  if (skeleton.up == to) return;
  for (auto& b : skeleton.branches)
    for (auto& s : b.sections) {
      s.centre = convertUpAxis(s.centre, skeleton.up, to);
      s.axis = convertUpAxis(s.axis, skeleton.up, to);
    }
  skeleton.up = to;
}

Skeleton refineSkeleton(const Skeleton& skeleton, int factor) {
  if (factor < 1) throw OptionsError("skeleton refinement factor must be >= 1, got " + std::to_string(factor));
  if (factor == 1) return skeleton;
  Skeleton out;
  out.up = skeleton.up;
  out.branches.reserve(skeleton.branches.size());
  for (const auto& b : skeleton.branches) {
    SkeletonBranch r = b;
    if (r.parentSection >= 0) r.parentSection *= factor;
    r.sections.clear();
    const auto& s = b.sections;
    const std::size_t n = s.size();
    if (n < 2) {
      r.sections = s;
      out.branches.push_back(std::move(r));
      continue;
    }
    // Catmull–Rom tangents (uniform parameter), one-sided at the ends.
    std::vector<Vec3> tangent(n);
    for (std::size_t i = 0; i < n; ++i) {
      const Vec3& prev = s[i == 0 ? 0 : i - 1].centre;
      const Vec3& next = s[i + 1 == n ? n - 1 : i + 1].centre;
      tangent[i] = (i == 0 || i + 1 == n) ? Vec3(next - prev) : Vec3(0.5 * (next - prev));
    }
    for (std::size_t i = 0; i + 1 < n; ++i) {
      r.sections.push_back(s[i]);
      for (int j = 1; j < factor; ++j) {
        double t = static_cast<double>(j) / factor;
        double t2 = t * t, t3 = t2 * t;
        // Cubic Hermite basis and its derivative.
        double h00 = 2 * t3 - 3 * t2 + 1, h10 = t3 - 2 * t2 + t, h01 = -2 * t3 + 3 * t2, h11 = t3 - t2;
        double d00 = 6 * t2 - 6 * t, d10 = 3 * t2 - 4 * t + 1, d01 = -6 * t2 + 6 * t, d11 = 3 * t2 - 2 * t;
        Section q;
        q.centre = h00 * s[i].centre + h10 * tangent[i] + h01 * s[i + 1].centre + h11 * tangent[i + 1];
        Vec3 d = d00 * s[i].centre + d10 * tangent[i] + d01 * s[i + 1].centre + d11 * tangent[i + 1];
        double dn = d.norm();
        q.axis = dn > 0 ? Vec3(d / dn) : Vec3(((1 - t) * s[i].axis + t * s[i + 1].axis).normalized());
        q.radius = (1 - t) * s[i].radius + t * s[i + 1].radius;
        r.sections.push_back(q);
      }
    }
    r.sections.push_back(s.back());
    out.branches.push_back(std::move(r));
  }
  return out;
}

}  // namespace treesketch::gen
