// Internal: validation of SkeletonOptions, shared by the stages' public entry points.
#pragma once

#include "treesketch/skeleton/skeleton.h"

namespace treesketch::skeleton::detail {

/// Throws OptionsError naming the first out-of-range option.
void checkOptions(const SkeletonOptions& options);

}  // namespace treesketch::skeleton::detail
