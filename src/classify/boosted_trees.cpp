// Gradient-boosted trees on quantile-binned features (classify/boosted_trees.h).
#include "treesketch/classify/boosted_trees.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>

#include "treesketch/util/error.h"

namespace treesketch::classify {

double BoostedTrees::logit(const float* row) const {
  double s = bias;
  for (const auto& tree : trees) {
    std::int32_t n = 0;
    while (tree[n].feature >= 0) n = row[tree[n].feature] <= tree[n].threshold ? tree[n].left : tree[n].right;
    s += tree[n].value;
  }
  return s;
}

double BoostedTrees::probability(const float* row) const { return 1.0 / (1.0 + std::exp(-logit(row))); }

namespace {

struct Binned {
  int features = 0;
  std::size_t rows = 0;
  std::vector<std::vector<float>> edges;  ///< per feature, increasing; bin b holds edges[b-1] < x <= edges[b]
  std::vector<std::uint8_t> bins;         ///< feature-major: bins[f * rows + i]
};

Binned binFeatures(const std::vector<float>& rows, int features, int binCount) {
  Binned b;
  b.features = features;
  b.rows = rows.size() / features;
  b.edges.resize(features);
  b.bins.resize(b.rows * features);
  tbb::parallel_for(0, features, [&](int f) {
    std::vector<float> v;
    const std::size_t step = std::max<std::size_t>(1, b.rows / 50000);
    for (std::size_t i = 0; i < b.rows; i += step) v.push_back(rows[i * features + f]);
    std::sort(v.begin(), v.end());
    std::vector<float>& e = b.edges[f];
    for (int q = 1; q < binCount; ++q) {
      const float x = v[std::min(v.size() - 1, v.size() * q / binCount)];
      if (e.empty() || x > e.back()) e.push_back(x);
    }
    for (std::size_t i = 0; i < b.rows; ++i) {
      const float x = rows[i * features + f];
      b.bins[f * b.rows + i] = static_cast<std::uint8_t>(std::lower_bound(e.begin(), e.end(), x) - e.begin());
    }
  });
  return b;
}

struct Split {
  double gain = 0;
  int feature = -1;
  int bin = -1;
};

/// The best split of the rows `idx` by the gradient histograms of every feature.
Split bestSplit(const Binned& b, const std::vector<std::uint32_t>& idx, const std::vector<double>& g,
                const std::vector<double>& h, const BoostOptions& o) {
  std::vector<Split> per(b.features);
  tbb::parallel_for(0, b.features, [&](int f) {
    const int nb = static_cast<int>(b.edges[f].size()) + 1;
    std::vector<double> hg(nb, 0.0), hh(nb, 0.0);
    const std::uint8_t* col = b.bins.data() + f * b.rows;
    for (std::uint32_t i : idx) {
      hg[col[i]] += g[i];
      hh[col[i]] += h[i];
    }
    double G = 0, H = 0;
    for (int k = 0; k < nb; ++k) G += hg[k], H += hh[k];
    const double parent = G * G / (H + o.l2);
    double gl = 0, hl = 0;
    for (int k = 0; k + 1 < nb; ++k) {
      gl += hg[k];
      hl += hh[k];
      const double gr = G - gl, hr = H - hl;
      if (hl < o.minHessian || hr < o.minHessian) continue;
      const double gain = gl * gl / (hl + o.l2) + gr * gr / (hr + o.l2) - parent;
      if (gain > per[f].gain) per[f] = {gain, f, k};
    }
  });
  Split best;
  for (const auto& s : per)
    if (s.gain > best.gain) best = s;
  return best;
}

/// Grows one tree on the rows `idx` at depth `depth`, appending its nodes to `tree`; returns the
/// node's index. Leaves add their value to `logits`.
std::int32_t grow(const Binned& b, std::vector<std::uint32_t> idx, int depth, const std::vector<double>& g,
                  const std::vector<double>& h, const BoostOptions& o, std::vector<TreeNode>& tree,
                  std::vector<double>& logits) {
  const std::int32_t id = static_cast<std::int32_t>(tree.size());
  tree.emplace_back();
  const Split s = depth < o.depth ? bestSplit(b, idx, g, h, o) : Split{};
  if (s.feature < 0) {
    double G = 0, H = 0;
    for (std::uint32_t i : idx) G += g[i], H += h[i];
    const double v = -G / (H + o.l2) * o.learningRate;
    tree[id].value = static_cast<float>(v);
    for (std::uint32_t i : idx) logits[i] += v;
    return id;
  }
  std::vector<std::uint32_t> left, right;
  const std::uint8_t* col = b.bins.data() + s.feature * b.rows;
  for (std::uint32_t i : idx) (col[i] <= s.bin ? left : right).push_back(i);
  idx.clear();
  idx.shrink_to_fit();
  tree[id].feature = s.feature;
  tree[id].threshold = b.edges[s.feature][s.bin];
  const std::int32_t l = grow(b, std::move(left), depth + 1, g, h, o, tree, logits);
  const std::int32_t r = grow(b, std::move(right), depth + 1, g, h, o, tree, logits);
  tree[id].left = l;
  tree[id].right = r;
  return id;
}

}  // namespace

BoostedTrees trainBoostedTrees(const std::vector<float>& rows, const std::vector<std::string>& names,
                               const std::vector<std::uint8_t>& labels, const std::vector<float>& weights,
                               const BoostOptions& o) {
  const int f = static_cast<int>(names.size());
  if (f == 0 || labels.empty() || rows.size() != labels.size() * f ||
      (!weights.empty() && weights.size() != labels.size()))
    throw OptionsError("classify training: rows, labels and weights do not match");
  if (o.bins < 2 || o.bins > 255 || o.depth < 1 || o.rounds < 1 || !(o.learningRate > 0))
    throw OptionsError("classify training: bins must be 2..255, depth, rounds and rate positive");
  const std::size_t n = labels.size();
  double wPos = 0, wAll = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const double w = weights.empty() ? 1.0 : weights[i];
    wAll += w;
    if (labels[i]) wPos += w;
  }
  if (wPos <= 0 || wPos >= wAll) throw OptionsError("classify training: the labels hold only one class");
  BoostedTrees model;
  model.featureNames = names;
  model.bias = std::log(wPos / (wAll - wPos));
  const Binned b = binFeatures(rows, f, o.bins);
  std::vector<double> logits(n, model.bias), g(n), h(n);
  std::vector<std::uint32_t> all(n);
  for (std::size_t i = 0; i < n; ++i) all[i] = static_cast<std::uint32_t>(i);
  for (int round = 0; round < o.rounds; ++round) {
    for (std::size_t i = 0; i < n; ++i) {
      const double p = 1.0 / (1.0 + std::exp(-logits[i])), w = weights.empty() ? 1.0 : weights[i];
      g[i] = w * (p - labels[i]);
      h[i] = w * std::max(p * (1 - p), 1e-6);
    }
    std::vector<TreeNode> tree;
    grow(b, all, 0, g, h, o, tree, logits);
    model.trees.push_back(std::move(tree));
  }
  return model;
}

std::string toJson(const BoostedTrees& m) {
  nlohmann::json j;
  j["format"] = "treesketch boosted trees 1";
  j["features"] = m.featureNames;
  j["bias"] = m.bias;
  j["threshold"] = m.threshold;
  nlohmann::json trees = nlohmann::json::array();
  for (const auto& t : m.trees) {
    nlohmann::json nodes = nlohmann::json::array();
    for (const auto& n : t)
      nodes.push_back(n.feature < 0 ? nlohmann::json::array({n.value})
                                    : nlohmann::json::array({n.feature, n.threshold, n.left, n.right}));
    trees.push_back(nodes);
  }
  j["trees"] = trees;
  return j.dump() + "\n";
}

BoostedTrees boostedTreesFromJson(const std::string& text, const std::string& source) {
  BoostedTrees m;
  try {
    const nlohmann::json j = nlohmann::json::parse(text);
    m.featureNames = j.at("features").get<std::vector<std::string>>();
    m.bias = j.at("bias").get<double>();
    m.threshold = j.at("threshold").get<double>();
    const int f = static_cast<int>(m.featureNames.size());
    for (const auto& jt : j.at("trees")) {
      std::vector<TreeNode> t;
      for (const auto& jn : jt) {
        TreeNode n;
        if (jn.size() == 1) {
          n.value = jn.at(0).get<float>();
        } else {
          n.feature = jn.at(0).get<int>();
          n.threshold = jn.at(1).get<float>();
          n.left = jn.at(2).get<int>();
          n.right = jn.at(3).get<int>();
        }
        t.push_back(n);
      }
      const auto size = static_cast<std::int32_t>(t.size());
      for (std::int32_t k = 0; k < size; ++k) {
        const TreeNode& n = t[k];
        if (n.feature >= f || (n.feature >= 0 && (n.left <= k || n.right <= k || n.left >= size || n.right >= size)))
          throw InputError(source + ": tree " + std::to_string(m.trees.size()) + " node " + std::to_string(k) +
                           " points outside its tree or features");
      }
      if (t.empty()) throw InputError(source + ": an empty tree");
      m.trees.push_back(std::move(t));
    }
  } catch (const nlohmann::json::exception& e) {
    throw InputError(source + ": not a boosted-tree model (" + e.what() + ")");
  }
  return m;
}

}  // namespace treesketch::classify
