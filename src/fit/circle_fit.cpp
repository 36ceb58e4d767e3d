// RANSAC circle fit (thesis §4.4, appendix B): sampling, scoring, arc coverage, and the
// refinement rounds around fitCircleLeastSquares (circle_least_squares.cpp).
#include "treesketch/fit/circle_fit.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numeric>

#include "treesketch/util/error.h"

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

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

// atan2 in degrees within ±0.3° (a rational approximation of atan on [0, 1]), in [0, 360).
double fastAngleDeg(double y, double x) {
  // (0, 0) gives 0. angleBins below does the same with bit-mask selects.
  const double ax = std::abs(x), ay = std::abs(y);
  const double mx = std::max(std::max(ax, ay), 1e-300);
  const double z = std::min(ax, ay) / mx;
  double a = z * (M_PI / 4 + 0.273 * (1.0 - z));  // atan(z), |error| < 0.004 rad
  a = ay > ax ? M_PI / 2 - a : a;
  a = x < 0 ? M_PI - a : a;
  a = y < 0 ? 2 * M_PI - a : a;
  return a * (180.0 / M_PI);
}

// The bin of each point's angle (fastAngleDeg · perBin, at most lastBin; 0 for an angle outside
// [0, 360)). The points' sign patterns are random, so the selects must not become branches: with
// SSE2 they are bit masks, two points at a time (the compiler keeps branches here, since the
// selected expressions could raise floating-point exceptions). Same operations, same results.
void angleBins(const double* bx, const double* by, std::size_t m, double perBin, int lastBin, int* bin) {
  std::size_t q = 0;
#if defined(__SSE2__)
  const __m128d sign = _mm_set1_pd(-0.0), zero = _mm_setzero_pd(), tiny = _mm_set1_pd(1e-300);
  const __m128d one = _mm_set1_pd(1.0), quarter = _mm_set1_pd(M_PI / 4), coef = _mm_set1_pd(0.273);
  const __m128d halfPi = _mm_set1_pd(M_PI / 2), pi = _mm_set1_pd(M_PI), twoPi = _mm_set1_pd(2 * M_PI);
  const __m128d toDeg = _mm_set1_pd(180.0 / M_PI), full = _mm_set1_pd(360.0);
  const __m128d vPerBin = _mm_set1_pd(perBin), vLast = _mm_set1_pd(double(lastBin));
  auto select = [](__m128d mask, __m128d a, __m128d b) { return _mm_or_pd(_mm_and_pd(mask, a), _mm_andnot_pd(mask, b)); };
  for (; q + 2 <= m; q += 2) {
    const __m128d x = _mm_loadu_pd(bx + q), y = _mm_loadu_pd(by + q);
    const __m128d ax = _mm_andnot_pd(sign, x), ay = _mm_andnot_pd(sign, y);
    const __m128d mx = _mm_max_pd(_mm_max_pd(ax, ay), tiny);
    const __m128d z = _mm_div_pd(_mm_min_pd(ax, ay), mx);
    __m128d a = _mm_mul_pd(z, _mm_add_pd(quarter, _mm_mul_pd(coef, _mm_sub_pd(one, z))));
    a = select(_mm_cmpgt_pd(ay, ax), _mm_sub_pd(halfPi, a), a);
    a = select(_mm_cmplt_pd(x, zero), _mm_sub_pd(pi, a), a);
    a = select(_mm_cmplt_pd(y, zero), _mm_sub_pd(twoPi, a), a);
    const __m128d deg = _mm_mul_pd(a, toDeg);
    const __m128d ok = _mm_and_pd(_mm_cmpge_pd(deg, zero), _mm_cmplt_pd(deg, full));
    // min(lastBin, deg · perBin) truncates like int(): both are non-negative when ok.
    const __m128d k = _mm_and_pd(ok, _mm_min_pd(_mm_mul_pd(deg, vPerBin), vLast));
    _mm_storel_epi64(reinterpret_cast<__m128i*>(bin + q), _mm_cvttpd_epi32(k));
  }
#endif
  for (; q < m; ++q) {
    const double deg = fastAngleDeg(by[q], bx[q]);
    bin[q] = deg >= 0.0 && deg < 360.0 ? std::min(lastBin, int(deg * perBin)) : 0;
  }
}

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

// The sampler's random numbers: SplitMix64 (a Weyl sequence through a 64-bit mixer). Design
// choice: a fit draws a few hundred numbers, and seeding a Mersenne Twister (312 words) per fit
// cost more than all of them; this generator's state is one word and its output passes the usual
// statistical batteries, which is far more than sample selection needs.
class SplitMix64 {
 public:
  explicit SplitMix64(std::uint64_t seed) : state_(seed) {}
  std::uint64_t next() {
    std::uint64_t z = (state_ += 0x9e3779b97f4a7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
  }
  /// Uniform in [0, n) by a multiply-shift (bias below n / 2^64: irrelevant here), no division.
  std::size_t below(std::size_t n) { return std::size_t((static_cast<unsigned __int128>(next()) * n) >> 64); }

 private:
  std::uint64_t state_;
};

struct Scorer {
  const std::vector<Vec2>& pts;
  const CircleFitOptions& opt;
  double threshold(double r) const { return std::max(opt.inlierThreshold, opt.inlierThresholdRelative * r); }
  // |distance − r| <= t  ⇔  distance² in [max(0, r − t)², (r + t)²]: the band test without a
  // square root (NaN compares false: never an inlier).
  struct Band {
    double lo2, hi2;
    bool contains(double d2) const { return (d2 >= lo2) & (d2 <= hi2); }  // no branch: unpredictable
  };
  Band band(double r) const {
    double t = threshold(r);
    double lo = std::max(0.0, r - t);
    return {r - t > 0.0 ? lo * lo : -1.0, (r + t) * (r + t)};
  }
  // Branch-free: the in/out pattern of noisy data defeats branch prediction. Two points at a time
  // with SSE2 (same arithmetic as the scalar test).
  // The indices of the points within the band of (c, r), into `out` (reused: a fit classifies all
  // points a few times, and fresh buffers of that size were a visible share of it).
  void inliers(std::size_t n, const Vec2& c, double r, std::vector<std::uint32_t>& out) const {
    const Band b = band(r);
    out.resize(n + 1);
    std::size_t k = 0, i = 0;
#if defined(__SSE2__)
    const __m128d vc = _mm_set_pd(c.y(), c.x()), lo = _mm_set1_pd(b.lo2), hi = _mm_set1_pd(b.hi2);
    for (; i + 2 <= n; i += 2) {
      const __m128d d0 = _mm_sub_pd(_mm_loadu_pd(pts[i].data()), vc);
      const __m128d d1 = _mm_sub_pd(_mm_loadu_pd(pts[i + 1].data()), vc);
      const __m128d s0 = _mm_mul_pd(d0, d0), s1 = _mm_mul_pd(d1, d1);
      const __m128d d2 = _mm_add_pd(_mm_unpacklo_pd(s0, s1), _mm_unpackhi_pd(s0, s1));
      const int in = _mm_movemask_pd(_mm_and_pd(_mm_cmpge_pd(d2, lo), _mm_cmple_pd(d2, hi)));
      out[k] = std::uint32_t(i);
      k += in & 1;
      out[k] = std::uint32_t(i + 1);
      k += in >> 1;
    }
#endif
    for (; i < n; ++i) {
      out[k] = std::uint32_t(i);
      k += b.contains((pts[i] - c).squaredNorm());
    }
    out.resize(k);
  }
  // Σ (|p − c| − r)² over the points of `idx`. Only reported (NodeResult::rms) and compared
  // with loose bounds, so the square roots are taken in float, four at a time (double square
  // roots were the bound of this pass, ~5 % of a node fit): the residual's error is ~1e-7 of the
  // radius, far below any scan noise. Squares and sums stay in double.
  double squaredResiduals(const std::vector<std::uint32_t>& idx, const Vec2& c, double r) const {
    double ss = 0.0;
    std::size_t k = 0;
#if defined(__SSE2__)
    const __m128d vc = _mm_set_pd(c.y(), c.x());
    const __m128 vr = _mm_set1_ps(float(r));
    __m128d acc0 = _mm_setzero_pd(), acc1 = _mm_setzero_pd();
    auto squares = [&](std::size_t q) {  // |p − c|² of points q and q + 1
      const __m128d d0 = _mm_sub_pd(_mm_loadu_pd(pts[idx[q]].data()), vc);
      const __m128d d1 = _mm_sub_pd(_mm_loadu_pd(pts[idx[q + 1]].data()), vc);
      const __m128d s0 = _mm_mul_pd(d0, d0), s1 = _mm_mul_pd(d1, d1);
      return _mm_add_pd(_mm_unpacklo_pd(s0, s1), _mm_unpackhi_pd(s0, s1));
    };
    for (; k + 4 <= idx.size(); k += 4) {
      const __m128 d2 = _mm_movelh_ps(_mm_cvtpd_ps(squares(k)), _mm_cvtpd_ps(squares(k + 2)));
      const __m128 e = _mm_sub_ps(_mm_sqrt_ps(d2), vr);
      const __m128d e0 = _mm_cvtps_pd(e), e1 = _mm_cvtps_pd(_mm_movehl_ps(e, e));
      acc0 = _mm_add_pd(acc0, _mm_mul_pd(e0, e0));
      acc1 = _mm_add_pd(acc1, _mm_mul_pd(e1, e1));
    }
    double lanes[2];
    _mm_storeu_pd(lanes, _mm_add_pd(acc0, acc1));
    ss = lanes[0] + lanes[1];
#endif
    for (; k < idx.size(); ++k) {
      const double e = (pts[idx[k]] - c).norm() - r;
      ss += e * e;
    }
    return ss;
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
    // Branch-free compaction of the subsample's band members (coordinates apart, so that the
    // angle loop below vectorizes), then their bins, then the histogram.
    double bx[kCoveragePoints + 1], by[kCoveragePoints + 1];
    std::size_t m = 0;
    for (std::size_t k = 0; k < idx.size() && m < kCoveragePoints; k += stride) {
      const Vec2 d = pts[idx[k]] - c;
      bx[m] = d.x();
      by[m] = d.y();
      m += b.contains(d.squaredNorm()) ? 1 : 0;  // NaN is never in the band
    }
    int bin[kCoveragePoints];
    angleBins(bx, by, m, perBin, bins - 1, bin);
    for (std::size_t q = 0; q < m; ++q) ++hit[bin[q]];
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

// True when every point is finite: in the common case one vectorizable test (x·0 + y·0 is NaN
// exactly when x or y is NaN or infinite).
bool allPointsFinite(const std::vector<Vec2>& points) {
  const std::size_t n = points.size();
  bool allFinite = true;
  std::size_t i = 0;
#if defined(__SSE2__)
  // Sums of p · 0 stay 0 unless some coordinate is NaN or infinite; four independent sums.
  const __m128d zero = _mm_setzero_pd();
  __m128d acc[4] = {zero, zero, zero, zero};
  for (; i + 4 <= n; i += 4)
    for (int q = 0; q < 4; ++q) acc[q] = _mm_add_pd(acc[q], _mm_mul_pd(_mm_loadu_pd(points[i + q].data()), zero));
  const __m128d all = _mm_add_pd(_mm_add_pd(acc[0], acc[1]), _mm_add_pd(acc[2], acc[3]));
  allFinite = _mm_movemask_pd(_mm_cmpeq_pd(all, all)) == 3;
#endif
  for (; i < n; ++i) allFinite &= points[i].allFinite();
  return allFinite;
}

// The indices of the finite points, into `finite`; returns their number.
std::size_t compactFinite(const std::vector<Vec2>& points, std::vector<std::uint32_t>& finite) {
  const std::size_t n = points.size();
  finite.resize(n);
  std::size_t nFinite = 0;
  for (std::size_t i = 0; i < n; ++i) {  // branch-free compaction
    finite[nFinite] = std::uint32_t(i);
    nFinite += points[i].allFinite() ? 1 : 0;
  }
  finite.resize(nFinite);
  return nFinite;
}

// The scoring subset, into `sample`: a deterministic random subset of m of the finite points (all
// of them when there are few).
void drawScoringSubset(SplitMix64& rng, std::size_t n, std::size_t nFinite, std::size_t m, bool allFinite,
                       const std::vector<std::uint32_t>& finite, std::vector<std::uint32_t>& sample,
                       std::vector<std::uint64_t>& taken) {
  if (nFinite <= m) {
    if (allFinite) {
      sample.resize(n);
      std::iota(sample.begin(), sample.end(), 0u);
    } else {
      sample = finite;
    }
  } else if (allFinite) {
    // Floyd's sampling of m of the n indices: m draws and a bit set, no array of all n.
    taken.assign((n + 63) / 64, 0);
    sample.clear();
    for (std::size_t j = n - m; j < n; ++j) {
      std::size_t t = rng.below(j + 1);
      if ((taken[t >> 6] >> (t & 63)) & 1) t = j;
      taken[t >> 6] |= std::uint64_t(1) << (t & 63);
      sample.push_back(std::uint32_t(t));
    }
  } else {
    sample = finite;  // partial Fisher–Yates
    for (std::size_t i = 0; i < m; ++i) {
      std::size_t j = i + rng.below(sample.size() - i);
      std::swap(sample[i], sample[j]);
    }
    sample.resize(m);
  }
}

// The scoring subset's coordinates, contiguous (structure of arrays) and in float: scoring only
// ranks hypotheses (the final inliers are classified in double), and float's relative error of
// ~1e-7 on plane coordinates is far below any inlier threshold; four points per SSE2 step.
struct SampleScorer {
  const Scorer& scorer;
  const std::vector<float>& sampleX;
  const std::vector<float>& sampleY;
  std::size_t ns;

  // Inlier count and residual sum of a hypothesis over the subset. The residual |d − r| is taken
  // as |d² − r²| / 2r (first order; only a tie-break between equal counts), which keeps the loop
  // free of square roots and branches.
  std::pair<std::size_t, double> operator()(const Vec2& centre, double r) const {
    const auto b = scorer.band(r);
    const float cx = float(centre.x()), cy = float(centre.y()), r2 = float(r * r);
    const float lo2 = float(b.lo2), hi2 = float(b.hi2);
    const float* xs = sampleX.data();
    const float* ys = sampleY.data();
    std::size_t count = 0;
    float sum = 0.0f;
    std::size_t k = 0;
#if defined(__SSE2__)
    const __m128 vcx = _mm_set1_ps(cx), vcy = _mm_set1_ps(cy), vr2 = _mm_set1_ps(r2);
    const __m128 vlo = _mm_set1_ps(lo2), vhi = _mm_set1_ps(hi2);
    const __m128 absMask = _mm_castsi128_ps(_mm_set1_epi32(0x7fffffff));
    __m128i vcount = _mm_setzero_si128();
    __m128 vsum = _mm_setzero_ps();
    for (; k + 4 <= ns; k += 4) {
      const __m128 dx = _mm_sub_ps(_mm_loadu_ps(xs + k), vcx), dy = _mm_sub_ps(_mm_loadu_ps(ys + k), vcy);
      const __m128 d2 = _mm_add_ps(_mm_mul_ps(dx, dx), _mm_mul_ps(dy, dy));
      const __m128 in = _mm_and_ps(_mm_cmpge_ps(d2, vlo), _mm_cmple_ps(d2, vhi));
      vcount = _mm_sub_epi32(vcount, _mm_castps_si128(in));  // a true lane is -1
      vsum = _mm_add_ps(vsum, _mm_and_ps(in, _mm_and_ps(absMask, _mm_sub_ps(d2, vr2))));
    }
    alignas(16) std::int32_t c4[4];
    alignas(16) float s4[4];
    _mm_store_si128(reinterpret_cast<__m128i*>(c4), vcount);
    _mm_store_ps(s4, vsum);
    count = std::size_t(c4[0]) + std::size_t(c4[1]) + std::size_t(c4[2]) + std::size_t(c4[3]);
    sum = (s4[0] + s4[1]) + (s4[2] + s4[3]);
#endif
    for (; k < ns; ++k) {
      const float dx = xs[k] - cx, dy = ys[k] - cy;
      const float d2 = dx * dx + dy * dy;
      const bool in = d2 >= lo2 && d2 <= hi2;
      count += in;
      sum += in ? std::abs(d2 - r2) : 0.0f;
    }
    return std::pair<std::size_t, double>(count, double(sum) / (2.0 * r));
  }
};

struct BestCircle {
  std::size_t count = 0;
  double sum = 0.0;
  Vec2 centre = Vec2::Zero();
  double radius = 0.0;
};

// RANSAC over 3-point circles of the scoring subset, with the adaptive sample count; returns the
// best circle and sets `iterations`.
BestCircle searchCircles(SplitMix64& rng, const std::vector<Vec2>& points, const std::vector<std::uint32_t>& sample,
                         const Scorer& scorer, const SampleScorer& scoreSample, const CircleFitOptions& options,
                         int& iterations) {
  const std::size_t ns = sample.size();
  BestCircle best;
  double maxIter = options.maxIterations;
  int it = 0;
  const double logFail = std::log(1.0 - options.probability);
  while (it < options.maxIterations && (it < options.minIterations || it < maxIter)) {
    ++it;
    std::size_t a = rng.below(ns), b = rng.below(ns), c = rng.below(ns);
    if (a == b || a == c || b == c) continue;
    Vec2 centre;
    double r;
    if (!circleFrom3(points[sample[a]], points[sample[b]], points[sample[c]], &centre, &r)) continue;
    if (!scorer.admissible(centre, r)) continue;
    auto [count, sum] = scoreSample(centre, r);
    if ((count > best.count || (count == best.count && count > 0 && sum < best.sum)) &&
        scorer.enoughArc(sample, centre, r)) {
      best.count = count;
      best.sum = sum;
      best.centre = centre;
      best.radius = r;
      // Adaptive sample count N = log(1 − p) / log(1 − w³) from the best inlier ratio w.
      double w = double(count) / double(ns);
      double w3 = w * w * w;
      if (w3 >= 1.0)
        maxIter = 0;
      else if (w3 > 0.0)
        maxIter = std::min<double>(options.maxIterations, std::ceil(logFail / std::log1p(-w3)));
    }
  }
  iterations = it;
  return best;
}

// Refinement: least-squares fit to the inliers, classify all points, repeat. The first fit takes
// the best circle's inliers within the scoring subset (a random sample of the points already at
// hand) rather than classifying all points first: one pass over them less. On return `inl` holds
// the inliers of (c, r) among all points.
void refineCircle(const std::vector<Vec2>& points, const std::vector<std::uint32_t>& sample, const Scorer& scorer,
                  const CircleFitOptions& options, Vec2& c, double& r, std::vector<std::uint32_t>& inl,
                  std::vector<std::uint32_t>& inl2, std::vector<std::uint32_t>& strided) {
  const std::size_t n = points.size();
  bool full = sample.size() == n;  // inl holds the inliers among all points (not only the subset's)
  if (full) {
    scorer.inliers(n, c, r, inl);
  } else {
    const auto b = scorer.band(r);
    inl.clear();
    for (std::uint32_t i : sample)
      if (b.contains((points[i] - c).squaredNorm())) inl.push_back(i);
  }
  for (int round = 0; round < options.refineRounds; ++round) {
    Vec2 c2 = c;
    double r2 = r;
    const std::vector<std::uint32_t>* fitSet = &inl;
    const std::size_t maxRefine = std::size_t(options.maxRefinePoints);
    if (maxRefine > 0 && inl.size() > maxRefine) {
      // Evenly strided: element ⌊k · size / maxRefine⌋, in integers.
      strided.resize(maxRefine);
      for (std::size_t k = 0; k < maxRefine; ++k) strided[k] = inl[k * inl.size() / maxRefine];
      fitSet = &strided;
    }
    if (!fitCircleLeastSquares(points, *fitSet, options.refineIterations, &c2, &r2, round > 0)) break;
    if (!scorer.admissible(c2, r2)) break;  // keep the last admissible circle
    scorer.inliers(n, c2, r2, inl2);
    if (inl2.size() < 3) break;
    const bool same = full && inl2 == inl;
    c = c2;
    r = r2;
    inl.swap(inl2);
    full = true;
    if (same) break;
  }
  if (!full) scorer.inliers(n, c, r, inl);
}

}  // namespace

CircleFitResult fitCircleRansac(const std::vector<Vec2>& points, const CircleFitOptions& options) {
  checkOptions(options);
  CircleFitResult res;
  const std::size_t n = points.size();
  // Per-thread index buffers, reused by every fit on the thread.
  thread_local std::vector<std::uint32_t> finite, sample, strided, inl, inl2;
  thread_local std::vector<std::uint64_t> taken;
  struct Release {  // ...but not the memory of a huge input
    ~Release() {
      for (auto* v : {&finite, &sample, &strided, &inl, &inl2})
        if (v->capacity() > (std::size_t(1) << 20)) *v = {};
      if (taken.capacity() > (std::size_t(1) << 16)) taken = {};
    }
  } release;
  // The finite points: in the common case all of them, else a compacted list.
  const bool allFinite = options.inputFinite || allPointsFinite(points);
  const std::size_t nFinite = allFinite ? n : compactFinite(points, finite);
  if (nFinite < 3) {
    res.reason = "fewer than 3 points (" + std::to_string(nFinite) + ")";
    return res;
  }
  const std::size_t needed =
      std::max<std::size_t>(std::size_t(options.minInliers), std::size_t(std::ceil(options.minInlierFraction * n)));
  if (nFinite < needed) {
    res.reason =
        "too few points for the minimum support (" + std::to_string(nFinite) + " < " + std::to_string(needed) + ")";
    return res;
  }

  SplitMix64 rng(options.seed);
  const std::size_t m = options.maxScoringPoints > 0 ? std::size_t(options.maxScoringPoints) : nFinite;
  drawScoringSubset(rng, n, nFinite, m, allFinite, finite, sample, taken);
  const std::size_t ns = sample.size();
  Scorer scorer{points, options};
  thread_local std::vector<float> sampleX, sampleY;
  sampleX.resize(ns);
  sampleY.resize(ns);
  for (std::size_t k = 0; k < ns; ++k) {
    sampleX[k] = float(points[sample[k]].x());
    sampleY[k] = float(points[sample[k]].y());
  }
  const SampleScorer scoreSample{scorer, sampleX, sampleY, ns};
  const BestCircle best = searchCircles(rng, points, sample, scorer, scoreSample, options, res.iterations);
  if (best.count < 3) {
    res.reason =
        "no admissible 3-point circle (collinear points, or outside the radius bounds or the minimum "
        "arc)";
    return res;
  }
  Vec2 c = best.centre;
  double r = best.radius;
  refineCircle(points, sample, scorer, options, c, r, inl, inl2, strided);
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
  const double ss = scorer.squaredResiduals(inl, c, r);
  res.ok = true;
  res.centre = c;
  res.radius = r;
  res.rms = std::sqrt(ss / double(inl.size()));
  res.inliers.assign(inl.begin(), inl.end());
  return res;
}

}  // namespace treesketch::fit
