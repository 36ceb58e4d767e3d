// The context pass (classify/context_pass.h): the first pass's probabilities around each core as
// features of a second classifier.
#include "treesketch/classify/context_pass.h"

#include <algorithm>
#include <cstdint>

#include "treesketch/util/error.h"

namespace treesketch::classify {

extern const char* const kContextModelJson;

std::vector<std::string> contextFeatureNames() {
  return {"context_p", "context_mean_k1", "context_max_k1", "context_mean_k2", "context_hops"};
}

const BoostedTrees& contextModel() {
  static const BoostedTrees model = boostedTreesFromJson(kContextModelJson, "the built-in context classifier");
  return model;
}

namespace {

/// Hops along the neighbour graph from every core to the nearest confident one (breadth first).
std::vector<int> hopsToConfident(const FeatureTable& f, const std::vector<float>& p) {
  const std::size_t n = p.size(), g = static_cast<std::size_t>(f.neighbourCount);
  std::vector<int> hops(n, kContextMaxHops);
  std::vector<std::uint32_t> front, next;
  for (std::size_t i = 0; i < n; ++i)
    if (p[i] >= kContextConfident) {
      hops[i] = 0;
      front.push_back(static_cast<std::uint32_t>(i));
    }
  for (int h = 1; h < kContextMaxHops && !front.empty(); ++h) {
    next.clear();
    for (std::uint32_t i : front)
      for (std::size_t k = 0; k < g; ++k) {
        const std::uint32_t j = f.neighbours[i * g + k];
        if (hops[j] > h) {
          hops[j] = h;
          next.push_back(j);
        }
      }
    std::swap(front, next);
  }
  return hops;
}

}  // namespace

FeatureTable withContext(const FeatureTable& f, const std::vector<float>& p) {
  const std::size_t n = f.points();
  if (p.size() != n) throw OptionsError("classify: the context pass needs one probability per core point");
  const std::size_t g = static_cast<std::size_t>(f.neighbourCount);
  const std::vector<std::string> extra = contextFeatureNames();
  FeatureTable t = f;
  t.names.insert(t.names.end(), extra.begin(), extra.end());
  t.count = f.count + static_cast<int>(extra.size());
  const std::size_t width = static_cast<std::size_t>(t.count);
  t.values.assign(n * width, 0.0f);
  const std::vector<int> hops = hopsToConfident(f, p);
  std::vector<float> mean1(n), max1(n);
  for (std::size_t i = 0; i < n; ++i) {
    float sum = 0, most = 0;
    for (std::size_t k = 0; k < g; ++k) {
      const float q = p[f.neighbours[i * g + k]];
      sum += q;
      most = std::max(most, q);
    }
    mean1[i] = g > 0 ? sum / static_cast<float>(g) : p[i];
    max1[i] = g > 0 ? most : p[i];
  }
  for (std::size_t i = 0; i < n; ++i) {
    float* row = t.values.data() + i * width;
    std::copy(f.row(i), f.row(i) + f.count, row);
    float sum2 = 0;
    for (std::size_t k = 0; k < g; ++k) sum2 += mean1[f.neighbours[i * g + k]];
    row[f.count] = p[i];
    row[f.count + 1] = mean1[i];
    row[f.count + 2] = max1[i];
    row[f.count + 3] = g > 0 ? sum2 / static_cast<float>(g) : p[i];
    row[f.count + 4] = static_cast<float>(hops[i]);
  }
  return t;
}

}  // namespace treesketch::classify
