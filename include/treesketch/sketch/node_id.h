// The id of a sketch node, on its own so that modules which only name nodes (the sweep's tube
// mesh) need not include the whole sketch model (sketch.h includes this).
#pragma once

#include <cstdint>

namespace treesketch::sketch {

/// A node's id within its sketch (>= 0).
using NodeId = std::int32_t;
/// "No node" (the root's parent, an empty selection).
constexpr NodeId kNoNode = -1;

}  // namespace treesketch::sketch
