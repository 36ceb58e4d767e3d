// One node's fit: slice, test points, RANSAC, lineEpsilon growth (thesis §4.4, appendix B).
#include "treesketch/fit/node_fit.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "treesketch/util/error.h"
#include "treesketch/util/stopwatch.h"

namespace treesketch::fit {

using geom::Vec2;
using geom::Vec3;

const char* toString(NodeStatus status) {
  switch (status) {
    case NodeStatus::Fitted:
      return "fitted";
    case NodeStatus::Skipped:
      return "skipped";
    case NodeStatus::Disabled:
      return "disabled";
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

namespace {

// Orthonormal plane basis (u, v) at the node's plane point; u follows L when L has a component in
// the plane.
PlaneFrame nodePlaneFrame(const sketch::NodeGeometry& g, const Vec3& n) {
  const Vec3 origin = g.planePoint;
  Vec3 u = g.hasLine ? Vec3(g.lineDir - g.lineDir.dot(n) * n) : Vec3::Zero();
  if (u.norm() < 1e-9) u = geom::anyPerpendicular(n);
  u.normalize();
  const Vec3 v = n.cross(u);
  return PlaneFrame{origin, u, v};
}

// The circle fit's options with the centre constrained to L (or to where L pierces the plane).
CircleFitOptions nodeCircleOptions(const NodeFitOptions& options, const sketch::NodeGeometry& g,
                                   const PlaneFrame& frame, const Vec3& n) {
  const Vec3& origin = frame.origin;
  const Vec3& u = frame.u;
  const Vec3& v = frame.v;
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
  return circle;
}

// Depth choice (screen nodes, options.chooseDepth): u runs along L (the plane contains L), so a
// test point's u coordinate is its depth along the view ray from L's near point.
struct DepthChoice {
  const DepthChoiceOptions& dc;
  const FitPrior* prior;
  double sliceHalfThickness;
  double gap;
  double expectedDepth;
  double maxJump;
};

DepthChoice depthChoice(const sketch::NodeGeometry& g, const sketch::SamplingParams& p, const NodeFitOptions& options,
                        const FitPrior* prior, const PlaneFrame& frame) {
  const DepthChoiceOptions& dc = options.depth;
  const double gap = dc.gap > 0 ? dc.gap : 4.0 * p.sliceHalfThickness;
  const double expectedDepth =
      prior ? (prior->centre - frame.origin).dot(frame.u) : std::numeric_limits<double>::quiet_NaN();
  // How far in depth the branch may have gone from its parent: maxTurn times the sideways
  // distance from the parent's centre to L (a branch turned towards or away from the viewer; a
  // steeper one is drawn from another view), plus the parent's radii and the surface gap.
  double maxJump = std::numeric_limits<double>::infinity();
  if (prior && g.hasLine) {
    const Vec3 d = prior->centre - g.linePoint;
    const Vec3 dirN = g.lineDir.normalized();
    const double lateral = (d - d.dot(dirN) * dirN).norm();
    maxJump = dc.maxTurn * lateral + dc.jumpRadii * prior->radius + gap;
  }
  return DepthChoice{dc, prior, p.sliceHalfThickness, gap, expectedDepth, maxJump};
}

// One circle per hypothesis: all surfaces together (a wide trunk's two arcs), the window where
// the parent says the branch is, and each group of points separated by more than a gap in depth.
std::vector<CircleFitResult> depthHypotheses(const DepthChoice& d, const std::vector<Vec2>& pts,
                                             const CircleFitOptions& copt) {
  std::vector<std::uint32_t> order(pts.size());
  for (std::uint32_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) { return pts[a].x() < pts[b].x(); });
  std::vector<std::pair<std::size_t, std::size_t>> groups;  // ranges of `order`
  std::size_t b0 = 0;
  for (std::size_t i = 1; i <= order.size(); ++i)
    if (i == order.size() || pts[order[i]].x() - pts[order[i - 1]].x() > d.gap) {
      groups.emplace_back(b0, i);
      b0 = i;
    }
  std::vector<CircleFitResult> hyps;
  hyps.push_back(fitCircleRansac(pts, copt));  // all surfaces together (a wide trunk's two arcs)
  if (std::isfinite(d.expectedDepth)) {
    // The window where the parent says the branch is: clutter elsewhere along the ray (leaves
    // in front, a limb behind) stays out of this hypothesis's RANSAC.
    std::vector<Vec2> win;
    std::vector<std::uint32_t> idx;
    for (std::uint32_t i = 0; i < pts.size(); ++i)
      if (std::abs(pts[i].x() - d.expectedDepth) <= d.maxJump) {
        win.push_back(pts[i]);
        idx.push_back(i);
      }
    if (win.size() >= std::size_t(std::max(copt.minInliers, 3)) && win.size() < pts.size()) {
      CircleFitResult h = fitCircleRansac(win, copt);
      for (auto& in : h.inliers) in = idx[in];
      hyps.push_back(std::move(h));
    }
  }
  if (groups.size() > 1) {
    std::vector<Vec2> sub;
    for (const auto& [a, e] : groups) {
      if (e - a < std::size_t(std::max(copt.minInliers, 3))) continue;
      sub.clear();
      for (std::size_t k = a; k < e; ++k) sub.push_back(pts[order[k]]);
      CircleFitResult h = fitCircleRansac(sub, copt);
      for (auto& in : h.inliers) in = order[a + in];
      std::sort(h.inliers.begin(), h.inliers.end());
      hyps.push_back(std::move(h));
    }
  }
  return hyps;
}

// With a parent, circles wider than it allows or beyond maxJump from its depth are refused. The
// parent's radius bounds the circles taken, after RANSAC: as a RANSAC bound it made the fit
// settle for a smaller circle on an arc of the wider branch.
void refuseHypotheses(const DepthChoice& d, std::vector<CircleFitResult>& hyps, int& refused, int& tooWide) {
  const double radiusCap = d.prior && d.dc.maxRadiusOfParent > 0 && d.prior->radius > 0
                               ? d.dc.maxRadiusOfParent * d.prior->radius + d.sliceHalfThickness
                               : std::numeric_limits<double>::infinity();
  for (auto& h : hyps) {
    if (h.ok && h.radius > radiusCap) {
      h.ok = false;
      ++tooWide;
    } else if (h.ok && std::abs(h.centre.x() - d.expectedDepth) > d.maxJump) {
      h.ok = false;
      ++refused;
    }
  }
}

// The index of the hypothesis to take (-1: none is ok): the one nearest the wanted depth.
int bestHypothesis(const DepthChoice& d, const std::vector<CircleFitResult>& hyps, double want) {
  int best = -1;
  for (std::size_t k = 0; k < hyps.size(); ++k) {
    if (!hyps[k].ok) continue;
    if (best < 0) {
      best = int(k);
      continue;
    }
    // Cost: the distance from the expected depth (in surface gaps, ties within half a gap),
    // and with a parent also how far the radius is from the parent's (a limb tapers; a circle
    // through a clump of leaves near the right depth has any radius): one factor of 2 in
    // radius weighs as much as one parent diameter in depth.
    auto cost = [&](const CircleFitResult& h) {
      double c = std::abs(h.centre.x() - want);
      if (d.prior && d.prior->radius > 0 && h.radius > 0)
        c += 2.0 * d.prior->radius * std::abs(std::log2(h.radius / d.prior->radius));
      return c;
    };
    const double dk = cost(hyps[k]), db = cost(hyps[best]);
    if (dk + 1e-12 < db - d.gap * 0.5 ||
        (std::abs(dk - db) <= d.gap * 0.5 && hyps[k].inliers.size() > hyps[best].inliers.size()))
      best = int(k);
  }
  return best;
}

// Fits a circle per surface along the view ray and takes the one continuing the parent (or the
// front-most); records the depth, the number of surfaces and a warning in res.
CircleFitResult fitByDepth(const DepthChoice& d, const std::vector<Vec2>& pts, const CircleFitOptions& copt,
                           NodeResult& res) {
  std::vector<CircleFitResult> hyps = depthHypotheses(d, pts, copt);
  double front = std::numeric_limits<double>::infinity();
  int distinct = 0;
  std::vector<double> seen;
  int refused = 0, tooWide = 0;
  refuseHypotheses(d, hyps, refused, tooWide);
  for (const auto& h : hyps) {
    if (!h.ok) continue;
    front = std::min(front, h.centre.x());
    if (std::none_of(seen.begin(), seen.end(), [&](double x) { return std::abs(x - h.centre.x()) <= d.gap; })) {
      seen.push_back(h.centre.x());
      ++distinct;
    }
  }
  const double want = std::isfinite(d.expectedDepth) ? d.expectedDepth : front;
  const int best = bestHypothesis(d, hyps, want);
  res.depthHypotheses = distinct;
  if (best < 0) {
    if (refused > 0 || tooWide > 0) {
      CircleFitResult none;
      none.reason = std::to_string(refused) + " circle(s) far along the view ray from the parent's depth and " +
                    std::to_string(tooWide) + " wider than the parent allows (not taken)";
      return none;
    }
    return hyps.front();
  }
  CircleFitResult out = std::move(hyps[best]);
  res.depth = out.centre.x();
  const double off = std::abs(out.centre.x() - want);
  res.depthJump = off > d.dc.jumpRadii * out.radius + d.gap;
  if (res.depthJump) {
    std::ostringstream w;
    w << "the circle lies " << off << " along the view ray from "
      << (std::isfinite(d.expectedDepth) ? "the parent's depth" : "the front-most surface") << " (" << distinct
      << " surfaces had a circle): check it from another view";
    res.warning = w.str();
  } else if (distinct > 1) {
    res.warning = std::to_string(distinct) + " surfaces along the view ray had a circle; took the one " +
                  (std::isfinite(d.expectedDepth) ? "continuing the parent" : "in front");
  }
  return out;
}

// The slice around the node's plane, computed once and only when needed. Plane coordinates always
// come from the index (its float copy, see CloudIndex::query), on both paths and whether or not
// the slice was computed: the fits then see the same numbers.
struct NodeSliceCache {
  std::vector<std::uint32_t> near;
  std::vector<Vec3> nearPos;
  std::vector<Vec2> nearCoords;

  void compute(const CloudIndex& index, const SliceRegion& slab, const PlaneFrame& frame, bool bruteForce,
               NodeResult& res) {
    if (res.sliceComputed) return;
    near = bruteForce ? index.queryBruteForce(slab, &nearPos, &frame, &nearCoords)
                      : index.query(slab, &nearPos, &frame, &nearCoords);
    res.sliceComputed = true;
  }
};

// The test points for one lineEpsilon: from the slice when it is known, else from the index.
void gatherTestPoints(const CloudIndex& index, const NodeSliceCache& slice, const SliceRegion& region,
                      const PlaneFrame& frame, bool sliceComputed, std::vector<std::uint32_t>& test,
                      std::vector<Vec2>& pts2) {
  test.clear();
  if (sliceComputed) {
    pts2.clear();
    for (std::size_t i = 0; i < slice.near.size(); ++i)
      if (region.contains(slice.nearPos[i])) {
        test.push_back(slice.near[i]);
        pts2.push_back(slice.nearCoords[i]);
      }
  } else {
    test = index.query(region, nullptr, &frame, &pts2);
  }
}

void takeFit(const CircleFitResult& fit, const PlaneFrame& frame, const std::vector<std::uint32_t>& test,
             NodeResult& res) {
  res.status = NodeStatus::Fitted;
  res.centre = frame.origin + fit.centre.x() * frame.u + fit.centre.y() * frame.v;
  res.radius = fit.radius;
  res.rms = fit.rms;
  res.inlierIndices.resize(fit.inliers.size());
  for (std::size_t k = 0; k < fit.inliers.size(); ++k) res.inlierIndices[k] = test[fit.inliers[k]];
}

std::string skipReason(const NodeResult& res, const sketch::SamplingParams& p, const std::string& lastReason,
                       double eps, bool covered) {
  std::ostringstream os;
  if (res.sliceComputed && res.sliceIndices.empty())
    os << "no points within " << p.sliceHalfThickness << " of the node's plane";
  else
    os << "no circle found (" << lastReason << ")";
  os << "; lineEpsilon grew from " << p.lineEpsilon << " to " << eps << " in " << res.growthSteps << " steps";
  if (!covered) os << " (growth cap reached)";
  return os.str();
}

}  // namespace

NodeResult fitNode(const CloudIndex& index, const sketch::NodeGeometry& g, const sketch::SamplingParams& p,
                   const NodeFitOptions& options, const FitPrior* prior) {
  const Stopwatch timer;
  NodeResult res;
  checkInputs(g, p);
  res.normal = g.planeNormal.normalized();
  res.lineEpsilon = p.lineEpsilon;
  auto finishTiming = [&] { res.ms = timer.ms(); };
  if (!p.enabled) {
    res.status = NodeStatus::Disabled;
    res.reason = "disabled";
    finishTiming();
    return res;
  }
  const PlaneFrame frame = nodePlaneFrame(g, res.normal);
  CircleFitOptions circle = nodeCircleOptions(options, g, frame, res.normal);
  const SliceRegion slab = slabRegion(g, p);
  NodeSliceCache slice;
  if (options.keepSlice || options.bruteForce) slice.compute(index, slab, frame, options.bruteForce, res);
  const DepthChoice depth = depthChoice(g, p, options, prior, frame);

  double eps = p.lineEpsilon;
  std::vector<std::uint32_t> test;
  // Per-thread buffer: a fit is short, and reallocating this (tens of kB) for every node was a
  // visible share of it.
  thread_local std::vector<Vec2> pts2;
  std::string lastReason;
  bool covered = false;
  for (;;) {
    SliceRegion region = testRegion(g, p, eps);
    gatherTestPoints(index, slice, region, frame, res.sliceComputed, test, pts2);
    circle.centreRegion.maxDistance = eps;
    CircleFitResult fit =
        options.chooseDepth && g.hasLine ? fitByDepth(depth, pts2, circle, res) : fitCircleRansac(pts2, circle);
    res.iterations += fit.iterations;
    res.lineEpsilon = eps;
    if (fit.ok) {
      takeFit(fit, frame, test, res);
      break;
    }
    lastReason = fit.reason;
    // Stop when the test points are the whole slice (thesis: testPts == nearPts).
    covered = index.regionCoversCloud(region);
    if (covered) break;
    slice.compute(index, slab, frame, options.bruteForce, res);
    if (test.size() >= slice.near.size()) {
      covered = true;
      break;
    }
    if (res.growthSteps >= options.maxGrowthSteps || (p.maxGrowthSteps >= 0 && res.growthSteps >= p.maxGrowthSteps) ||
        (g.hasLine && !options.growScreenNodes))
      break;
    eps += p.lineEpsilonStep;
    ++res.growthSteps;
  }
  if (pts2.capacity() > (std::size_t(1) << 20)) pts2 = {};  // do not keep a huge slice's memory per thread
  res.testIndices = std::move(test);
  if (res.sliceComputed) res.sliceIndices = std::move(slice.near);
  if (res.status != NodeStatus::Fitted) res.reason = skipReason(res, p, lastReason, eps, covered);
  finishTiming();
  return res;
}

}  // namespace treesketch::fit
