// Portable seeded random numbers for the procedural generator: std::mt19937_64 (whose output the
// C++ standard fixes) with distributions written here, because std:: distributions differ
// between standard libraries. Same seed -> same numbers on every platform and thread count.
#pragma once

#include <cstdint>
#include <random>

#include "treesketch/geom/types.h"

namespace treesketch::gen {

/// SplitMix64 finaliser (Steele, Lea, Flood 2014): mixes a 64-bit value into a well-spread one.
/// Used to derive independent seeds for sub-streams (one per branch) from one user seed.
std::uint64_t mixSeed(std::uint64_t x);

class Rng {
 public:
  explicit Rng(std::uint64_t seed) : engine_(seed) {}
  /// A sub-stream seeded from (seed, stream, salt): independent streams per branch, so changing
  /// one branch's number of draws does not change any other branch.
  static Rng substream(std::uint64_t seed, std::uint64_t stream, std::uint64_t salt);

  /// 64 raw bits from the engine.
  std::uint64_t bits() { return engine_(); }
  /// Uniform in [0, 1), 53 random bits.
  double uniform01() { return static_cast<double>(engine_() >> 11) * 0x1.0p-53; }
  /// Uniform in [a, b).
  double uniform(double a, double b) { return a + (b - a) * uniform01(); }
  /// Uniform integer in [0, n) (n > 0; returns 0 for n <= 0). Multiply-shift, bias < n / 2^64.
  std::int64_t uniformInt(std::int64_t n);
  /// Standard normal (mean 0, std dev 1) by the Box–Muller transform (one value per call).
  double normal();
  /// Normal with mean `mean` and standard deviation `sd`.
  double normal(double mean, double sd) { return mean + sd * normal(); }
  /// Uniformly distributed unit vector on the sphere.
  geom::Vec3 unitVector();

 private:
  std::mt19937_64 engine_;
};

}  // namespace treesketch::gen
