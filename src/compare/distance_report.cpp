#include "treesketch/compare/distance_report.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "treesketch/util/error.h"

namespace treesketch::compare {

double DistanceReport::percent(double value) const {
  return diagonal > 0 ? 100.0 * value / diagonal : std::numeric_limits<double>::quiet_NaN();
}

DistanceReport summarizeDistances(const std::vector<double>& distances, double diagonal, int bins) {
  if (bins < 1) throw OptionsError("comparison: histogram bins must be >= 1, got " + std::to_string(bins));
  DistanceReport r;
  r.diagonal = diagonal;
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  // Sums in long double: a million squared distances keep full double precision.
  long double sum = 0, sum2 = 0;
  for (double d : distances) {
    if (!std::isfinite(d)) {
      ++r.samplesDropped;
      continue;
    }
    ++r.samplesUsed;
    lo = std::min(lo, d);
    hi = std::max(hi, d);
    sum += d;
    sum2 += static_cast<long double>(d) * d;
  }
  if (r.samplesUsed == 0) return r;
  const auto n = static_cast<long double>(r.samplesUsed);
  r.min = lo;
  r.max = hi;
  r.mean = static_cast<double>(sum / n);
  r.rms = static_cast<double>(std::sqrt(sum2 / n));
  r.histogram.min = lo;
  r.histogram.max = hi;
  r.histogram.counts.assign(static_cast<std::size_t>(bins), 0);
  const double width = (hi - lo) / bins;
  for (double d : distances) {
    if (!std::isfinite(d)) continue;
    std::size_t b = width > 0 ? static_cast<std::size_t>((d - lo) / width) : 0;
    ++r.histogram.counts[std::min<std::size_t>(b, static_cast<std::size_t>(bins) - 1)];
  }
  return r;
}

namespace {

nlohmann::json number(double x) { return std::isfinite(x) ? nlohmann::json(x) : nlohmann::json(nullptr); }

}  // namespace

nlohmann::json toJson(const DistanceReport& r) {
  nlohmann::json j;
  j["samples"] = {{"used", r.samplesUsed},
                  {"dropped", r.samplesDropped},
                  {"vertex", r.vertexSamples},
                  {"edge", r.edgeSamples},
                  {"face", r.faceSamples}};
  j["diagonal"] = number(r.diagonal);
  j["maxDistance"] = number(r.maxDistance);
  for (auto [name, value] :
       {std::pair<const char*, double>{"min", r.min}, {"max", r.max}, {"mean", r.mean}, {"rms", r.rms}}) {
    j[name] = number(value);
    j[std::string(name) + "Percent"] = number(r.percent(value));
  }
  j["histogram"] = {{"min", number(r.histogram.min)}, {"max", number(r.histogram.max)}, {"counts", r.histogram.counts}};
  if (!r.distances.empty()) {
    nlohmann::json d = nlohmann::json::array(), k = nlohmann::json::array();
    for (double x : r.distances) d.push_back(number(x));
    for (SampleKind kind : r.sampleKinds) k.push_back(toString(kind));
    j["perSample"] = {{"distance", d}, {"kind", k}, {"vertex", r.sampleVertex}};
  }
  return j;
}

}  // namespace treesketch::compare
