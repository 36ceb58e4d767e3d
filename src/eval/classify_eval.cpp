// The classification's measurement and training on labelled virtual scans (eval/classify_eval.h).
#include "treesketch/eval/classify_eval.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <map>
#include <random>

#include "treesketch/classify/context_pass.h"
#include "treesketch/eval/evaluation.h"
#include "treesketch/util/error.h"
#include "treesketch/util/stopwatch.h"
#include "treesketch/util/union_find.h"

namespace treesketch::eval {

std::vector<ScanCondition> leafOnConditions() {
  std::vector<ScanCondition> out;
  for (const auto& c : fullMatrix())
    if (c.leafOn) out.push_back(c);
  return out;
}

// ---- leaf shapes ---------------------------------------------------------------------------------

geom::TriMesh warpLeaves(const geom::TriMesh& leaves, const LeafWarp& w) {
  geom::TriMesh out = leaves;
  const std::size_t nv = leaves.vertices.size();
  util::UnionFind pieces(nv);
  for (const auto& t : leaves.triangles) {
    pieces.unite(t[0], t[1]);
    pieces.unite(t[0], t[2]);
  }
  std::map<std::uint32_t, std::vector<std::uint32_t>> members;
  for (std::uint32_t v = 0; v < nv; ++v) members[pieces.find(v)].push_back(v);
  std::map<std::uint32_t, geom::Vec3> normal;
  for (const auto& t : leaves.triangles) {
    const geom::Vec3 n =
        (leaves.vertices[t[1]] - leaves.vertices[t[0]]).cross(leaves.vertices[t[2]] - leaves.vertices[t[0]]);
    if (n.norm() > 0) normal.emplace(pieces.find(t[0]), n.normalized());
  }
  std::mt19937_64 rng(w.seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0), unit(0.0, 1.0);
  for (const auto& [root, vs] : members) {
    geom::Vec3 c = geom::Vec3::Zero();
    for (auto v : vs) c += leaves.vertices[v];
    c /= static_cast<double>(vs.size());
    double size = 0;
    for (auto v : vs) size = std::max(size, (leaves.vertices[v] - c).norm());
    const auto it = normal.find(root);
    const geom::Vec3 n = it == normal.end() ? geom::Vec3::UnitY() : it->second;
    geom::Vec3 a = n.unitOrthogonal();
    const double angle = M_PI * unit(rng);
    a = std::cos(angle) * a + std::sin(angle) * n.cross(a);
    const double scale = 1.0 + w.scaleJitter * u(rng);
    const double aspect = w.minAspect + (1.0 - w.minAspect) * unit(rng);
    for (auto v : vs) {
      geom::Vec3 d = leaves.vertices[v] - c;
      d -= (1.0 - aspect) * d.dot(a) * a;
      out.vertices[v] = c + scale * d + n * (w.bend * size * u(rng));
    }
  }
  return out;
}

// ---- scores --------------------------------------------------------------------------------------

double WoodScore::precision() const { return tp + fp == 0 ? 0.0 : static_cast<double>(tp) / (tp + fp); }
double WoodScore::recall() const { return tp + fn == 0 ? 0.0 : static_cast<double>(tp) / (tp + fn); }
double WoodScore::f1() const {
  return tp == 0 ? 0.0 : 2.0 * static_cast<double>(tp) / (2.0 * static_cast<double>(tp) + fp + fn);
}
double WoodScore::mcc() const {
  const double a = static_cast<double>(tp), b = static_cast<double>(fp), c = static_cast<double>(fn),
               d = static_cast<double>(tn);
  const double den = std::sqrt((a + b) * (a + c) * (d + b) * (d + c));
  return den == 0 ? 0.0 : (a * d - b * c) / den;
}
void WoodScore::add(bool truth, bool called) {
  if (truth && called)
    ++tp;
  else if (called)
    ++fp;
  else if (truth)
    ++fn;
  else
    ++tn;
}

// ---- evaluation ----------------------------------------------------------------------------------

namespace {

/// Leaf-on scan of a tree (with its leaves as given or replaced by `leaves`).
TreeScan scanLeafOn(const TreeCase& tree, const ScanCondition& c, std::uint64_t seed) {
  return scanTree(tree, c, true, seed);
}

}  // namespace

std::vector<ClassifyRow> evaluateClassifier(const std::vector<TreeCase>& trees, const ClassifyEvalOptions& o,
                                            const classify::BoostedTrees* model) {
  std::vector<ClassifyRow> rows;
  for (const auto& tree : trees) {
    for (const auto& c : o.conditions) {
      const TreeScan scan = scanLeafOn(tree, c, o.seed);
      ClassifyRow r;
      r.tree = tree.name;
      r.half = halfName(treeHalf(tree.name));
      r.condition = c.name;
      r.factor = c.factor;
      r.points = scan.cloud.size();
      Stopwatch clock;
      const classify::Classification k = classify::classifyWood(scan.cloud, tree.up, o.classify, model);
      r.ms = clock.ms();
      for (std::size_t i = 0; i < scan.cloud.size(); ++i) {
        const bool truth = scan.cloud.meshId[i] == 0;
        r.woodPoints += truth;
        r.score.add(truth, k.wood[i] != 0);
        r.rawScore.add(truth, k.woodProbability[i] >= k.threshold);
      }
      if (o.log) {
        char buf[256];
        std::snprintf(buf, sizeof buf,
                      "%s %s: %zu points (%zu wood), F1 %.3f MCC %.3f (classifier alone %.3f %.3f), %.0f ms",
                      tree.name.c_str(), c.name.c_str(), r.points, r.woodPoints, r.score.f1(), r.score.mcc(),
                      r.rawScore.f1(), r.rawScore.mcc(), r.ms);
        o.log(buf);
      }
      rows.push_back(std::move(r));
    }
  }
  return rows;
}

std::string classifyReport(const std::vector<ClassifyRow>& rows) {
  std::string s =
      "| condition | half | scans | F1 mean | F1 worst | MCC mean | MCC worst | precision | recall | "
      "F1 classifier alone |\n|---|---|---|---|---|---|---|---|---|---|\n";
  std::vector<std::string> conditions;
  for (const auto& r : rows)
    if (std::find(conditions.begin(), conditions.end(), r.condition) == conditions.end())
      conditions.push_back(r.condition);
  conditions.push_back("all");
  char buf[512];
  for (const auto& c : conditions) {
    for (const char* half : {"tune", "held-out"}) {
      int n = 0;
      double f1 = 0, mcc = 0, pr = 0, re = 0, raw = 0, f1w = INFINITY, mccw = INFINITY;
      for (const auto& r : rows) {
        if ((c != "all" && r.condition != c) || r.half != half) continue;
        ++n;
        f1 += r.score.f1();
        mcc += r.score.mcc();
        pr += r.score.precision();
        re += r.score.recall();
        raw += r.rawScore.f1();
        f1w = std::min(f1w, r.score.f1());
        mccw = std::min(mccw, r.score.mcc());
      }
      if (n == 0) continue;
      std::snprintf(buf, sizeof buf, "| %s | %s | %d | %.3f | %.3f | %.3f | %.3f | %.3f | %.3f | %.3f |\n", c.c_str(),
                    half, n, f1 / n, f1w, mcc / n, mccw, pr / n, re / n, raw / n);
      s += buf;
    }
  }
  s += "\n| tree | half | condition | points | wood | precision | recall | F1 | MCC | ms |\n"
       "|---|---|---|---|---|---|---|---|---|---|\n";
  for (const auto& r : rows) {
    std::snprintf(buf, sizeof buf, "| %s | %s | %s | %zu | %zu | %.3f | %.3f | %.3f | %.3f | %.0f |\n", r.tree.c_str(),
                  r.half.c_str(), r.condition.c_str(), r.points, r.woodPoints, r.score.precision(), r.score.recall(),
                  r.score.f1(), r.score.mcc(), r.ms);
    s += buf;
  }
  return s;
}

// ---- training ------------------------------------------------------------------------------------

namespace {

struct Samples {
  std::vector<float> rows;
  std::vector<std::uint8_t> labels;
  std::vector<float> weights;
  std::vector<std::uint32_t> scan;  ///< which scan each row came from
  std::vector<std::uint8_t> fold;   ///< which half of the trees (0 or 1) each row came from
};

/// Samples up to `count` core points of one labelled scan into `s`, each labelled wood when most
/// of its points are, wood and leaves weighted to equal totals.
void sampleScan(const classify::FeatureTable& f, const geom::PointCloud& cloud, std::size_t count, std::uint32_t scanId,
                std::uint8_t fold, std::mt19937_64& rng, Samples& s) {
  const std::size_t n = f.points();
  std::vector<std::uint32_t> woodIn(n, 0);
  for (std::size_t i = 0; i < cloud.size(); ++i) woodIn[f.coreOf[i]] += cloud.meshId[i] == 0;
  std::vector<std::uint32_t> pick(n);
  for (std::size_t i = 0; i < n; ++i) pick[i] = static_cast<std::uint32_t>(i);
  std::shuffle(pick.begin(), pick.end(), rng);
  pick.resize(std::min(count, n));
  std::size_t wood = 0;
  for (auto i : pick) wood += 2 * woodIn[i] > f.coreSize[i];
  if (wood == 0 || wood == pick.size()) return;
  const float ww = 0.5f * pick.size() / wood, wl = 0.5f * pick.size() / (pick.size() - wood);
  for (auto i : pick) {
    const bool isWood = 2 * woodIn[i] > f.coreSize[i];
    s.rows.insert(s.rows.end(), f.row(i), f.row(i) + f.count);
    s.labels.push_back(isWood);
    s.weights.push_back(isWood ? ww : wl);
    s.scan.push_back(scanId);
    s.fold.push_back(fold);
  }
}

/// Out-of-fold wood probabilities: a model trained on the rows of one half of the trees predicts
/// the other half's rows, so the threshold is chosen on answers the model did not learn from.
std::vector<float> outOfFold(const Samples& s, const std::vector<std::string>& names, const classify::BoostOptions& o) {
  const std::size_t n = s.labels.size(), f = names.size();
  std::vector<float> p(n, 0.5f);
  for (std::uint8_t fold = 0; fold < 2; ++fold) {
    Samples in;
    for (std::size_t i = 0; i < n; ++i)
      if (s.fold[i] != fold) {
        in.rows.insert(in.rows.end(), s.rows.begin() + i * f, s.rows.begin() + (i + 1) * f);
        in.labels.push_back(s.labels[i]);
        in.weights.push_back(s.weights[i]);
      }
    const classify::BoostedTrees m = classify::trainBoostedTrees(in.rows, names, in.labels, in.weights, o);
    for (std::size_t i = 0; i < n; ++i)
      if (s.fold[i] == fold) p[i] = static_cast<float>(m.probability(s.rows.data() + i * f));
  }
  return p;
}

/// The threshold with the best mean F1 over the training scans (on their samples' probabilities `p`).
double chooseThreshold(const std::vector<float>& p, const Samples& s) {
  const std::size_t n = s.labels.size();
  const std::uint32_t scans = s.scan.empty() ? 0 : s.scan.back() + 1;
  double best = 0.5, bestF1 = -1;
  for (double t = 0.1; t < 0.951; t += 0.025) {
    std::vector<WoodScore> per(scans);
    for (std::size_t i = 0; i < n; ++i) per[s.scan[i]].add(s.labels[i] != 0, p[i] >= t);
    double f1 = 0;
    for (const auto& w : per) f1 += w.f1();
    if (f1 > bestF1) bestF1 = f1, best = t;
  }
  return best;
}

/// A stable hash of a name (FNV-1a), for per-tree seeds.
std::uint64_t nameHash(const std::string& name) {
  std::uint64_t h = 1469598103934665603ull;
  for (unsigned char c : name) h = (h ^ c) * 1099511628211ull;
  return h;
}

}  // namespace

namespace {

/// Calls `scanned(tree index, its scan, the scan's features)` for every training scan of `trees`
/// (each tree, leaf variant and condition, in that order).
void forEachTrainingScan(
    const std::vector<TreeCase>& trees, const ClassifierTraining& o,
    const std::function<void(std::size_t, const TreeScan&, const classify::FeatureTable&)>& scanned) {
  for (std::size_t t = 0; t < trees.size(); ++t) {
    const TreeCase& tree = trees[t];
    for (int v = 0; v < o.leafVariants; ++v) {
      TreeCase variant = tree;
      if (v > 0 && !tree.leaves.empty()) {
        LeafWarp w = o.warp;
        w.seed = o.seed * 1000 + v * 7 + nameHash(tree.name) % 997;
        variant.leaves = warpLeaves(tree.leaves, w);
      }
      for (const auto& c : o.conditions) {
        const TreeScan scan = scanLeafOn(variant, c, o.seed + v);
        const classify::FeatureTable f = classify::computeFeatures(scan.cloud, tree.up, o.features);
        scanned(t, scan, f);
        if (o.log)
          o.log(tree.name + " variant " + std::to_string(v) + " " + c.name + ": " + std::to_string(scan.cloud.size()) +
                " points");
      }
    }
  }
}

/// The model trained on the rows of the other half of the trees than `fold`.
classify::BoostedTrees foldModel(const Samples& s, const std::vector<std::string>& names, std::uint8_t fold,
                                 const classify::BoostOptions& o) {
  Samples in;
  const std::size_t f = names.size();
  for (std::size_t i = 0; i < s.labels.size(); ++i)
    if (s.fold[i] != fold) {
      in.rows.insert(in.rows.end(), s.rows.begin() + i * f, s.rows.begin() + (i + 1) * f);
      in.labels.push_back(s.labels[i]);
      in.weights.push_back(s.weights[i]);
    }
  return classify::trainBoostedTrees(in.rows, names, in.labels, in.weights, o);
}

/// Samples of every training scan with the first pass's features (fold: the tree's half).
Samples firstPassSamples(const std::vector<TreeCase>& trees, const ClassifierTraining& o, std::uint64_t seed) {
  Samples s;
  std::mt19937_64 rng(seed);
  std::uint32_t scanId = 0;
  forEachTrainingScan(trees, o, [&](std::size_t t, const TreeScan& scan, const classify::FeatureTable& f) {
    sampleScan(f, scan.cloud, o.rowsPerScan, scanId++, static_cast<std::uint8_t>(t % 2), rng, s);
  });
  return s;
}

}  // namespace

classify::BoostedTrees trainClassifier(const std::vector<TreeCase>& trees, const ClassifierTraining& o) {
  const Samples s = firstPassSamples(trees, o, o.seed);
  const std::vector<std::string> names = classify::featureNames(o.features);
  classify::BoostedTrees m = classify::trainBoostedTrees(s.rows, names, s.labels, s.weights, o.boost);
  m.threshold = trees.size() >= 2 ? chooseThreshold(outOfFold(s, names, o.boost), s) : 0.5;
  if (o.log)
    o.log("trained on " + std::to_string(s.labels.size()) + " points of " + std::to_string(s.scan.empty() ? 0 : s.scan.back() + 1) +
          " scans; threshold " + std::to_string(m.threshold));
  return m;
}

classify::BoostedTrees trainContextClassifier(const std::vector<TreeCase>& trees, const ClassifierTraining& o) {
  if (trees.size() < 2) throw OptionsError("classify: the context model is trained by two folds, on two trees or more");
  const Samples first = firstPassSamples(trees, o, o.seed);
  const std::vector<std::string> names = classify::featureNames(o.features);
  const classify::BoostedTrees folds[2] = {foldModel(first, names, 0, o.boost), foldModel(first, names, 1, o.boost)};
  Samples s;
  std::mt19937_64 rng(o.seed + 17);
  std::uint32_t scanId = 0;
  forEachTrainingScan(trees, o, [&](std::size_t t, const TreeScan& scan, const classify::FeatureTable& f) {
    // The first pass of a model that did not see this tree: as unsure as on a new one.
    const classify::FeatureTable withContext = classify::withContext(f, classify::predictWood(f, folds[t % 2]));
    sampleScan(withContext, scan.cloud, o.rowsPerScan, scanId++, static_cast<std::uint8_t>(t % 2), rng, s);
  });
  std::vector<std::string> contextNames = names;
  for (const auto& n : classify::contextFeatureNames()) contextNames.push_back(n);
  classify::BoostedTrees m = classify::trainBoostedTrees(s.rows, contextNames, s.labels, s.weights, o.boost);
  m.threshold = chooseThreshold(outOfFold(s, contextNames, o.boost), s);
  if (o.log) o.log("context model: trained on " + std::to_string(s.labels.size()) + " points; threshold " + std::to_string(m.threshold));
  return m;
}

}  // namespace treesketch::eval
