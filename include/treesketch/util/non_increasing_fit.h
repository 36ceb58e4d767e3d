// The least-absolute-deviations non-increasing sequence to a weighted sequence of values
// (isotonic regression by pooling adjacent violators, each pool at its members' weighted median):
// a branch's taper, shared by the automatic model's radius rules and a fitted sketch's inferred
// radii.
#pragma once

#include <vector>

namespace treesketch::util {

/// In place: the least-absolute-deviations non-increasing sequence to `values` with `weights`
/// (> 0, one per value). Runs of values that rise are replaced by their weighted median (the lower
/// one at a tie); an empty or one-value sequence is left as it is. The median, not the mean: a run
/// of thick fits just below a fork (a slice through the crotch holds both limbs) would raise the
/// whole trunk below it by their mean (a real tree's stem at 1.3 m from 13 to 17.6 cm); the median
/// moves only as far as the majority of the values, and one odd value is outvoted.
void nonIncreasingFit(std::vector<double>& values, const std::vector<double>& weights);

}  // namespace treesketch::util
