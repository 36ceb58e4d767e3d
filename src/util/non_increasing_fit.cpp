// Isotonic regression by pooling adjacent violators at their weighted median (see
// non_increasing_fit.h).
#include "treesketch/util/non_increasing_fit.h"

#include <algorithm>
#include <cstddef>
#include <utility>

namespace treesketch::util {
namespace {

/// The weighted median of `members` (value, weight): the lower one at a tie.
double weightedMedian(std::vector<std::pair<double, double>> members) {
  std::sort(members.begin(), members.end());
  double total = 0;
  for (const auto& m : members) total += m.second;
  double acc = 0;
  for (const auto& m : members) {
    acc += m.second;
    if (acc >= 0.5 * total) return m.first;
  }
  return members.back().first;
}

}  // namespace

void nonIncreasingFit(std::vector<double>& values, const std::vector<double>& weights) {
  struct Block {
    double value;
    std::vector<std::pair<double, double>> members;
  };
  std::vector<Block> blocks;
  for (std::size_t k = 0; k < values.size(); ++k) {
    blocks.push_back({values[k], {{values[k], weights[k]}}});
    // Pool while a block is above the one before it (the sequence must not rise).
    while (blocks.size() > 1 && blocks.back().value > blocks[blocks.size() - 2].value) {
      Block b = std::move(blocks.back());
      blocks.pop_back();
      Block& a = blocks.back();
      a.members.insert(a.members.end(), b.members.begin(), b.members.end());
      a.value = weightedMedian(a.members);
    }
  }
  std::size_t k = 0;
  for (const Block& b : blocks)
    for (std::size_t j = 0; j < b.members.size(); ++j) values[k++] = b.value;
}

}  // namespace treesketch::util
