// Counter-based random numbers for the scanner: every ray's random numbers are a pure function of
// (seed, ray index, stream), so a scan gives the same cloud whatever the number of threads and
// whatever order the rays are cast in. No generator state is shared between rays.
#pragma once

#include <cmath>
#include <cstdint>
#include <numbers>

namespace treesketch::scan {

/// SplitMix64's finaliser (Steele, Lea & Flood 2014): a bijective 64-bit mix with good avalanche.
inline std::uint64_t mix64(std::uint64_t x) {
  x += 0x9E3779B97F4A7C15ull;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
  return x ^ (x >> 31);
}

/// A 64-bit hash of (seed, index, stream): independent-looking values for every combination.
inline std::uint64_t counterHash(std::uint64_t seed, std::uint64_t index, std::uint32_t stream) {
  return mix64(mix64(seed ^ (0x632BE59BD9B4E019ull * (stream + 1ull))) ^ index);
}

/// Uniform double in [0, 1) from (seed, index, stream): 53 random bits.
inline double counterUniform(std::uint64_t seed, std::uint64_t index, std::uint32_t stream) {
  return static_cast<double>(counterHash(seed, index, stream) >> 11) * 0x1.0p-53;
}

/// Standard normal N(0,1) from (seed, index, stream) and (seed, index, stream + 1) by the
/// Box-Muller transform. Uses two streams: callers should step their stream numbers by 2.
inline double counterGaussian(std::uint64_t seed, std::uint64_t index, std::uint32_t stream) {
  const double u1 = 1.0 - counterUniform(seed, index, stream);  // (0, 1]: log is finite
  const double u2 = counterUniform(seed, index, stream + 1);
  return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * std::numbers::pi * u2);
}

}  // namespace treesketch::scan
