// The float pre-test of CloudIndex's queries (see cloud_index.cpp): which of a block of stored
// points may lie inside a slice region, and which surely do, with SSE2 (and AVX2 where the
// processor has it). Private to src/fit/.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <limits>

#include "treesketch/fit/cloud_index.h"

#if defined(__SSE2__)
#include <emmintrin.h>
#endif
#if defined(__GNUC__) && (defined(__x86_64__) || defined(__i386__))
#include <immintrin.h>
#define TREESKETCH_AVX2_DISPATCH 1
#endif

namespace treesketch::fit {

// The float pre-test of forEachHit, on blocks of up to 64 consecutive stored points. A slab has
// no radial term (radialOff), a ball has a zero axis (no projection). Reads up to 3 floats past
// the block (fpos_ is padded); those lanes are masked off.
struct FloatTest {
  std::array<float, 3> n{}, l{}, a{};
  float pd = 0, hs = 0, hsIn = 0, r2 = 0, r2In = 0;
  bool radialOff = true;     ///< no radial test: the slab decides alone
  bool sureNoRadial = true;  ///< without a radial test, "inside the slab" is "surely inside"

  // Bit q of *in: point b0 + q may be inside (exact test needed unless bit q of *sure is set:
  // inside by more than the float tolerance).
  void block(const float* const f[3], std::uint32_t b0, std::uint32_t len, std::uint64_t* in,
             std::uint64_t* sure) const {
    std::uint64_t mi = 0, ms = 0;
#if defined(__SSE2__)
    const __m128 nx = _mm_set1_ps(n[0]), ny = _mm_set1_ps(n[1]), nz = _mm_set1_ps(n[2]);
    const __m128 lx = _mm_set1_ps(l[0]), ly = _mm_set1_ps(l[1]), lz = _mm_set1_ps(l[2]);
    const __m128 ax = _mm_set1_ps(a[0]), ay = _mm_set1_ps(a[1]), az = _mm_set1_ps(a[2]);
    const __m128 vpd = _mm_set1_ps(pd), vhs = _mm_set1_ps(hs), vhsIn = _mm_set1_ps(hsIn);
    const __m128 vr2 = _mm_set1_ps(r2), vr2In = _mm_set1_ps(r2In);
    const __m128 absMask = _mm_castsi128_ps(_mm_set1_epi32(0x7fffffff));
    const __m128 off = _mm_castsi128_ps(_mm_set1_epi32(radialOff ? -1 : 0));
    const __m128 sureOff = _mm_castsi128_ps(_mm_set1_epi32(sureNoRadial ? -1 : 0));
    for (std::uint32_t q = 0; q < len; q += 4) {
      const __m128 x = _mm_loadu_ps(f[0] + b0 + q), y = _mm_loadu_ps(f[1] + b0 + q), z = _mm_loadu_ps(f[2] + b0 + q);
      const __m128 ds = _mm_and_ps(
          absMask, _mm_sub_ps(_mm_add_ps(_mm_add_ps(_mm_mul_ps(nx, x), _mm_mul_ps(ny, y)), _mm_mul_ps(nz, z)), vpd));
      __m128 dx = _mm_sub_ps(x, lx), dy = _mm_sub_ps(y, ly), dz = _mm_sub_ps(z, lz);
      const __m128 t = _mm_add_ps(_mm_add_ps(_mm_mul_ps(dx, ax), _mm_mul_ps(dy, ay)), _mm_mul_ps(dz, az));
      dx = _mm_sub_ps(dx, _mm_mul_ps(t, ax));
      dy = _mm_sub_ps(dy, _mm_mul_ps(t, ay));
      dz = _mm_sub_ps(dz, _mm_mul_ps(t, az));
      const __m128 rq = _mm_add_ps(_mm_add_ps(_mm_mul_ps(dx, dx), _mm_mul_ps(dy, dy)), _mm_mul_ps(dz, dz));
      const __m128 inside = _mm_and_ps(_mm_cmplt_ps(ds, vhs), _mm_or_ps(_mm_cmplt_ps(rq, vr2), off));
      const __m128 surely = _mm_and_ps(_mm_cmplt_ps(ds, vhsIn), _mm_or_ps(_mm_cmplt_ps(rq, vr2In), sureOff));
      mi |= std::uint64_t(_mm_movemask_ps(inside)) << q;
      ms |= std::uint64_t(_mm_movemask_ps(surely)) << q;
    }
#else
    for (std::uint32_t q = 0; q < len; ++q) {
      const float x = f[0][b0 + q], y = f[1][b0 + q], z = f[2][b0 + q];
      const float ds = std::abs(n[0] * x + n[1] * y + n[2] * z - pd);
      float dx = x - l[0], dy = y - l[1], dz = z - l[2];
      const float t = dx * a[0] + dy * a[1] + dz * a[2];
      dx -= t * a[0];
      dy -= t * a[1];
      dz -= t * a[2];
      const float rq = dx * dx + dy * dy + dz * dz;
      mi |= std::uint64_t((ds < hs) & ((rq < r2) | radialOff)) << q;
      ms |= std::uint64_t((ds < hsIn) & ((rq < r2In) | sureNoRadial)) << q;
    }
#endif
    const std::uint64_t valid = len >= 64 ? ~std::uint64_t(0) : (std::uint64_t(1) << len) - 1;
    *in = mi & valid;
    *sure = ms & valid;
  }

#if defined(TREESKETCH_AVX2_DISPATCH)
  // block() eight points at a time, for processors with AVX2 (chosen at run time: the build
  // targets baseline x86-64). The same operations in the same order on each lane, and no fused
  // multiply-add (the target is "avx2" alone), so the masks are bit-identical to block()'s. Reads
  // up to 7 floats past the block: fpos_ is padded by 8.
  __attribute__((target("avx2"))) void block8(const float* const f[3], std::uint32_t b0, std::uint32_t len,
                                              std::uint64_t* in, std::uint64_t* sure) const {
    std::uint64_t mi = 0, ms = 0;
    const __m256 nx = _mm256_set1_ps(n[0]), ny = _mm256_set1_ps(n[1]), nz = _mm256_set1_ps(n[2]);
    const __m256 lx = _mm256_set1_ps(l[0]), ly = _mm256_set1_ps(l[1]), lz = _mm256_set1_ps(l[2]);
    const __m256 ax = _mm256_set1_ps(a[0]), ay = _mm256_set1_ps(a[1]), az = _mm256_set1_ps(a[2]);
    const __m256 vpd = _mm256_set1_ps(pd), vhs = _mm256_set1_ps(hs), vhsIn = _mm256_set1_ps(hsIn);
    const __m256 vr2 = _mm256_set1_ps(r2), vr2In = _mm256_set1_ps(r2In);
    const __m256 absMask = _mm256_castsi256_ps(_mm256_set1_epi32(0x7fffffff));
    const __m256 off = _mm256_castsi256_ps(_mm256_set1_epi32(radialOff ? -1 : 0));
    const __m256 sureOff = _mm256_castsi256_ps(_mm256_set1_epi32(sureNoRadial ? -1 : 0));
    for (std::uint32_t q = 0; q < len; q += 8) {
      const __m256 x = _mm256_loadu_ps(f[0] + b0 + q), y = _mm256_loadu_ps(f[1] + b0 + q),
                   z = _mm256_loadu_ps(f[2] + b0 + q);
      const __m256 ds = _mm256_and_ps(
          absMask,
          _mm256_sub_ps(_mm256_add_ps(_mm256_add_ps(_mm256_mul_ps(nx, x), _mm256_mul_ps(ny, y)), _mm256_mul_ps(nz, z)),
                        vpd));
      __m256 dx = _mm256_sub_ps(x, lx), dy = _mm256_sub_ps(y, ly), dz = _mm256_sub_ps(z, lz);
      const __m256 t =
          _mm256_add_ps(_mm256_add_ps(_mm256_mul_ps(dx, ax), _mm256_mul_ps(dy, ay)), _mm256_mul_ps(dz, az));
      dx = _mm256_sub_ps(dx, _mm256_mul_ps(t, ax));
      dy = _mm256_sub_ps(dy, _mm256_mul_ps(t, ay));
      dz = _mm256_sub_ps(dz, _mm256_mul_ps(t, az));
      const __m256 rq =
          _mm256_add_ps(_mm256_add_ps(_mm256_mul_ps(dx, dx), _mm256_mul_ps(dy, dy)), _mm256_mul_ps(dz, dz));
      const __m256 inside =
          _mm256_and_ps(_mm256_cmp_ps(ds, vhs, _CMP_LT_OQ), _mm256_or_ps(_mm256_cmp_ps(rq, vr2, _CMP_LT_OQ), off));
      const __m256 surely = _mm256_and_ps(_mm256_cmp_ps(ds, vhsIn, _CMP_LT_OQ),
                                          _mm256_or_ps(_mm256_cmp_ps(rq, vr2In, _CMP_LT_OQ), sureOff));
      mi |= std::uint64_t(unsigned(_mm256_movemask_ps(inside))) << q;
      ms |= std::uint64_t(unsigned(_mm256_movemask_ps(surely))) << q;
    }
    const std::uint64_t valid = len >= 64 ? ~std::uint64_t(0) : (std::uint64_t(1) << len) - 1;
    *in = mi & valid;
    *sure = ms & valid;
  }
#endif
};

// The float pre-test for `region`, in coordinates relative to the grid's centre (pp: the plane
// point, lp: the line point or ball centre, both relative; mag: half the grid's diagonal).
inline FloatTest floatTest(const SliceRegion& region, const geom::Vec3& pp, const geom::Vec3& lp, double mag,
                           bool radial) {
  const geom::Vec3& n = region.planeNormal;
  const double slabTol = 1e-5 * (mag + pp.norm()) + 1e-30;
  // Without a usable radial pre-test (radius too large for float) a cylinder or ball is never
  // "surely inside".
  FloatTest ft;
  ft.n = {float(n.x()), float(n.y()), float(n.z())};
  ft.pd = float(n.dot(pp));
  ft.hs = float(region.halfThickness + slabTol);
  ft.hsIn = float(std::max(0.0, region.halfThickness - slabTol));
  constexpr float kInf = std::numeric_limits<float>::infinity();
  ft.r2 = kInf;
  ft.r2In = -kInf;
  ft.radialOff = !radial;
  ft.sureNoRadial = !radial && region.kind == SliceRegion::Kind::Slab;
  if (radial) {
    const double rad = 1e-5 * (mag + lp.norm() + region.radius);
    const double rOut = region.radius + rad + 1e-30, rIn = std::max(0.0, region.radius - rad);
    ft.r2 = float(rOut * rOut);
    ft.r2In = float(rIn * rIn);
    ft.l = {float(lp.x()), float(lp.y()), float(lp.z())};
    if (region.kind == SliceRegion::Kind::Cylinder)
      ft.a = {float(region.lineDir.x()), float(region.lineDir.y()), float(region.lineDir.z())};
  }
  return ft;
}

}  // namespace treesketch::fit
