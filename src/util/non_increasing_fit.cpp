// Isotonic regression by pooling adjacent violators (see non_increasing_fit.h).
#include "treesketch/util/non_increasing_fit.h"

#include <cstddef>

namespace treesketch::util {

void nonIncreasingFit(std::vector<double>& values, const std::vector<double>& weights) {
  struct Block {
    double mean, weight;
    std::size_t count;
  };
  std::vector<Block> blocks;
  for (std::size_t k = 0; k < values.size(); ++k) {
    blocks.push_back({values[k], weights[k], 1});
    // Pool while a block is above the one before it (the sequence must not rise).
    while (blocks.size() > 1 && blocks.back().mean > blocks[blocks.size() - 2].mean) {
      const Block b = blocks.back();
      blocks.pop_back();
      Block& a = blocks.back();
      const double w = a.weight + b.weight;
      a.mean = (a.mean * a.weight + b.mean * b.weight) / w;
      a.weight = w;
      a.count += b.count;
    }
  }
  std::size_t k = 0;
  for (const Block& b : blocks)
    for (std::size_t j = 0; j < b.count; ++j) values[k++] = b.mean;
}

}  // namespace treesketch::util
