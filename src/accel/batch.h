// Internal: the batch driver shared by the closest-point indexes (mesh BVH, point cloud).
#pragma once

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/partitioner.h>

#include <algorithm>
#include <atomic>
#include <limits>
#include <numeric>
#include <string>
#include <vector>

#include "treesketch/accel/closest_point.h"
#include "treesketch/util/error.h"

namespace treesketch::accel::detail {

// Runs `answerOne(queryIndex, warmState)` over all queries, Morton-ordered, in parallel blocks.
// Throws OptionsError for more queries than 32-bit indices hold.
template <class AnswerFn>
void runBatch(const std::vector<geom::Vec3>& points, const ClosestPointOptions& options, const ProgressFn& progress,
              AnswerFn&& answerOne) {
  const std::size_t n = points.size();
  if (n >= std::numeric_limits<std::uint32_t>::max())
    throw OptionsError("closest point: too many queries (" + std::to_string(n) + ")");
  std::vector<std::uint32_t> order;
  if (options.mortonOrder) {
    order = mortonOrder(points);
  } else {
    order.resize(n);
    std::iota(order.begin(), order.end(), 0u);
  }
  std::atomic<std::uint64_t> done{0};
  const std::size_t block = static_cast<std::size_t>(std::max(1, options.blockSize));
  // simple_partitioner splits the range the same way on every run, so the warm starts, hence the
  // tie-breaks between equally close triangles, hence the results are reproducible bit for bit.
  tbb::parallel_for(
      tbb::blocked_range<std::size_t>(0, n, block),
      [&](const tbb::blocked_range<std::size_t>& r) {
        std::int64_t warm = -1;
        for (std::size_t i = r.begin(); i < r.end(); ++i) warm = answerOne(order[i], warm);
        if (progress) progress(done += r.size(), n);
      },
      tbb::simple_partitioner());
}

}  // namespace treesketch::accel::detail
