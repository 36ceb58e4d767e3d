// Wood/leaf classification of a tree's point cloud, a stage of its own before the skeleton:
// per-point features (features.h) -> a wood probability from a classifier the project trains on
// its own labelled virtual scans (boosted_trees.h; the trained model is built into the library,
// see docs/classify.md for the command that makes it) -> the probability averaged with its graph
// neighbours' -> a class, with wood kept connected to the stem (wood_graph.h).
#pragma once

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "treesketch/classify/boosted_trees.h"
#include "treesketch/classify/features.h"
#include "treesketch/classify/wood_graph.h"
#include "treesketch/geom/point_cloud.h"

namespace treesketch::classify {

/// The class codes written to files: the LAS classification field and the PLY `classification`
/// property. 64 and 65 are the first of the codes LAS 1.4 leaves to users (R15, table 17: 64-255
/// "user definable").
inline constexpr std::uint8_t kWoodClass = 64;
inline constexpr std::uint8_t kLeafClass = 65;

struct ClassifyOptions {
  FeatureOptions features;
  WoodGraphOptions graph;
  /// Apply the graph step (off: the classifier's call alone).
  bool connect = true;
  /// Wood at and above this probability; NaN = the model's own threshold (chosen in training).
  double threshold = NAN;
  /// Average each core's probability with its graph neighbours' before the threshold and the graph
  /// step (smoothOverGraph, kSmoothingWeight, kSmoothingPasses; wood then at kSmoothedWoodThreshold
  /// unless `threshold` is set). Applies to the built-in model's first pass only: its threshold
  /// for the averaged probabilities was chosen on the tuning half, and the context pass already
  /// reads its neighbours' answers.
  bool smoothing = true;
  /// Classify again with the context pass (context_pass.h): the first pass's probabilities around
  /// each point as features of the context model, whose probability and threshold then stand.
  bool contextPass = false;
};

/// The smoothing of the built-in model's probabilities over the core graph (ClassifyOptions::
/// smoothing): each pass replaces a core's probability by the mean of its own and its neighbours'
/// mean (weight 0.5), two passes (the neighbours' neighbours, a few core spacings along a limb).
/// Chosen with kSmoothedWoodThreshold on the tuning half, each tree scored by a model trained on
/// the other half of the tuning trees (as the model's own threshold is chosen; without smoothing
/// mean wood F1 0.759, worst scan 0.173). Over weights 0.3-0.7, 1-4 passes and thresholds
/// 0.75-0.875, the settings that do not lower the worst scan score 0.771-0.773, within 0.002 of
/// the best of them; of those, the fewest passes whose tuning scans as the built-in model scores
/// them gain in mean and worst scan alike (0.814 -> 0.823, 0.429 -> 0.435; docs/classify.md,
/// "Measured").
inline constexpr double kSmoothingWeight = 0.5;
inline constexpr int kSmoothingPasses = 2;
/// Wood at and above this smoothed probability (the built-in model's own threshold, 0.875, is for
/// its probabilities as they come): averaging pulls a limb's unsure cores up towards the limb and
/// a leaf's stray confident cores down towards the leaves, so the best cut moves down (chosen with
/// the smoothing, above: 0.772 mean F1 out of half at 0.825, 0.771 at 0.80, 0.773 at 0.85 but with
/// the worst scan lower, 0.164).
inline constexpr double kSmoothedWoodThreshold = 0.825;

/// The threshold of the context pass for the points a wood-only model is made from: lower than the
/// context model's own (chosen for the best F1 of the classes), because a model of the wood loses
/// more by a twig called leaf than it gains by a leaf kept out. Chosen on the tuning half's
/// wood-only models (docs/classify.md, "Modelling the wood").
inline constexpr double kWoodModellingThreshold = 0.75;

/// The options the wood-only model classifies with: the context pass at kWoodModellingThreshold.
ClassifyOptions woodModellingOptions();

struct Classification {
  std::vector<float> woodProbability;  ///< the classifier's (smoothed when `smoothed`), one per point, 0..1
  std::vector<std::uint8_t> wood;      ///< the class after the graph step: 1 wood, 0 leaf
  std::size_t woodPoints = 0;
  double threshold = 0.5;  ///< the threshold used
  double spacing = 0;      ///< the spacing the features worked at (FeatureTable::spacing, cloud units)
  double measuredSpacing = 0;  ///< the cloud's median spacing (cloud units)
  std::size_t cores = 0;   ///< core points the features, classifier and graph ran on
  bool contextPass = false;  ///< the probabilities are the context pass's (ClassifyOptions::contextPass)
  bool smoothed = false;     ///< the probabilities were averaged over the graph (ClassifyOptions::smoothing)
  WoodGraphResult graph;   ///< what the graph step did, in cores (its `wood` is moved to `wood` above)
  double featuresMs = 0, predictMs = 0, graphMs = 0;
};

/// The model built into the library (src/classify/trained_model.json, embedded at build time).
const BoostedTrees& trainedModel();

/// Classifies every point of `cloud` with `model` (default: trainedModel()). `up` is the cloud's up
/// axis. The feature switches follow the model (featureOptionsFor). Throws OptionsError when the
/// model's features are not those of options.features in any switch setting, and
/// DegenerateInputError for a cloud too small for the largest feature scale.
Classification classifyWood(const geom::PointCloud& cloud, geom::UpAxis up, const ClassifyOptions& options = {},
                            const BoostedTrees* model = nullptr);

/// `options` with the feature switches set to what `model` was trained on (the model's feature
/// names decide). Throws OptionsError when no switch setting gives its names.
FeatureOptions featureOptionsFor(const BoostedTrees& model, FeatureOptions options = {});

/// The wood probability of every row of `features` (TBB parallel).
std::vector<float> predictWood(const FeatureTable& features, const BoostedTrees& model);

/// The class codes (kWoodClass / kLeafClass) of a classification, one per point.
std::vector<std::uint8_t> classCodes(const Classification& c);

}  // namespace treesketch::classify
