// The least-squares non-increasing sequence to a weighted sequence of values (isotonic regression
// by pooling adjacent violators, Ayer et al. 1955): a branch's taper, shared by the automatic
// model's radius rules and a fitted sketch's inferred radii.
#pragma once

#include <vector>

namespace treesketch::util {

/// In place: the least-squares non-increasing sequence to `values` with `weights` (> 0, one per
/// value). Runs of values that rise are replaced by their weighted mean; an empty or one-value
/// sequence is left as it is.
void nonIncreasingFit(std::vector<double>& values, const std::vector<double>& weights);

}  // namespace treesketch::util
