// RANSAC circle fit (thesis §4.4, appendix B) with least-squares refinement.
#include "treesketch/fit/circle_fit.h"

#include <Eigen/Dense>
#include <algorithm>
#include <limits>
#include <cmath>
#include <numeric>
#include <random>

#include "treesketch/util/error.h"

namespace treesketch::fit {

using geom::Vec2;

bool CentreRegion::contains(const Vec2& c) const {
  if (!active) return true;
  Vec2 d = c - origin;
  double dist = hasLine ? std::abs(d.x() * dir.y() - d.y() * dir.x()) : d.norm();
  return dist <= maxDistance;
}

bool circleFrom3(const Vec2& a, const Vec2& b, const Vec2& c, Vec2* centre, double* radius) {
  Vec2 ab = b - a, ac = c - a;
  double d = 2.0 * (ab.x() * ac.y() - ab.y() * ac.x());
  double scale = ab.squaredNorm() * ac.squaredNorm();
  // Reject (nearly) collinear triples: |sin(angle)| below ~1e-6.
  if (!(d * d > 4e-12 * scale) || scale == 0.0) return false;
  double ab2 = ab.squaredNorm(), ac2 = ac.squaredNorm();
  Vec2 rel((ac.y() * ab2 - ab.y() * ac2) / d, (ab.x() * ac2 - ac.x() * ab2) / d);
  *centre = a + rel;
  *radius = rel.norm();
  return std::isfinite(*radius);
}

namespace {

bool kasaFit(const std::vector<Vec2>& pts, const std::vector<std::uint32_t>& idx, Vec2* centre, double* radius) {
  Vec2 mean = Vec2::Zero();
  for (auto i : idx) mean += pts[i];
  mean /= double(idx.size());
  // Minimize Σ (x² + y² + D x + E y + F)² in coordinates relative to the mean.
  double sxx = 0, sxy = 0, syy = 0, sx = 0, sy = 0, bx = 0, by = 0, b1 = 0;
  for (auto i : idx) {
    const double x = pts[i].x() - mean.x(), y = pts[i].y() - mean.y();
    const double rhs = -(x * x + y * y);
    sxx += x * x;
    sxy += x * y;
    syy += y * y;
    sx += x;
    sy += y;
    bx += x * rhs;
    by += y * rhs;
    b1 += rhs;
  }
  Eigen::Matrix3d ata;
  ata << sxx, sxy, sx, sxy, syy, sy, sx, sy, double(idx.size());
  Eigen::Vector3d atb(bx, by, b1);
  Eigen::LDLT<Eigen::Matrix3d> ldlt(ata);
  if (ldlt.info() != Eigen::Success) return false;
  Eigen::Vector3d s = ldlt.solve(atb);
  if (!s.allFinite()) return false;
  Vec2 c(-0.5 * s[0], -0.5 * s[1]);
  double r2 = c.squaredNorm() - s[2];
  if (!(r2 > 0.0)) return false;
  *centre = c + mean;
  *radius = std::sqrt(r2);
  return true;
}

// atan2 in degrees within ±0.3° (a rational approximation of atan on [0, 1]), in [0, 360).
double fastAngleDeg(double y, double x) {
  // Selects instead of branches (the signs of noisy data are unpredictable); (0, 0) gives 0.
  const double ax = std::abs(x), ay = std::abs(y);
  const double mx = std::max(std::max(ax, ay), 1e-300);
  const double z = std::min(ax, ay) / mx;
  double a = z * (M_PI / 4 + 0.273 * (1.0 - z));  // atan(z), |error| < 0.004 rad
  a = ay > ax ? M_PI / 2 - a : a;
  a = x < 0 ? M_PI - a : a;
  a = y < 0 ? 2 * M_PI - a : a;
  return a * (180.0 / M_PI);
}

}  // namespace

bool fitCircleLeastSquares(const std::vector<Vec2>& pts, const std::vector<std::uint32_t>& idx, int iterations,
                           Vec2* centre, double* radius) {
  if (idx.size() < 3) return false;
  Vec2 c;
  double r;
  if (!kasaFit(pts, idx, &c, &r)) {
    // Kåsa fails only for (nearly) collinear data; start from the given estimate if any.
    if (!(*radius > 0.0) || !centre->allFinite()) return false;
    c = *centre;
    r = *radius;
  }
  // Gauss–Newton on the geometric residuals |p − c| − r. Each pass evaluates the cost at the
  // current circle with the normal equations; a step that raised the cost is undone.
  Vec2 prevC = c;
  double prevR = r, prevCost = std::numeric_limits<double>::infinity();
  for (int it = 0; it < iterations; ++it) {
    // J row = (−dx/n, −dy/n, −1); accumulate the 6 distinct entries of JᵀJ and Jᵀr.
    double sxx = 0, sxy = 0, syy = 0, sx = 0, sy = 0, cnt = 0, rx = 0, ry = 0, rr = 0, cost = 0.0;
    const double cx = c.x(), cy = c.y();
    for (auto i : idx) {
      double dx = pts[i].x() - cx, dy = pts[i].y() - cy;
      double n = std::sqrt(dx * dx + dy * dy);
      if (n <= 0.0) continue;
      double ux = dx / n, uy = dy / n, res = n - r;
      cost += res * res;
      sxx += ux * ux;
      sxy += ux * uy;
      syy += uy * uy;
      sx += ux;
      sy += uy;
      cnt += 1.0;
      rx += ux * res;
      ry += uy * res;
      rr += res;
    }
    Eigen::Matrix3d jtj;
    jtj << sxx, sxy, sx, sxy, syy, sy, sx, sy, cnt;
    Eigen::Vector3d jtr(-rx, -ry, -rr);
    if (!(cost <= prevCost)) {
      c = prevC;
      r = prevR;
      break;
    }
    prevC = c;
    prevR = r;
    prevCost = cost;
    Eigen::Vector3d step = jtj.ldlt().solve(-jtr);
    if (!step.allFinite() || !(r + step[2] > 0.0)) break;
    c += step.head<2>();
    r += step[2];
    if (step.norm() <= 1e-6 * r) break;  // converged: the circle moved by < 1e-6 of its radius
  }
  if (!c.allFinite() || !std::isfinite(r)) return false;
  *centre = c;
  *radius = r;
  return true;
}

namespace {

void checkOptions(const CircleFitOptions& o) {
  auto bad = [](const std::string& what) { throw OptionsError("circle fit: " + what); };
  if (!(o.probability > 0.0 && o.probability < 1.0)) bad("probability must be in (0, 1)");
  if (!(o.inlierThreshold >= 0.0) || !std::isfinite(o.inlierThreshold)) bad("inlierThreshold must be >= 0");
  if (!(o.inlierThresholdRelative >= 0.0) || !std::isfinite(o.inlierThresholdRelative))
    bad("inlierThresholdRelative must be >= 0");
  if (o.inlierThreshold == 0.0 && o.inlierThresholdRelative == 0.0) bad("an inlier threshold must be positive");
  if (o.minInliers < 3) bad("minInliers must be >= 3");
  if (!(o.minInlierFraction >= 0.0 && o.minInlierFraction <= 1.0)) bad("minInlierFraction must be in [0, 1]");
  if (!(o.minRadius >= 0.0) || !(o.maxRadius > o.minRadius)) bad("radius bounds must satisfy 0 <= min < max");
  if (o.maxIterations < 1 || o.minIterations < 0) bad("iteration bounds must be positive");
  if (!(o.minArcDegrees >= 0.0 && o.minArcDegrees <= 360.0)) bad("minArcDegrees must be in [0, 360]");
  if (!(o.arcBinDegrees > 0.0 && o.arcBinDegrees <= 360.0)) bad("arcBinDegrees must be in (0, 360]");
  if (o.maxScoringPoints < 0 || o.maxRefinePoints < 0 || o.refineIterations < 0 || o.refineRounds < 0) bad("counts must be >= 0");
}

constexpr std::size_t kCoveragePoints = 256;

struct Scorer {
  const std::vector<Vec2>& pts;
  const CircleFitOptions& opt;
  double threshold(double r) const { return std::max(opt.inlierThreshold, opt.inlierThresholdRelative * r); }
  // |distance − r| <= t  ⇔  distance² in [max(0, r − t)², (r + t)²]: the band test without a
  // square root (NaN compares false: never an inlier).
  struct Band {
    double lo2, hi2;
    bool contains(double d2) const { return d2 >= lo2 && d2 <= hi2; }
  };
  Band band(double r) const {
    double t = threshold(r);
    double lo = std::max(0.0, r - t);
    return {r - t > 0.0 ? lo * lo : -1.0, (r + t) * (r + t)};
  }
  // Branch-free: the in/out pattern of noisy data defeats branch prediction.
  std::vector<std::uint32_t> inliers(std::size_t n, const Vec2& c, double r) const {
    const Band b = band(r);
    std::vector<std::uint32_t> out(n);
    std::size_t k = 0;
    for (std::size_t i = 0; i < n; ++i) {
      out[k] = std::uint32_t(i);
      k += b.contains((pts[i] - c).squaredNorm());
    }
    out.resize(k);
    return out;
  }
  // Angular coverage (degrees) of the points of `idx` within the threshold of the circle: the
  // bins holding at least a quarter of the fullest bin's count (so that a few scattered clutter
  // points do not count as arc).
  double coverage(const std::vector<std::uint32_t>& idx, const Vec2& c, double r) const {
    const int bins = std::max(1, int(std::ceil(360.0 / opt.arcBinDegrees)));
    constexpr int kStackBins = 128;
    int stackHit[kStackBins];
    std::vector<int> heapHit;
    int* hit = stackHit;
    if (bins > kStackBins) {
      heapHit.assign(std::size_t(bins), 0);
      hit = heapHit.data();
    } else {
      std::fill(stackHit, stackHit + bins, 0);
    }
    const Band b = band(r);
    const double perBin = 1.0 / opt.arcBinDegrees;
    // A strided subsample of at most kCoveragePoints points is plenty for 10° bins.
    const std::size_t stride = std::max<std::size_t>(1, (idx.size() + kCoveragePoints - 1) / kCoveragePoints);
    // Branch-free compaction of the subsample's band members, then their angles.
    Vec2 inBand[kCoveragePoints + 1];
    std::size_t m = 0;
    for (std::size_t k = 0; k < idx.size() && m < kCoveragePoints; k += stride) {
      const Vec2 d = pts[idx[k]] - c;
      inBand[m] = d;
      m += b.contains(d.squaredNorm()) ? 1 : 0;  // NaN is never in the band
    }
    for (std::size_t q = 0; q < m; ++q) {
      const double deg = fastAngleDeg(inBand[q].y(), inBand[q].x());
      ++hit[deg >= 0.0 && deg < 360.0 ? std::min(bins - 1, int(deg * perBin)) : 0];
    }
    const double floor = 0.25 * *std::max_element(hit, hit + bins);
    int covered = 0;
    for (int k = 0; k < bins; ++k) covered += hit[k] > 0 && hit[k] >= floor;
    return std::min(360.0, covered * opt.arcBinDegrees);
  }
  bool enoughArc(const std::vector<std::uint32_t>& idx, const Vec2& c, double r) const {
    return opt.minArcDegrees <= 0.0 || coverage(idx, c, r) >= opt.minArcDegrees;
  }
  bool admissible(const Vec2& c, double r) const {
    return r >= opt.minRadius && r <= opt.maxRadius;
  }
};

}  // namespace

CircleFitResult fitCircleRansac(const std::vector<Vec2>& points, const CircleFitOptions& options) {
  checkOptions(options);
  CircleFitResult res;
  const std::size_t n = points.size();
  std::vector<std::uint32_t> finite;
  finite.reserve(n);
  for (std::size_t i = 0; i < n; ++i)
    if (points[i].allFinite()) finite.push_back(std::uint32_t(i));
  if (finite.size() < 3) {
    res.reason = "fewer than 3 points (" + std::to_string(finite.size()) + ")";
    return res;
  }
  const std::size_t needed =
      std::max<std::size_t>(std::size_t(options.minInliers), std::size_t(std::ceil(options.minInlierFraction * n)));
  if (finite.size() < needed) {
    res.reason = "too few points for the minimum support (" + std::to_string(finite.size()) + " < " +
                 std::to_string(needed) + ")";
    return res;
  }

  std::mt19937_64 rng(options.seed);
  // The scoring subset: a deterministic random subset of the finite points.
  std::vector<std::uint32_t> sample = finite;
  if (options.maxScoringPoints > 0 && sample.size() > std::size_t(options.maxScoringPoints)) {
    std::size_t m = std::size_t(options.maxScoringPoints);
    for (std::size_t i = 0; i < m; ++i) {
      std::size_t j = i + std::size_t(rng() % (sample.size() - i));
      std::swap(sample[i], sample[j]);
    }
    sample.resize(m);
  }
  const std::size_t ns = sample.size();
  Scorer scorer{points, options};
  // The scoring subset's coordinates, contiguous (structure of arrays: the scoring loop below is
  // branch-free and vectorizes).
  std::vector<double> sampleX(ns), sampleY(ns);
  for (std::size_t k = 0; k < ns; ++k) {
    sampleX[k] = points[sample[k]].x();
    sampleY[k] = points[sample[k]].y();
  }
  // Inlier count and residual sum of a hypothesis over the subset. The residual |d − r| is taken
  // as |d² − r²| / 2r (first order; only a tie-break between equal counts), which keeps the loop
  // free of square roots and branches; four lanes let the compiler vectorize it.
  auto scoreSample = [&](const Vec2& centre, double r) {
    const auto b = scorer.band(r);
    const double cx = centre.x(), cy = centre.y(), r2 = r * r;
    double count[4] = {0, 0, 0, 0}, sum[4] = {0, 0, 0, 0};
    std::size_t k = 0;
    for (; k + 4 <= ns; k += 4)
      for (int j = 0; j < 4; ++j) {
        const double dx = sampleX[k + j] - cx, dy = sampleY[k + j] - cy;
        const double d2 = dx * dx + dy * dy;
        const double m = (d2 >= b.lo2 && d2 <= b.hi2) ? 1.0 : 0.0;
        count[j] += m;
        sum[j] += m * std::abs(d2 - r2);
      }
    for (; k < ns; ++k) {
      const double dx = sampleX[k] - cx, dy = sampleY[k] - cy;
      const double d2 = dx * dx + dy * dy;
      const double m = (d2 >= b.lo2 && d2 <= b.hi2) ? 1.0 : 0.0;
      count[0] += m;
      sum[0] += m * std::abs(d2 - r2);
    }
    const double total = (count[0] + count[1]) + (count[2] + count[3]);
    const double residual = ((sum[0] + sum[1]) + (sum[2] + sum[3])) / (2.0 * r);
    return std::pair<std::size_t, double>(std::size_t(total), residual);
  };

  std::size_t bestCount = 0;
  double bestSum = 0.0;
  Vec2 bestC = Vec2::Zero();
  double bestR = 0.0;
  double maxIter = options.maxIterations;
  int it = 0;
  const double logFail = std::log(1.0 - options.probability);
  while (it < options.maxIterations && (it < options.minIterations || it < maxIter)) {
    ++it;
    std::size_t a = rng() % ns, b = rng() % ns, c = rng() % ns;
    if (a == b || a == c || b == c) continue;
    Vec2 centre;
    double r;
    if (!circleFrom3(points[sample[a]], points[sample[b]], points[sample[c]], &centre, &r)) continue;
    if (!scorer.admissible(centre, r)) continue;
    auto [count, sum] = scoreSample(centre, r);
    if ((count > bestCount || (count == bestCount && count > 0 && sum < bestSum)) &&
        scorer.enoughArc(sample, centre, r)) {
      bestCount = count;
      bestSum = sum;
      bestC = centre;
      bestR = r;
      // Adaptive sample count N = log(1 − p) / log(1 − w³) from the best inlier ratio w.
      double w = double(count) / double(ns);
      double w3 = w * w * w;
      if (w3 >= 1.0)
        maxIter = 0;
      else if (w3 > 0.0)
        maxIter = std::min<double>(options.maxIterations, std::ceil(logFail / std::log1p(-w3)));
    }
  }
  res.iterations = it;
  if (bestCount < 3) {
    res.reason = "no admissible 3-point circle (collinear points, or outside the radius bounds or the minimum "
                 "arc)";
    return res;
  }

  // Refinement: classify on all points, least-squares fit, repeat.
  Vec2 c = bestC;
  double r = bestR;
  std::vector<std::uint32_t> inl = scorer.inliers(n, c, r);
  for (int round = 0; round < options.refineRounds; ++round) {
    Vec2 c2 = c;
    double r2 = r;
    const std::vector<std::uint32_t>* fitSet = &inl;
    std::vector<std::uint32_t> strided;
    if (options.maxRefinePoints > 0 && inl.size() > std::size_t(options.maxRefinePoints)) {
      const double step = double(inl.size()) / double(options.maxRefinePoints);
      for (int k = 0; k < options.maxRefinePoints; ++k) strided.push_back(inl[std::size_t(k * step)]);
      fitSet = &strided;
    }
    if (!fitCircleLeastSquares(points, *fitSet, options.refineIterations, &c2, &r2)) break;
    if (!scorer.admissible(c2, r2)) break;  // keep the last admissible circle
    auto inl2 = scorer.inliers(n, c2, r2);
    if (inl2.size() < 3) break;
    bool same = inl2 == inl;
    c = c2;
    r = r2;
    inl = std::move(inl2);
    if (same) break;
  }
  if (inl.size() < needed) {
    res.reason = "best circle has too few inliers (" + std::to_string(inl.size()) + " < " + std::to_string(needed) +
                 " of " + std::to_string(n) + ")";
    return res;
  }
  if (!options.centreRegion.contains(c)) {
    res.reason = "the best circle's centre lies outside the centre region";
    return res;
  }
  if (!scorer.enoughArc(inl, c, r)) {
    res.reason = "the inliers cover only " + std::to_string(int(scorer.coverage(inl, c, r))) + " degrees of the circle";
    return res;
  }
  double ss = 0.0;
  for (auto i : inl) {
    double e = (points[i] - c).norm() - r;
    ss += e * e;
  }
  res.ok = true;
  res.centre = c;
  res.radius = r;
  res.rms = std::sqrt(ss / double(inl.size()));
  res.inliers = std::move(inl);
  return res;
}

}  // namespace treesketch::fit
