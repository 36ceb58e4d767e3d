// Internal: the checks of the automatic model's radius rules (RadiusRules), shared by the options'
// check and regularizeRadii (radius_rules.cpp).
#pragma once

#include "treesketch/skeleton/skeleton_sketch.h"

namespace treesketch::skeleton::detail {

/// Throws OptionsError naming the first rule out of its range.
void checkRadiusRules(const RadiusRules& rules);

}  // namespace treesketch::skeleton::detail
