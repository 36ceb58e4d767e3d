// The wood/leaf classification measured and trained on labelled virtual scans: every test tree
// is scanned leaf-on under the matrix's conditions with the scanner recording which mesh each
// point hit (branches = wood), then classified (classify/classify.h) and scored per point like a
// classifier: wood precision, recall, F1 and Matthews correlation, per tree and condition, tuning
// and held-out trees apart. Training scans the tuning trees the same way, with the leaves' shape
// varied (warpLeaves) so the classifier does not learn the generator's flat squares.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "treesketch/classify/classify.h"
#include "treesketch/eval/condition_matrix.h"
#include "treesketch/eval/tree_suite.h"
#include "treesketch/geom/tri_mesh.h"

namespace treesketch::eval {

/// The rows of the full matrix scanned leaf-on (fullMatrix() rows with leafOn).
std::vector<ScanCondition> leafOnConditions();

/// Leaf shape variation: every leaf (a connected piece of `leaves`) is scaled about its centre by
/// a factor in [1 - scaleJitter, 1 + scaleJitter], squeezed along a random direction in its plane
/// to an aspect in [minAspect, 1] (narrow leaves, needles at the low end), and its corners moved off
/// its plane by up to `bend` times its size (curled, folded leaves). Deterministic for a seed.
struct LeafWarp {
  double scaleJitter = 0.4;
  double minAspect = 0.25;
  double bend = 0.35;
  std::uint64_t seed = 1;
};
geom::TriMesh warpLeaves(const geom::TriMesh& leaves, const LeafWarp& warp);

/// Per point scores of the wood class against the scanner's truth.
struct WoodScore {
  std::uint64_t tp = 0, fp = 0, fn = 0, tn = 0;
  double precision() const;
  double recall() const;
  double f1() const;
  /// Matthews correlation coefficient (0 when a margin is empty).
  double mcc() const;
  void add(bool truthWood, bool calledWood);
};

/// One classified scan.
struct ClassifyRow {
  std::string tree, half, condition, factor;
  std::size_t points = 0, woodPoints = 0;
  WoodScore score;     ///< after the graph step
  WoodScore rawScore;  ///< the classifier alone
  double ms = 0;       ///< classification wall time (features, classifier, graph)
};

struct ClassifyEvalOptions {
  std::vector<ScanCondition> conditions = leafOnConditions();
  classify::ClassifyOptions classify;
  std::uint64_t seed = 1;
  std::function<void(const std::string&)> log;
};

/// Scans every tree under every condition leaf-on, classifies with `model` (default: the built-in
/// one) and scores. Trees without a leaf mesh are scanned as they are. Throws OptionsError for an
/// unknown pattern.
std::vector<ClassifyRow> evaluateClassifier(const std::vector<TreeCase>& trees, const ClassifyEvalOptions& options,
                                            const classify::BoostedTrees* model = nullptr);

/// Mean and worst F1 / MCC over rows, per condition and half ("tune", "held-out"), as a Markdown
/// report with the per-scan table.
std::string classifyReport(const std::vector<ClassifyRow>& rows);

struct ClassifierTraining {
  std::vector<ScanCondition> conditions = leafOnConditions();
  /// Scans per tree and condition: the first with the leaves as they are, the others warped.
  int leafVariants = 2;
  LeafWarp warp;
  /// Points sampled per scan (wood and leaf points weighted to equal totals per scan, so every
  /// scan counts alike and the rare wood counts as much as the leaves).
  std::size_t rowsPerScan = 20000;
  classify::FeatureOptions features;
  classify::BoostOptions boost;
  std::uint64_t seed = 1;
  std::function<void(const std::string&)> log;
};

/// Trains a classifier on scans of `trees` (pass the tuning half) and chooses its threshold as
/// the one with the best mean F1 over the training scans, each scored by a model trained on the
/// other half of the trees (two folds by tree; 0.5 with a single tree).
classify::BoostedTrees trainClassifier(const std::vector<TreeCase>& trees, const ClassifierTraining& options);

/// Trains the context model (classify/context_pass.h) on the same scans: the first pass on each
/// tree's scans is a model trained on the other half of the trees (two folds by tree), its
/// probabilities give the context columns, and the threshold is chosen as trainClassifier's (by
/// two folds over the context rows). Throws OptionsError for fewer than two trees.
classify::BoostedTrees trainContextClassifier(const std::vector<TreeCase>& trees, const ClassifierTraining& options);

}  // namespace treesketch::eval
