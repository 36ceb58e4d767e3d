// A small gradient-boosted tree classifier (logistic loss, depth-limited trees on binned
// features), trained by the project on its own labelled scans: what turns per-point features into
// a wood probability. Trees are grown on histograms of the features' quantile bins, as
// LightGBM and XGBoost's "hist" method do (Friedman 2001, "Greedy function approximation").
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace treesketch::classify {

struct TreeNode {
  std::int32_t feature = -1;  ///< -1: a leaf
  float threshold = 0;        ///< x <= threshold goes to `left`
  std::int32_t left = -1, right = -1;
  float value = 0;  ///< a leaf's contribution to the logit
};

/// A trained model: logit = bias + the sum of every tree's leaf; probability = 1 / (1 + e^-logit).
struct BoostedTrees {
  std::vector<std::string> featureNames;
  double bias = 0;
  std::vector<std::vector<TreeNode>> trees;  ///< node 0 is each tree's root
  /// The probability at and above which a point is called wood (chosen on the training data).
  double threshold = 0.5;

  bool empty() const { return trees.empty(); }
  /// Logit / probability of one feature row (featureNames.size() values).
  double logit(const float* row) const;
  double probability(const float* row) const;
};

struct BoostOptions {
  /// Trees. 150 at a rate of 0.15: the held-out loss stops falling well before (measured on the
  /// tuning scans, docs/classify.md).
  int rounds = 150;
  /// Depth of each tree (3: interactions of three features, e.g. planar at one scale and linear at
  /// another, high in the crown).
  int depth = 3;
  double learningRate = 0.15;
  /// Quantile bins per feature (<= 255).
  int bins = 64;
  /// L2 penalty on leaf values and the least hessian sum a leaf may have (XGBoost's lambda and
  /// min_child_weight): keeps leaves off a handful of points.
  double l2 = 1.0;
  double minHessian = 5.0;
};

/// Trains on `rows` (row-major, `names.size()` values each) with labels (1 = wood) and per-row
/// weights (same length as labels; empty = all 1). Deterministic. Throws OptionsError for
/// inconsistent sizes, no rows, or only one class.
BoostedTrees trainBoostedTrees(const std::vector<float>& rows, const std::vector<std::string>& names,
                               const std::vector<std::uint8_t>& labels, const std::vector<float>& weights,
                               const BoostOptions& options = {});

/// The model as JSON text, and back. fromJson throws InputError naming `source` for malformed
/// text or a model that does not hold together (a node pointing outside its tree, a feature out
/// of range).
std::string toJson(const BoostedTrees& model);
BoostedTrees boostedTreesFromJson(const std::string& text, const std::string& source);

}  // namespace treesketch::classify
