// The classification stage (classify/classify.h): features, the trained model, the graph step.
#include "treesketch/classify/classify.h"

#include <tbb/parallel_for.h>

#include <cmath>

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
  for (int position = 1; position >= 0; --position)
    for (int graph = 1; graph >= 0; --graph) {
      options.positionFeatures = position != 0;
      options.graphFeatures = graph != 0;
      if (featureNames(options) == model.featureNames) return options;
    }
  throw OptionsError("classify: the model was trained on other features than these (" +
                     std::to_string(model.featureNames.size()) + " features)");
}

std::vector<float> predictWood(const FeatureTable& f, const BoostedTrees& model) {
  if (model.featureNames != f.names)
    throw OptionsError("classify: the model was trained on other features than these (" +
                       std::to_string(model.featureNames.size()) + " against " + std::to_string(f.names.size()) + ")");
  std::vector<float> p(f.points());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, p.size(), 4096), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t i = r.begin(); i != r.end(); ++i) p[i] = static_cast<float>(model.probability(f.row(i)));
  });
  return p;
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
  c.cores = f.points();
  const std::vector<float> coreP = predictWood(f, m);
  c.predictMs = clock.ms();
  clock.restart();
  c.threshold = std::isnan(options.threshold) ? m.threshold : options.threshold;
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
