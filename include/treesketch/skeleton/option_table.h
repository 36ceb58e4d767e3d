// The automatic model's settings by name: one table of the AutoSkeletonOptions fields a user may
// change (the dotted field path as the name, its type, its allowed range, one line on what it
// does), a parser for "NAME=VALUE" assignments that refuses unknown names (naming the nearest)
// and out-of-range values, and the table printed with a preset's values. The CLI's `--set` and
// the ablation script (scripts/ablation.py) go through it.
#pragma once

#include <string>
#include <vector>

#include "treesketch/skeleton/skeleton_sketch.h"

namespace treesketch::skeleton {

enum class SettingType { Real, Integer, Boolean };

/// One settable field of AutoSkeletonOptions.
struct SettingInfo {
  std::string name;  ///< the field's path, e.g. "radii.medianWindow", "skeleton.graph.maxGapVoxels"
  SettingType type = SettingType::Real;
  double min = 0;  ///< allowed range, inclusive (booleans: 0 and 1)
  double max = 0;
  std::string help;  ///< what the setting does, one line
};

/// Every settable field, in the order of the option structs. The seed and the ring size are not
/// in it (the CLI's --seed and --ring set them).
const std::vector<SettingInfo>& settingTable();

/// The value of setting `name` in `options`, as a number (booleans 0/1). Throws OptionsError for
/// an unknown name.
double settingValue(const AutoSkeletonOptions& options, const std::string& name);

/// Applies one assignment "NAME=VALUE" to `options`. Booleans take true/false, on/off, 1/0;
/// integers a whole number; reals any finite number. Throws OptionsError, naming the setting, when
/// the name is unknown (with the nearest known name), the value does not parse as its type or lies
/// outside its range. `options` is unchanged when it throws.
void applySetting(AutoSkeletonOptions& options, const std::string& assignment);

/// The known name closest to `name` (edit distance, case-insensitive; "" when the table is empty).
std::string nearestSettingName(const std::string& name);

/// A value as the table prints it: true/false for booleans, else the number (6 significant digits).
std::string formatSettingValue(const SettingInfo& setting, double value);

/// The table as text: one line per setting with its type, range, the value in `options` and its
/// help line.
std::string formatSettingTable(const AutoSkeletonOptions& options);

}  // namespace treesketch::skeleton
