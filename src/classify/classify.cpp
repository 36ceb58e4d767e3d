// The classification stage (classify/classify.h): features, the trained model, the graph step.
#include "treesketch/classify/classify.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

#include "treesketch/classify/context_pass.h"
#include "treesketch/util/error.h"
#include "treesketch/util/stopwatch.h"

namespace treesketch::classify {

// Defined in the file CMake generates from src/classify/trained_model.json.
extern const char* const kTrainedModelJson;

const BoostedTrees& trainedModel() {
  static const BoostedTrees model = boostedTreesFromJson(kTrainedModelJson, "the built-in classifier");
  return model;
}

FeatureOptions featureOptionsFor(const BoostedTrees& model, FeatureOptions options) {
  for (int off = 0; off < 8; ++off) {  // every setting of the three switches, all on first
    options.normalFeatures = (off & 4) == 0;
    options.positionFeatures = (off & 2) == 0;
    options.graphFeatures = (off & 1) == 0;
    if (featureNames(options) == model.featureNames) return options;
  }
  throw OptionsError("classify: the model was trained on other features than these (" +
                     std::to_string(model.featureNames.size()) + " features)");
}

std::vector<float> predictWood(const FeatureTable& f, const BoostedTrees& model) {
  if (model.featureNames != f.names)
    throw OptionsError("classify: the model was trained on other features than these (" +
                       std::to_string(model.featureNames.size()) + " against " + std::to_string(f.names.size()) + ")");
  // Tree by tree over blocks of rows: one tree's few nodes stay in the cache while a block of rows
  // passes through it (row by row, every row walks all 150 trees' nodes). Each row's logit adds the
  // same terms in the same order as BoostedTrees::logit, so the answer is the same to the bit.
  constexpr std::size_t kBlock = 256;
  std::vector<float> p(f.points());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, p.size(), kBlock), [&](const tbb::blocked_range<std::size_t>& r) {
    double logit[kBlock];
    for (std::size_t begin = r.begin(); begin < r.end(); begin += kBlock) {
      const std::size_t end = std::min(r.end(), begin + kBlock);
      std::fill_n(logit, end - begin, model.bias);
      for (const auto& tree : model.trees)
        for (std::size_t i = begin; i < end; ++i) {
          const float* row = f.row(i);
          std::int32_t n = 0;
          while (tree[n].feature >= 0) n = row[tree[n].feature] <= tree[n].threshold ? tree[n].left : tree[n].right;
          logit[i - begin] += tree[n].value;
        }
      for (std::size_t i = begin; i < end; ++i) p[i] = static_cast<float>(1.0 / (1.0 + std::exp(-logit[i - begin])));
    }
  });
  return p;
}

ClassifyOptions woodModellingOptions() {
  ClassifyOptions o;
  o.contextPass = true;
  o.threshold = kWoodModellingThreshold;
  return o;
}

Classification classifyWood(const geom::PointCloud& cloud, geom::UpAxis up, const ClassifyOptions& options,
                            const BoostedTrees* model) {
  const BoostedTrees& m = model ? *model : trainedModel();
  Classification c;
  Stopwatch clock;
  const FeatureTable f = computeFeatures(cloud, up, featureOptionsFor(m, options.features));
  c.featuresMs = clock.ms();
  clock.restart();
  c.spacing = f.spacing;
  c.measuredSpacing = f.measuredSpacing;
  c.cores = f.points();
  std::vector<float> coreP = predictWood(f, m);
  double ownThreshold = m.threshold;
  if (options.contextPass) {
    coreP = predictWood(withContext(f, coreP), contextModel());
    ownThreshold = contextModel().threshold;
    c.contextPass = true;
  } else if (options.smoothing && &m == &trainedModel()) {
    coreP = smoothOverGraph(f, coreP, kSmoothingWeight, kSmoothingPasses, options.graph.maxEdgeSpacings);
    ownThreshold = kSmoothedWoodThreshold;
    c.smoothed = true;
  }
  c.predictMs = clock.ms();
  clock.restart();
  c.threshold = std::isnan(options.threshold) ? ownThreshold : options.threshold;
  std::vector<std::uint8_t> coreWood;
  if (options.connect) {
    c.graph = connectWood(f, coreP, c.threshold, options.graph);
    coreWood = std::move(c.graph.wood);
    c.graph.wood.clear();
  } else {
    coreWood.resize(coreP.size());
    for (std::size_t i = 0; i < coreP.size(); ++i) coreWood[i] = coreP[i] >= c.threshold ? 1 : 0;
  }
  c.woodProbability.resize(cloud.size());
  c.wood.resize(cloud.size());
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    c.woodProbability[i] = coreP[f.coreOf[i]];
    c.wood[i] = coreWood[f.coreOf[i]];
  }
  c.graphMs = clock.ms();
  for (auto w : c.wood) c.woodPoints += w;
  return c;
}

std::vector<std::uint8_t> classCodes(const Classification& c) {
  std::vector<std::uint8_t> codes(c.wood.size());
  for (std::size_t i = 0; i < codes.size(); ++i) codes[i] = c.wood[i] ? kWoodClass : kLeafClass;
  return codes;
}

}  // namespace treesketch::classify
