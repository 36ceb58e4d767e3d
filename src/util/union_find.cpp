#include "treesketch/util/union_find.h"

namespace treesketch::util {

// Depth-first from each unlabelled vertex in increasing order, so a component's label is the
// number of components whose lowest vertex comes before its own.
std::vector<std::int32_t> labelComponents(const std::vector<std::uint32_t>& offsets,
                                          const std::vector<std::uint32_t>& targets, std::int32_t* count) {
  const std::size_t n = offsets.empty() ? 0 : offsets.size() - 1;
  std::vector<std::int32_t> label(n, -1);
  std::int32_t next = 0;
  std::vector<std::uint32_t> stack;
  for (std::size_t s = 0; s < n; ++s) {
    if (label[s] >= 0) continue;
    label[s] = next;
    stack.assign(1, static_cast<std::uint32_t>(s));
    while (!stack.empty()) {
      const std::uint32_t v = stack.back();
      stack.pop_back();
      for (std::uint32_t k = offsets[v]; k < offsets[v + 1]; ++k)
        if (label[targets[k]] < 0) {
          label[targets[k]] = next;
          stack.push_back(targets[k]);
        }
    }
    ++next;
  }
  if (count) *count = next;
  return label;
}

}  // namespace treesketch::util
