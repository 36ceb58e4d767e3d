// Parallel, deterministic casting of a ray pattern: see include/treesketch/scan/pattern_cast.h.
// Rays are cut into fixed-size chunks (independent of the thread count); each chunk collects its
// hits in ray order, and the chunks are joined in order.
#include "treesketch/scan/pattern_cast.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <atomic>
#include <cmath>
#include <numbers>

#include "treesketch/scan/counter_rng.h"
#include "treesketch/util/error.h"
#include "treesketch/util/stopwatch.h"

namespace treesketch::scan {

namespace {

// Rays per chunk: a unit of work and of progress reports; results do not depend on it.
constexpr std::uint64_t kRaysPerChunk = 4096;
// counterGaussian streams used for range noise (sphere jitter uses streams 16 and up).
constexpr std::uint32_t kNoiseStream = 8;
// counterUniform stream of the beam footprint's ring phase.
constexpr std::uint32_t kBeamStream = 10;

struct ChunkOut {
  std::vector<geom::Vec3> positions;
  std::vector<std::int32_t> meshId;
  std::vector<std::int32_t> station;
  std::vector<geom::Vec3> scanner;
  std::vector<std::uint64_t> hitsPerMesh;
  std::uint64_t mixed = 0, partial = 0, weak = 0;
};

// Casts rays [first, last) into `out`, in ray order.
void castChunk(const accel::RayScene& scene, const RayBatchGenerator& generator, const CastOptions& options,
               double sigma, std::uint64_t first, std::uint64_t last, ChunkOut& out) {
  const bool footprint = options.beam.enabled;
  out.hitsPerMesh.assign(scene.meshCount(), 0);
  ScanRay batch[kRayBatch];
  for (std::uint64_t b = first; b < last; b += kRayBatch) {
    const auto count = static_cast<std::size_t>(std::min<std::uint64_t>(kRayBatch, last - b));
    generator(b, count, batch);
    for (std::size_t k = 0; k < count; ++k) {
      const ScanRay& sr = batch[k];
      geom::Vec3 p;
      std::int32_t mesh = -1;
      if (footprint) {
        const double phase = 2.0 * std::numbers::pi * counterUniform(options.seed, b + k, kBeamStream);
        const BeamReturn beam = castBeam(scene, sr.ray, options.beam, options.unitMetres, phase);
        out.weak += beam.weak;
        if (!beam.hit) continue;
        out.mixed += beam.mixed;
        out.partial += beam.partial;
        p = beam.point;
        mesh = beam.meshIndex;
      } else {
        const accel::RayHit hit = scene.intersect(sr.ray);
        if (!hit.hit()) continue;
        p = hit.point;
        mesh = hit.meshIndex;
      }
      if (sigma > 0.0) p += (sigma * counterGaussian(options.seed, b + k, kNoiseStream)) * sr.ray.dir.normalized();
      out.positions.push_back(p);
      ++out.hitsPerMesh[static_cast<std::size_t>(mesh)];
      if (options.recordMesh) out.meshId.push_back(mesh);
      if (options.recordStation) out.station.push_back(sr.station);
      if (options.recordScanner) out.scanner.push_back(sr.ray.origin);
    }
  }
}

// Joins the chunks in order into result (freeing each chunk's memory as it goes).
void joinChunks(std::vector<ChunkOut>& chunks, const CastOptions& options, ScanResult& result) {
  std::size_t total = 0;
  for (const ChunkOut& c : chunks) total += c.positions.size();
  geom::PointCloud& cloud = result.cloud;
  cloud.positions.reserve(total);
  if (options.recordMesh) cloud.meshId.reserve(total);
  if (options.recordStation) cloud.station.reserve(total);
  if (options.recordScanner) cloud.scanner.reserve(total);
  std::vector<std::uint64_t>& perMesh = result.stats.hitsPerMesh;
  for (ChunkOut& c : chunks) {
    cloud.positions.insert(cloud.positions.end(), c.positions.begin(), c.positions.end());
    cloud.meshId.insert(cloud.meshId.end(), c.meshId.begin(), c.meshId.end());
    cloud.station.insert(cloud.station.end(), c.station.begin(), c.station.end());
    cloud.scanner.insert(cloud.scanner.end(), c.scanner.begin(), c.scanner.end());
    result.stats.mixed += c.mixed;
    result.stats.partial += c.partial;
    result.stats.weak += c.weak;
    for (std::size_t m = 0; m < perMesh.size(); ++m) perMesh[m] += c.hitsPerMesh[m];
    ChunkOut().positions.swap(c.positions);  // free as we go
    ChunkOut().scanner.swap(c.scanner);
  }
  result.stats.hits = total;
}

}  // namespace

ScanResult castPattern(const accel::RayScene& scene, std::uint64_t rayCount, const RayGenerator& generator,
                       const CastOptions& options, const ProgressFn& progress) {
  const RayBatchGenerator batch = [&generator](std::uint64_t first, std::size_t count, ScanRay* out) {
    for (std::size_t k = 0; k < count; ++k) out[k] = generator(first + k);
  };
  return castPattern(scene, rayCount, batch, options, progress);
}

ScanResult castPattern(const accel::RayScene& scene, std::uint64_t rayCount, const RayBatchGenerator& generator,
                       const CastOptions& options, const ProgressFn& progress) {
  if (!(options.rangeNoise >= 0.0) || !std::isfinite(options.rangeNoise))
    throw OptionsError("scan: range noise must be a finite number >= 0, got " + std::to_string(options.rangeNoise));
  if (!(options.unitMetres > 0.0) || !std::isfinite(options.unitMetres))
    throw OptionsError("scan: the scene unit must be a finite number of metres > 0, got " +
                       std::to_string(options.unitMetres));
  checkBeamFootprint(options.beam);
  const Stopwatch timer;
  ScanResult result;
  result.stats.raysCast = rayCount;
  result.stats.hitsPerMesh.assign(scene.meshCount(), 0);
  if (rayCount == 0) return result;

  const std::uint64_t chunkCount = (rayCount + kRaysPerChunk - 1) / kRaysPerChunk;
  std::vector<ChunkOut> chunks(chunkCount);
  std::atomic<std::uint64_t> done{0};
  const double sigma = options.rangeNoise / options.unitMetres;  // scene units

  tbb::parallel_for(tbb::blocked_range<std::uint64_t>(0, chunkCount, 1),
                    [&](const tbb::blocked_range<std::uint64_t>& r) {
                      for (std::uint64_t c = r.begin(); c != r.end(); ++c) {
                        const std::uint64_t first = c * kRaysPerChunk;
                        const std::uint64_t last = std::min(rayCount, first + kRaysPerChunk);
                        castChunk(scene, generator, options, sigma, first, last, chunks[c]);
                        if (progress) progress(done.fetch_add(last - first) + (last - first), rayCount);
                      }
                    });

  joinChunks(chunks, options, result);
  result.stats.milliseconds = timer.ms();
  return result;
}

}  // namespace treesketch::scan
