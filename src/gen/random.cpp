#include "treesketch/gen/random.h"

#include <cmath>
#include <numbers>

namespace treesketch::gen {

std::uint64_t mixSeed(std::uint64_t x) {
  x += 0x9E3779B97F4A7C15ull;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
  return x ^ (x >> 31);
}

Rng Rng::substream(std::uint64_t seed, std::uint64_t stream, std::uint64_t salt) {
  return Rng(mixSeed(mixSeed(mixSeed(seed) ^ stream) ^ (salt * 0xD1B54A32D192ED03ull)));
}

std::int64_t Rng::uniformInt(std::int64_t n) {
  if (n <= 0) return 0;
  unsigned __int128 product = static_cast<unsigned __int128>(engine_()) * static_cast<std::uint64_t>(n);
  return static_cast<std::int64_t>(product >> 64);
}

double Rng::normal() {
  // u1 in (0, 1] so that log(u1) is finite.
  double u1 = 1.0 - uniform01();
  double u2 = uniform01();
  return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * std::numbers::pi * u2);
}

geom::Vec3 Rng::unitVector() {
  // Archimedes: z uniform in [-1, 1], azimuth uniform.
  double z = uniform(-1.0, 1.0);
  double phi = uniform(0.0, 2.0 * std::numbers::pi);
  double s = std::sqrt(std::max(0.0, 1.0 - z * z));
  return geom::Vec3(s * std::cos(phi), s * std::sin(phi), z);
}

}  // namespace treesketch::gen
