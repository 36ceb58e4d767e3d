// The result of a one-directional surface comparison, as Metro and MeshLab report it (thesis
// §2.5): samples used and dropped, min / max / mean / RMS distance, absolute and as a percentage of
// the sampled surface's bounding-box diagonal, plus a histogram; and its JSON form.
#pragma once

#include <cstdint>
#include <limits>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "treesketch/compare/surface_sampling.h"

namespace treesketch::compare {

/// Counts of the used distances in `counts.size()` equal bins over [min, max] (metres); the last
/// bin includes max. Empty when no sample was used.
struct Histogram {
  double min = 0, max = 0;
  std::vector<std::uint64_t> counts;
};

struct DistanceReport {
  std::uint64_t samplesUsed = 0;     ///< samples whose closest point was within the search distance
  std::uint64_t samplesDropped = 0;  ///< samples farther than the search distance (not in the statistics)
  std::uint64_t vertexSamples = 0, edgeSamples = 0, faceSamples = 0;  ///< samples taken per kind
  /// Distances in metres over the used samples; NaN when none was used.
  double min = std::numeric_limits<double>::quiet_NaN();
  double max = std::numeric_limits<double>::quiet_NaN();
  double mean = std::numeric_limits<double>::quiet_NaN();
  double rms = std::numeric_limits<double>::quiet_NaN();
  /// Bounding-box diagonal of the sampled surface (metres): the percentages are relative to it.
  double diagonal = 0;
  /// The search distance used (metres; +inf for none).
  double maxDistance = std::numeric_limits<double>::infinity();
  Histogram histogram;
  /// Optional (CompareOptions::keepSamples): per sample, its distance (+inf when dropped), its kind
  /// and, for vertex samples, the vertex index (-1 otherwise), in sampling order.
  std::vector<double> distances;
  std::vector<SampleKind> sampleKinds;
  std::vector<std::int64_t> sampleVertex;

  /// `value` (metres) as a percentage of `diagonal`; NaN when the diagonal is 0.
  double percent(double value) const;
};

/// Statistics of `distances` (metres; +inf or NaN entries count as dropped), with `bins` histogram
/// bins (>= 1; throws OptionsError otherwise). Sums run in input order, so the result is
/// reproducible bit for bit. Sample kinds and kept samples are left to the caller.
DistanceReport summarizeDistances(const std::vector<double>& distances, double diagonal, int bins);

/// JSON object of a report: counts, statistics (NaN as null), the same as percentages of the
/// diagonal (`minPercent`...), the histogram, and the per-sample arrays when kept.
nlohmann::json toJson(const DistanceReport& report);

}  // namespace treesketch::compare
