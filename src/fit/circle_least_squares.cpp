// Least-squares circle fit (the refinement of the RANSAC fit in circle_fit.cpp, and usable on its
// own): an algebraic (Kåsa) start, then Gauss–Newton on the geometric residuals. The per-point
// sums run two points at a time with SSE2.
#include <Eigen/Dense>
#include <array>
#include <cmath>
#include <limits>
#include <vector>

#include "treesketch/fit/circle_fit.h"

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace treesketch::fit {

using geom::Vec2;

namespace {

// The sums over m points (xs, ys) of N per-point terms, two points at a time with SSE2 (the
// compiler does not vectorize floating-point reductions): terms(x, y, out) writes the N terms of
// the points (x, y), x and y being __m128d pairs under SSE2 (the odd last point in lane 0) and
// doubles otherwise.
template <int N, class Terms>
std::array<double, N> pairSums(const double* xs, const double* ys, std::size_t m, Terms&& terms) {
  std::array<double, N> sum{};
  std::size_t k = 0;
#if defined(__SSE2__)
  __m128d acc[N], t[N];
  for (auto& a : acc) a = _mm_setzero_pd();
  for (; k + 2 <= m; k += 2) {
    terms(_mm_loadu_pd(xs + k), _mm_loadu_pd(ys + k), t);
    for (int j = 0; j < N; ++j) acc[j] = _mm_add_pd(acc[j], t[j]);
  }
  for (int j = 0; j < N; ++j) {
    double lanes[2];
    _mm_storeu_pd(lanes, acc[j]);
    sum[j] = lanes[0] + lanes[1];
  }
  for (; k < m; ++k) {
    double lanes[N][2];
    terms(_mm_set_sd(xs[k]), _mm_set_sd(ys[k]), t);
    for (int j = 0; j < N; ++j) {
      _mm_storeu_pd(lanes[j], t[j]);
      sum[j] += lanes[j][0];
    }
  }
#else
  for (; k < m; ++k) {
    double t[N];
    terms(xs[k], ys[k], t);
    for (int j = 0; j < N; ++j) sum[j] += t[j];
  }
#endif
  return sum;
}

// Algebraic (Kåsa) circle through the m points (xs, ys).
bool kasaFit(const double* xs, const double* ys, std::size_t m, Vec2* centre, double* radius) {
  const auto total = pairSums<2>(xs, ys, m, [](auto x, auto y, auto* t) {
    t[0] = x;
    t[1] = y;
  });
  const Vec2 mean = Vec2(total[0], total[1]) / double(m);
  // Minimize Σ (x² + y² + D x + E y + F)² in coordinates relative to the mean.
#if defined(__SSE2__)
  const __m128d mx = _mm_set1_pd(mean.x()), my = _mm_set1_pd(mean.y());
  const auto sums = pairSums<8>(xs, ys, m, [&](__m128d px, __m128d py, __m128d* t) {
    const __m128d x = _mm_sub_pd(px, mx), y = _mm_sub_pd(py, my);
    const __m128d rhs = _mm_sub_pd(_mm_setzero_pd(), _mm_add_pd(_mm_mul_pd(x, x), _mm_mul_pd(y, y)));
    t[0] = _mm_mul_pd(x, x);
    t[1] = _mm_mul_pd(x, y);
    t[2] = _mm_mul_pd(y, y);
    t[3] = x;
    t[4] = y;
    t[5] = _mm_mul_pd(x, rhs);
    t[6] = _mm_mul_pd(y, rhs);
    t[7] = rhs;
  });
#else
  const auto sums = pairSums<8>(xs, ys, m, [&](double px, double py, double* t) {
    const double x = px - mean.x(), y = py - mean.y();
    const double rhs = -(x * x + y * y);
    const double terms[8] = {x * x, x * y, y * y, x, y, x * rhs, y * rhs, rhs};
    std::copy(terms, terms + 8, t);
  });
#endif
  const double sxx = sums[0], sxy = sums[1], syy = sums[2], sx = sums[3], sy = sums[4], bx = sums[5], by = sums[6],
               b1 = sums[7];
  Eigen::Matrix3d ata;
  ata << sxx, sxy, sx, sxy, syy, sy, sx, sy, double(m);
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

// Σ over the points of a Gauss–Newton pass (see fitCircleLeastSquares): ux², ux·uy, uy², ux, uy,
// count, ux·res, uy·res, res, res², with (ux, uy) the unit direction from the centre and res the
// residual. A point at the centre (no direction) is left out.
std::array<double, 10> gaussNewtonSums(const double* xs, const double* ys, std::size_t m, double cx, double cy,
                                       double r) {
#if defined(__SSE2__)
  const __m128d vcx = _mm_set1_pd(cx), vcy = _mm_set1_pd(cy), vr = _mm_set1_pd(r), one = _mm_set1_pd(1.0);
  const __m128d zero = _mm_setzero_pd();
  return pairSums<10>(xs, ys, m, [&](__m128d px, __m128d py, __m128d* t) {
    const __m128d dx = _mm_sub_pd(px, vcx), dy = _mm_sub_pd(py, vcy);
    const __m128d n = _mm_sqrt_pd(_mm_add_pd(_mm_mul_pd(dx, dx), _mm_mul_pd(dy, dy)));
    const __m128d valid = _mm_cmpgt_pd(n, zero);
    // Invalid lanes divide by 1 and are then zeroed.
    const __m128d nn = _mm_or_pd(_mm_and_pd(valid, n), _mm_andnot_pd(valid, one));
    const __m128d inv = _mm_div_pd(one, nn);  // one division for both components
    const __m128d ux = _mm_and_pd(valid, _mm_mul_pd(dx, inv)), uy = _mm_and_pd(valid, _mm_mul_pd(dy, inv));
    const __m128d res = _mm_and_pd(valid, _mm_sub_pd(n, vr));
    t[0] = _mm_mul_pd(ux, ux);
    t[1] = _mm_mul_pd(ux, uy);
    t[2] = _mm_mul_pd(uy, uy);
    t[3] = ux;
    t[4] = uy;
    t[5] = _mm_and_pd(valid, one);
    t[6] = _mm_mul_pd(ux, res);
    t[7] = _mm_mul_pd(uy, res);
    t[8] = res;
    t[9] = _mm_mul_pd(res, res);
  });
#else
  return pairSums<10>(xs, ys, m, [&](double px, double py, double* t) {
    const double dx = px - cx, dy = py - cy;
    const double n = std::sqrt(dx * dx + dy * dy);
    const double w = n > 0.0 ? 1.0 : 0.0;
    const double inv = n > 0.0 ? 1.0 / n : 0.0;
    const double ux = dx * inv, uy = dy * inv, res = w * (n - r);
    const double terms[10] = {ux * ux, ux * uy, uy * uy, ux, uy, w, ux * res, uy * res, res, res * res};
    std::copy(terms, terms + 10, t);
  });
#endif
}

}  // namespace

bool fitCircleLeastSquares(const std::vector<Vec2>& pts, const std::vector<std::uint32_t>& idx, int iterations,
                           Vec2* centre, double* radius, bool warmStart) {
  if (idx.size() < 3) return false;
  // The points, gathered once and coordinates apart, so that every pass below streams them two at
  // a time.
  thread_local std::vector<double> xs, ys;
  xs.resize(idx.size());
  ys.resize(idx.size());
  for (std::size_t k = 0; k < idx.size(); ++k) {
    xs[k] = pts[idx[k]].x();
    ys[k] = pts[idx[k]].y();
  }
  Vec2 c;
  double r;
  const bool fromGiven = warmStart && *radius > 0.0 && std::isfinite(*radius) && centre->allFinite();
  if (fromGiven) {
    c = *centre;
    r = *radius;
  } else if (!kasaFit(xs.data(), ys.data(), idx.size(), &c, &r)) {
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
    const auto g = gaussNewtonSums(xs.data(), ys.data(), idx.size(), c.x(), c.y(), r);
    const double sxx = g[0], sxy = g[1], syy = g[2], sx = g[3], sy = g[4], cnt = g[5], rx = g[6], ry = g[7], rr = g[8],
                 cost = g[9];
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

}  // namespace treesketch::fit
