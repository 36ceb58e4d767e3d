// One node's fit: slice, test points, RANSAC, lineEpsilon growth (thesis §4.4, appendix B).
#include "treesketch/fit/node_fit.h"

#include <chrono>
#include <cmath>
#include <sstream>

#include "treesketch/util/error.h"

namespace treesketch::fit {

using geom::Vec2;
using geom::Vec3;

const char* toString(NodeStatus status) {
  switch (status) {
    case NodeStatus::Fitted: return "fitted";
    case NodeStatus::Skipped: return "skipped";
    case NodeStatus::Disabled: return "disabled";
  }
  return "?";
}

namespace {

void checkInputs(const sketch::NodeGeometry& g, const sketch::SamplingParams& p) {
  auto bad = [](const std::string& what) { throw OptionsError("node fit: " + what); };
  auto positive = [](double v) { return v > 0.0 && std::isfinite(v); };
  if (!positive(p.sliceHalfThickness)) bad("sliceHalfThickness must be positive and finite");
  if (!positive(p.lineEpsilon)) bad("lineEpsilon must be positive and finite");
  if (!positive(p.lineEpsilonStep)) bad("lineEpsilonStep must be positive and finite");
  if (!g.planePoint.allFinite() || !g.planeNormal.allFinite() || !(g.planeNormal.norm() > 0.0))
    bad("the node's plane must have a finite point and a non-zero normal");
  if (g.hasLine && (!g.linePoint.allFinite() || !g.lineDir.allFinite() || !(g.lineDir.norm() > 0.0)))
    bad("the node's line must have a finite point and a non-zero direction");
}

}  // namespace

SliceRegion slabRegion(const sketch::NodeGeometry& g, const sketch::SamplingParams& p) {
  checkInputs(g, p);
  SliceRegion r;
  r.kind = SliceRegion::Kind::Slab;
  r.planePoint = g.planePoint;
  r.planeNormal = g.planeNormal.normalized();
  r.halfThickness = p.sliceHalfThickness;
  return r;
}

SliceRegion testRegion(const sketch::NodeGeometry& g, const sketch::SamplingParams& p, double lineEpsilon) {
  SliceRegion r = slabRegion(g, p);
  r.radius = lineEpsilon;
  if (g.hasLine) {
    r.kind = SliceRegion::Kind::Cylinder;
    r.linePoint = g.linePoint;
    r.lineDir = g.lineDir.normalized();
  } else {
    r.kind = SliceRegion::Kind::Ball;
    r.linePoint = g.planePoint;
  }
  return r;
}

std::vector<std::uint32_t> nodeSlice(const CloudIndex& index, const sketch::NodeGeometry& g,
                                     const sketch::SamplingParams& p) {
  return index.query(slabRegion(g, p));
}

NodeResult keptCircleResult(const sketch::NodeGeometry& g, const sketch::SamplingParams& p,
                            const sketch::KeptCircle& circle) {
  NodeResult res;
  checkInputs(g, p);
  res.normal = g.planeNormal.normalized();
  res.lineEpsilon = p.lineEpsilon;
  if (!p.enabled) {
    res.status = NodeStatus::Disabled;
    res.reason = "disabled";
    return res;
  }
  if (!circle.centre.allFinite() || !(circle.radius > 0) || !std::isfinite(circle.radius))
    throw OptionsError("kept circle: the centre must be finite and the radius > 0");
  res.status = NodeStatus::Fitted;
  res.kept = true;
  res.centre = circle.centre - res.normal * res.normal.dot(circle.centre - g.planePoint);
  res.radius = circle.radius;
  return res;
}

NodeResult fitNode(const CloudIndex& index, const sketch::NodeGeometry& g, const sketch::SamplingParams& p,
                   const NodeFitOptions& options) {
  auto t0 = std::chrono::steady_clock::now();
  NodeResult res;
  checkInputs(g, p);
  res.normal = g.planeNormal.normalized();
  res.lineEpsilon = p.lineEpsilon;
  auto finishTiming = [&] {
    res.ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  };
  if (!p.enabled) {
    res.status = NodeStatus::Disabled;
    res.reason = "disabled";
    finishTiming();
    return res;
  }

  // Orthonormal plane basis (u, v); u follows L when L has a component in the plane.
  const Vec3 n = res.normal;
  const Vec3 origin = g.planePoint;
  Vec3 u = g.hasLine ? Vec3(g.lineDir - g.lineDir.dot(n) * n) : Vec3::Zero();
  if (u.norm() < 1e-9) u = geom::anyPerpendicular(n);
  u.normalize();
  const Vec3 v = n.cross(u);
  const PlaneFrame frame{origin, u, v};

  CircleFitOptions circle = options.circle;
  circle.inputFinite = true;  // slices come from the index, which leaves non-finite points out
  circle.centreRegion.active = true;
  circle.centreRegion.hasLine = g.hasLine;
  circle.centreRegion.origin = g.hasLine ? frame(g.linePoint) : Vec2::Zero();
  if (g.hasLine) {
    Vec2 d2(g.lineDir.dot(u), g.lineDir.dot(v));
    if (d2.norm() > 1e-9) {
      circle.centreRegion.dir = d2.normalized();
    } else {
      circle.centreRegion.hasLine = false;  // L pierces the plane: constrain to the pierce point
      double t = (origin - g.linePoint).dot(n) / g.lineDir.dot(n);
      circle.centreRegion.origin = frame(g.linePoint + t * g.lineDir);
    }
  }

  const SliceRegion slab = slabRegion(g, p);
  std::vector<std::uint32_t> near;
  std::vector<Vec3> nearPos;
  std::vector<Vec2> nearCoords;
  // Plane coordinates always come from the index (its float copy, see CloudIndex::query), on
  // both paths and whether or not the slice was computed: the fits then see the same numbers.
  auto computeSlice = [&] {
    if (res.sliceComputed) return;
    near = options.bruteForce ? index.queryBruteForce(slab, &nearPos, &frame, &nearCoords)
                              : index.query(slab, &nearPos, &frame, &nearCoords);
    res.sliceComputed = true;
  };
  if (options.keepSlice || options.bruteForce) computeSlice();

  double eps = p.lineEpsilon;
  std::vector<std::uint32_t> test;
  // Per-thread buffer: a fit is short, and reallocating this (tens of kB) for every node was a
  // visible share of it.
  thread_local std::vector<Vec2> pts2;
  std::string lastReason;
  bool covered = false;
  for (;;) {
    SliceRegion region = testRegion(g, p, eps);
    test.clear();
    if (res.sliceComputed) {
      pts2.clear();
      for (std::size_t i = 0; i < near.size(); ++i)
        if (region.contains(nearPos[i])) {
          test.push_back(near[i]);
          pts2.push_back(nearCoords[i]);
        }
    } else {
      test = index.query(region, nullptr, &frame, &pts2);
    }
    circle.centreRegion.maxDistance = eps;
    CircleFitResult fit = fitCircleRansac(pts2, circle);
    res.iterations += fit.iterations;
    res.lineEpsilon = eps;
    if (fit.ok) {
      res.status = NodeStatus::Fitted;
      res.centre = origin + fit.centre.x() * u + fit.centre.y() * v;
      res.radius = fit.radius;
      res.rms = fit.rms;
      res.inlierIndices.resize(fit.inliers.size());
      for (std::size_t k = 0; k < fit.inliers.size(); ++k) res.inlierIndices[k] = test[fit.inliers[k]];
      break;
    }
    lastReason = fit.reason;
    // Stop when the test points are the whole slice (thesis: testPts == nearPts).
    covered = index.regionCoversCloud(region);
    if (covered) break;
    computeSlice();
    if (test.size() >= near.size()) {
      covered = true;
      break;
    }
    if (res.growthSteps >= options.maxGrowthSteps || (p.maxGrowthSteps >= 0 && res.growthSteps >= p.maxGrowthSteps))
      break;
    eps += p.lineEpsilonStep;
    ++res.growthSteps;
  }
  if (pts2.capacity() > (std::size_t(1) << 20)) pts2 = {};  // do not keep a huge slice's memory per thread
  res.testIndices = std::move(test);
  if (res.sliceComputed) res.sliceIndices = std::move(near);
  if (res.status != NodeStatus::Fitted) {
    std::ostringstream os;
    if (res.sliceComputed && res.sliceIndices.empty())
      os << "no points within " << p.sliceHalfThickness << " of the node's plane";
    else
      os << "no circle found (" << lastReason << ")";
    os << "; lineEpsilon grew from " << p.lineEpsilon << " to " << eps << " in " << res.growthSteps << " steps";
    if (!covered) os << " (growth cap reached)";
    res.reason = os.str();
  }
  finishTiming();
  return res;
}

}  // namespace treesketch::fit
