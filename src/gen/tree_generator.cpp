#include "treesketch/gen/tree_generator.h"

#include <algorithm>
#include <cmath>
#include <deque>
#include <numbers>

#include "treesketch/gen/random.h"
#include "treesketch/util/error.h"

namespace treesketch::gen {

using geom::Vec3;

namespace {

constexpr double kDegToRad = std::numbers::pi / 180.0;
constexpr double kGoldenAngle = 2.399963229728653;  // pi * (3 - sqrt(5)), rad: spiral phyllotaxis
constexpr std::uint64_t kSaltBranch = 1, kSaltLeaves = 2;
constexpr std::size_t kMaxBranches = 200000;  // guards against runaway child counts

/// A branch waiting to be grown: where it starts and its nominal size (drawn by its parent).
struct Bud {
  int parent = -1;
  int parentSection = -1;
  int level = 0;
  Vec3 start = Vec3::Zero();
  Vec3 direction = Vec3::UnitY();
  double length = 0;
  double radius = 0;
};

/// Rotates unit `d` towards unit `target` by `angle` (rad), not past it.
Vec3 bendTowards(const Vec3& d, const Vec3& target, double angle) {
  Vec3 w = target - target.dot(d) * d;
  double wn = w.norm();
  if (wn < 1e-12) return d;
  angle = std::min(angle, std::acos(std::clamp(d.dot(target), -1.0, 1.0)));
  return (std::cos(angle) * d + std::sin(angle) * (w / wn)).normalized();
}

/// Grows the centre line and radii of a bud as a random walk of its direction.
SkeletonBranch growBranch(const Bud& bud, const LevelOptions& lo, double minRadius, Rng& rng) {
  const Vec3 up(0, 1, 0);
  const int n = lo.sections;
  const double step = bud.length / (n - 1);
  std::vector<Vec3> centres{bud.start};
  Vec3 d = bud.direction.normalized();
  for (int i = 1; i < n; ++i) {
    if (i > 1) {  // the first segment leaves at the drawn angle; then gnarl and tropism
      double alpha = rng.normal() * lo.gnarlDeg * kDegToRad * std::sqrt(step);
      double phi = rng.uniform(0.0, 2.0 * std::numbers::pi);
      Vec3 u = geom::anyPerpendicular(d), v = d.cross(u);
      d = (std::cos(alpha) * d + std::sin(alpha) * (std::cos(phi) * u + std::sin(phi) * v)).normalized();
      d = bendTowards(d, lo.tropism >= 0 ? up : Vec3(-up), std::abs(lo.tropism) * step);
    }
    centres.push_back(centres.back() + step * d);
  }
  SkeletonBranch b;
  b.parent = bud.parent;
  b.parentSection = bud.parentSection;
  b.level = bud.level;
  for (int i = 0; i < n; ++i) {
    Section s;
    s.centre = centres[i];
    Vec3 tangent = centres[std::min(i + 1, n - 1)] - centres[std::max(i - 1, 0)];
    s.axis = tangent.normalized();
    double t = static_cast<double>(i) / (n - 1);
    s.radius = std::max(minRadius, bud.radius * (1.0 - (1.0 - lo.tipRadius) * t));
    s.radius = std::min(s.radius, bud.radius);  // never thicker than the base
    b.sections.push_back(s);
  }
  return b;
}

/// Orthonormal frames along a branch (u transported by projection), for placing children.
std::vector<Vec3> transportedFrames(const SkeletonBranch& b) {
  std::vector<Vec3> u;
  Vec3 current = geom::anyPerpendicular(b.sections[0].axis);
  for (const Section& s : b.sections) {
    current -= current.dot(s.axis) * s.axis;
    current = current.norm() > 1e-9 ? Vec3(current.normalized()) : geom::anyPerpendicular(s.axis);
    u.push_back(current);
  }
  return u;
}

/// Draws the children buds of branch `b` (of level b.level) from its random stream.
void budChildren(const SkeletonBranch& b, const TreeOptions& options, Rng& rng, std::vector<Bud>& buds) {
  const LevelOptions& lo = options.levels[b.level];
  if (lo.children == 0 || b.level + 1 >= static_cast<int>(options.levels.size())) return;
  const LevelOptions& child = options.levels[b.level + 1];
  const int n = static_cast<int>(b.sections.size());
  const double length = branchLength(b);
  const std::vector<Vec3> frames = transportedFrames(b);
  const double phase = rng.uniform(0.0, 2.0 * std::numbers::pi);
  for (int c = 0; c < lo.children; ++c) {
    double u = std::clamp((c + 0.5 + rng.uniform(-0.4, 0.4)) / lo.children, 0.0, 1.0);
    double t = lo.childStart + (1.0 - lo.childStart) * u;
    int k = std::clamp(static_cast<int>(std::lround(t * (n - 1))), 0, n - 2);
    const Section& at = b.sections[k];
    double theta = std::clamp(child.angleDeg + child.angleJitterDeg * rng.normal(), 5.0, 150.0) * kDegToRad;
    double phi = phase + c * kGoldenAngle + rng.uniform(-0.3, 0.3);
    Vec3 fu = frames[k], fv = at.axis.cross(fu);
    Bud bud;
    bud.parent = b.id;
    bud.parentSection = k;
    bud.level = b.level + 1;
    bud.start = at.centre;
    bud.direction = (std::cos(theta) * at.axis + std::sin(theta) * (std::cos(phi) * fu + std::sin(phi) * fv)).normalized();
    double jitter = std::clamp(1.0 + child.lengthJitter * rng.normal(), 0.3, 1.7);
    bud.length = child.length * length * (1.0 - lo.childLengthTaper * u) * jitter;
    bud.radius = std::min(std::max(child.radius * at.radius, options.minRadius), at.radius);
    buds.push_back(bud);
  }
}

/// Leaf quads along the outer part of the branches of the highest levels (Y-up, coarse skeleton).
geom::TriMesh growLeaves(const Skeleton& skeleton, const TreeOptions& options) {
  geom::TriMesh leaves;
  const int minLevel = skeleton.maxLevel() - options.leafLevels + 1;
  const double s = options.leafSize;
  for (const SkeletonBranch& b : skeleton.branches) {
    if (b.level < minLevel) continue;
    Rng rng = Rng::substream(options.seed, static_cast<std::uint64_t>(b.id), kSaltLeaves);
    std::vector<double> cumulative{0.0};
    for (std::size_t i = 1; i < b.sections.size(); ++i)
      cumulative.push_back(cumulative.back() + (b.sections[i].centre - b.sections[i - 1].centre).norm());
    const double length = cumulative.back();
    if (length <= 0) continue;
    for (int l = 0; l < options.leavesPerBranch; ++l) {
      double at = rng.uniform(options.leafStart, 1.0) * length;
      std::size_t i = std::upper_bound(cumulative.begin(), cumulative.end(), at) - cumulative.begin();
      i = std::clamp<std::size_t>(i, 1, b.sections.size() - 1);
      const Section &s0 = b.sections[i - 1], &s1 = b.sections[i];
      double seg = cumulative[i] - cumulative[i - 1];
      double f = seg > 0 ? std::clamp((at - cumulative[i - 1]) / seg, 0.0, 1.0) : 0.0;
      Vec3 axis = (s1.centre - s0.centre).normalized();
      Vec3 centre = (1 - f) * s0.centre + f * s1.centre;
      double radius = (1 - f) * s0.radius + f * s1.radius;
      Vec3 pu = geom::anyPerpendicular(axis), pv = axis.cross(pu);
      double phi = rng.uniform(0.0, 2.0 * std::numbers::pi);
      Vec3 w = std::cos(phi) * pu + std::sin(phi) * pv;
      Vec3 e1 = (w + rng.uniform(0.0, 1.0) * axis).normalized();  // leaf points outwards and forwards
      Vec3 t0 = geom::anyPerpendicular(e1), t1 = e1.cross(t0);
      double gamma = rng.uniform(0.0, std::numbers::pi);
      Vec3 e2 = std::cos(gamma) * t0 + std::sin(gamma) * t1;
      Vec3 base = centre + radius * w;
      auto first = static_cast<std::uint32_t>(leaves.vertices.size());
      leaves.vertices.push_back(base - 0.5 * s * e2);
      leaves.vertices.push_back(base + 0.5 * s * e2);
      leaves.vertices.push_back(base + s * e1 + 0.5 * s * e2);
      leaves.vertices.push_back(base + s * e1 - 0.5 * s * e2);
      leaves.triangles.push_back({first, first + 1, first + 2});
      leaves.triangles.push_back({first, first + 2, first + 3});
    }
  }
  return leaves;
}

/// The Y-up skeleton at the base resolution (before refinement).
Skeleton growCoarseSkeleton(const TreeOptions& options) {
  Skeleton skeleton;
  skeleton.up = geom::UpAxis::Y;
  const LevelOptions& trunk = options.levels[0];
  Rng trunkRng = Rng::substream(options.seed, 0, kSaltBranch);
  Bud root;
  root.length = trunk.length * std::clamp(1.0 + trunk.lengthJitter * trunkRng.normal(), 0.3, 1.7);
  root.radius = trunk.radius;
  std::deque<Bud> queue{root};
  std::vector<Bud> buds;
  while (!queue.empty()) {
    Bud bud = queue.front();
    queue.pop_front();
    const int id = static_cast<int>(skeleton.branches.size());
    Rng rng = id == 0 ? trunkRng : Rng::substream(options.seed, static_cast<std::uint64_t>(id), kSaltBranch);
    SkeletonBranch b = growBranch(bud, options.levels[bud.level], options.minRadius, rng);
    b.id = id;
    buds.clear();
    budChildren(b, options, rng, buds);
    skeleton.branches.push_back(std::move(b));
    queue.insert(queue.end(), buds.begin(), buds.end());
    if (skeleton.branches.size() + queue.size() > kMaxBranches)
      throw OptionsError("tree generator: more than " + std::to_string(kMaxBranches) +
                         " branches; reduce the children counts");
  }
  return skeleton;
}

void rotateMesh(geom::TriMesh& mesh, geom::UpAxis to) {
  for (Vec3& v : mesh.vertices) v = convertUpAxis(v, geom::UpAxis::Y, to);
}

}  // namespace

std::vector<LevelOptions> defaultLevels() {
  LevelOptions trunk;
  trunk.length = 7.0;
  trunk.radius = 0.15;
  trunk.tipRadius = 0.15;
  trunk.sections = 16;
  trunk.segments = 12;
  trunk.gnarlDeg = 6;
  trunk.tropism = 0.3;
  trunk.lengthJitter = 0.05;
  trunk.children = 14;
  trunk.childStart = 0.3;
  trunk.childLengthTaper = 0.55;

  LevelOptions l1;
  l1.length = 0.5;
  l1.radius = 0.55;
  l1.tipRadius = 0.2;
  l1.sections = 10;
  l1.segments = 8;
  l1.angleDeg = 50;
  l1.angleJitterDeg = 10;
  l1.gnarlDeg = 12;
  l1.tropism = 0.15;
  l1.children = 5;
  l1.childStart = 0.25;
  l1.childLengthTaper = 0.4;

  LevelOptions l2;
  l2.length = 0.45;
  l2.radius = 0.6;
  l2.tipRadius = 0.25;
  l2.sections = 8;
  l2.segments = 6;
  l2.angleDeg = 40;
  l2.angleJitterDeg = 12;
  l2.gnarlDeg = 15;
  l2.tropism = 0.1;
  l2.children = 4;
  l2.childStart = 0.3;
  l2.childLengthTaper = 0.4;

  LevelOptions l3;
  l3.length = 0.4;
  l3.radius = 0.6;
  l3.tipRadius = 0.3;
  l3.sections = 4;
  l3.segments = 6;
  l3.angleDeg = 35;
  l3.angleJitterDeg = 12;
  l3.gnarlDeg = 20;
  l3.tropism = 0.05;
  l3.children = 0;
  return {trunk, l1, l2, l3};
}

void TreeOptions::validate() const {
  auto fail = [](const std::string& what) { throw OptionsError("tree generator: " + what); };
  if (levels.empty() || levels.size() > 5) fail("levels must hold 1 to 5 entries, got " + std::to_string(levels.size()));
  for (std::size_t i = 0; i < levels.size(); ++i) {
    const LevelOptions& l = levels[i];
    std::string at = "level " + std::to_string(i) + ": ";
    auto finite = [](double x) { return std::isfinite(x); };
    if (!finite(l.length) || l.length <= 0) fail(at + "length must be positive");
    if (!finite(l.radius) || l.radius <= 0 || (i > 0 && l.radius > 1))
      fail(at + (i == 0 ? "radius must be positive" : "radius fraction must be in (0, 1]"));
    if (!finite(l.tipRadius) || l.tipRadius <= 0 || l.tipRadius > 1) fail(at + "tipRadius must be in (0, 1]");
    if (l.sections < 2 || l.sections > 1000) fail(at + "sections must be in [2, 1000]");
    if (l.segments < 3 || l.segments > 256) fail(at + "segments must be in [3, 256]");
    if (!finite(l.angleDeg) || !finite(l.angleJitterDeg) || l.angleJitterDeg < 0) fail(at + "bad branch angle");
    if (!finite(l.gnarlDeg) || l.gnarlDeg < 0) fail(at + "gnarlDeg must be >= 0");
    if (!finite(l.tropism)) fail(at + "tropism must be finite");
    if (!finite(l.lengthJitter) || l.lengthJitter < 0 || l.lengthJitter >= 1) fail(at + "lengthJitter must be in [0, 1)");
    if (l.children < 0 || l.children > 1000) fail(at + "children must be in [0, 1000]");
    if (!finite(l.childStart) || l.childStart < 0 || l.childStart >= 1) fail(at + "childStart must be in [0, 1)");
    if (!finite(l.childLengthTaper) || l.childLengthTaper < 0 || l.childLengthTaper >= 1)
      fail(at + "childLengthTaper must be in [0, 1)");
  }
  double perBranch = 1, expected = 1;  // branches of each level, expected total
  for (std::size_t i = 0; i + 1 < levels.size(); ++i) expected += (perBranch *= levels[i].children);
  if (expected > static_cast<double>(kMaxBranches))
    fail("the children counts give " + std::to_string(static_cast<long long>(expected)) + " branches, more than " +
         std::to_string(kMaxBranches));
  if (detail < 1 || detail > 16) fail("detail must be in [1, 16], got " + std::to_string(detail));
  if (!std::isfinite(minRadius) || minRadius <= 0 || minRadius > levels[0].radius)
    fail("minRadius must be in (0, trunk radius]");
  if (leaves) {
    if (leafLevels < 1) fail("leafLevels must be >= 1");
    if (leavesPerBranch < 0 || leavesPerBranch > 10000) fail("leavesPerBranch must be in [0, 10000]");
    if (!std::isfinite(leafSize) || leafSize <= 0) fail("leafSize must be positive");
    if (!std::isfinite(leafStart) || leafStart < 0 || leafStart > 1) fail("leafStart must be in [0, 1]");
  }
}

std::vector<std::string> presetNames() { return {"default", "conifer", "sparse"}; }

TreeOptions presetOptions(const std::string& name) {
  TreeOptions o;
  if (name == "default") return o;
  if (name == "conifer") {
    o.levels.resize(3);
    LevelOptions& trunk = o.levels[0];
    trunk = LevelOptions{};
    trunk.length = 9.0;
    trunk.radius = 0.18;
    trunk.tipRadius = 0.05;
    trunk.sections = 20;
    trunk.segments = 12;
    trunk.gnarlDeg = 2;
    trunk.tropism = 1.0;
    trunk.lengthJitter = 0.05;
    trunk.children = 36;
    trunk.childStart = 0.15;
    trunk.childLengthTaper = 0.85;
    LevelOptions& l1 = o.levels[1];
    l1 = LevelOptions{};
    l1.length = 0.4;
    l1.radius = 0.45;
    l1.tipRadius = 0.2;
    l1.sections = 8;
    l1.segments = 6;
    l1.angleDeg = 80;
    l1.angleJitterDeg = 8;
    l1.gnarlDeg = 10;
    l1.tropism = -0.05;
    l1.children = 6;
    l1.childStart = 0.2;
    l1.childLengthTaper = 0.5;
    LevelOptions& l2 = o.levels[2];
    l2 = LevelOptions{};
    l2.length = 0.35;
    l2.radius = 0.6;
    l2.tipRadius = 0.3;
    l2.sections = 4;
    l2.segments = 4;
    l2.angleDeg = 50;
    l2.gnarlDeg = 15;
    l2.tropism = 0.0;
    o.leafSize = 0.04;
    o.leavesPerBranch = 6;
    return o;
  }
  if (name == "sparse") {
    o.levels.resize(3);
    o.levels[0].length = 6.0;
    o.levels[0].radius = 0.12;
    o.levels[0].children = 6;
    o.levels[0].childStart = 0.4;
    o.levels[1].length = 0.55;
    o.levels[1].children = 3;
    o.levels[2] = defaultLevels()[3];
    o.levels[2].length = 0.45;
    o.levels[2].sections = 5;
    o.leavesPerBranch = 10;
    return o;
  }
  throw OptionsError("unknown tree preset '" + name + "' (expected default, conifer or sparse)");
}

Skeleton generateSkeleton(const TreeOptions& options) {
  options.validate();
  Skeleton skeleton = refineSkeleton(growCoarseSkeleton(options), options.detail);
  convertUpAxis(skeleton, options.up);
  return skeleton;
}

GeneratedTree generateTree(const TreeOptions& options) {
  options.validate();
  const Skeleton coarse = growCoarseSkeleton(options);
  GeneratedTree tree;
  tree.skeleton = refineSkeleton(coarse, options.detail);
  BranchMeshOptions meshOptions;
  meshOptions.segmentsPerLevel.clear();
  for (const LevelOptions& l : options.levels) meshOptions.segmentsPerLevel.push_back(l.segments * options.detail);
  tree.branches = buildBranchMesh(tree.skeleton, meshOptions);
  if (options.leaves) tree.leaves = growLeaves(coarse, options);
  if (options.up != geom::UpAxis::Y) {
    convertUpAxis(tree.skeleton, options.up);
    rotateMesh(tree.branches.mesh, options.up);
    rotateMesh(tree.leaves, options.up);
  }
  return tree;
}

}  // namespace treesketch::gen
