// The context pass of the wood/leaf classification: a second classifier that sees, beside each
// core's own features, what the first pass called the cores around it. Wood is continuous (a twig
// runs on from the wood it grows from), so a core the first pass is unsure of is more likely wood
// when its neighbours are wood and it lies a few hops along the neighbour graph from confident
// wood; a leaf beside a twig has the same shape but sits at the end of such a run, among leaves.
// The context model is trained like the first (classify --train-context): on the tuning half's
// scans, with each scan's first-pass probabilities from a model trained on the other half of the
// trees (two folds by tree), so the context it learns from is as unsure as on a new tree.
#pragma once

#include <string>
#include <vector>

#include "treesketch/classify/boosted_trees.h"
#include "treesketch/classify/features.h"

namespace treesketch::classify {

/// The context columns appended to the features (FeatureTable::names), in this order: the core's
/// own first-pass probability; the mean and the largest over its graph neighbours
/// (FeatureOptions::graphNeighbours); the mean of the neighbours' means (two hops); the hops along
/// the neighbour graph to the nearest core of at least kContextConfident (kContextMaxHops when
/// none is nearer).
std::vector<std::string> contextFeatureNames();

/// First-pass probability counted as confident wood by the hops column (the built-in first model's
/// threshold when the context model was trained), and the cap of that column.
inline constexpr float kContextConfident = 0.875f;
inline constexpr int kContextMaxHops = 10;

/// `features` with the context columns of `probability` (one per core) appended. Throws
/// OptionsError when `probability` does not hold one value per core.
FeatureTable withContext(const FeatureTable& features, const std::vector<float>& probability);

/// The context model built into the library (src/classify/context_model.json): its features are
/// the built-in first model's followed by contextFeatureNames().
const BoostedTrees& contextModel();

}  // namespace treesketch::classify
