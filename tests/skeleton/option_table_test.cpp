// The settings table: names bound to the right fields, ranges that hold the presets, refusals.
#include "treesketch/skeleton/option_table.h"

#include <gtest/gtest.h>

#include <set>
#include <string>

#include "treesketch/util/error.h"

namespace treesketch::skeleton {
namespace {

AutoSkeletonOptions leafOff() { return autoSkeletonPreset(Foliage::LeafOff); }

TEST(OptionTable, NamesAreUniqueAndEveryPresetValueIsInRange) {
  std::set<std::string> names;
  for (const SettingInfo& s : settingTable()) {
    EXPECT_TRUE(names.insert(s.name).second) << s.name;
    EXPECT_LE(s.min, s.max) << s.name;
    for (const Foliage f : {Foliage::LeafOff, Foliage::LeafOn}) {
      const double v = settingValue(autoSkeletonPreset(f), s.name);
      EXPECT_GE(v, s.min) << s.name;
      EXPECT_LE(v, s.max) << s.name;
    }
  }
  EXPECT_GE(settingTable().size(), 70u);
}

TEST(OptionTable, NamesReachTheirFields) {
  AutoSkeletonOptions o = leafOff();
  applySetting(o, "radii.medianWindow=3");
  applySetting(o, "skeleton.graph.maxGapVoxels=7.5");
  applySetting(o, "completion.enabled=off");
  applySetting(o, "radii.surfaceBound=FALSE");
  applySetting(o, "skeleton.trackStem=0");
  applySetting(o, "fit.circle.maxIterations=123");
  applySetting(o, "strays.linkSpacings=12");
  applySetting(o, "markedNoise.enabled=false");
  EXPECT_EQ(o.radii.medianWindow, 3);
  EXPECT_EQ(o.skeleton.graph.maxGapVoxels, 7.5);
  EXPECT_FALSE(o.completion.enabled);
  EXPECT_FALSE(o.radii.surfaceBound);
  EXPECT_FALSE(o.skeleton.trackStem);
  EXPECT_EQ(o.fit.circle.maxIterations, 123);
  EXPECT_EQ(o.strays.linkSpacings, 12.0);
  EXPECT_FALSE(o.markedNoise.enabled);
  EXPECT_TRUE(leafOff().markedNoise.enabled);
  // Untouched fields keep the preset's values.
  EXPECT_EQ(o.skeleton.radiusMedianWindow, leafOff().skeleton.radiusMedianWindow);
  EXPECT_EQ(settingValue(o, "radii.medianWindow"), 3.0);
}

// Writing each setting's own value back changes nothing, and each setter writes its own field
// only: a value moved within its range shows under its name and under no other.
TEST(OptionTable, EachSetterWritesItsOwnFieldOnly) {
  const AutoSkeletonOptions base = leafOff();
  for (const SettingInfo& s : settingTable()) {
    AutoSkeletonOptions o = base;
    const double v = settingValue(base, s.name);
    double moved = s.type == SettingType::Boolean ? 1.0 - v : (v + 1 <= s.max ? v + 1 : s.min);
    if (s.type == SettingType::Real && moved == v) moved = (s.min + s.max) / 2;
    char text[64];
    std::snprintf(text, sizeof text, "%s=%.17g", s.name.c_str(), moved);
    applySetting(o, text);
    EXPECT_EQ(settingValue(o, s.name), moved) << s.name;
    for (const SettingInfo& other : settingTable())
      if (other.name != s.name) EXPECT_EQ(settingValue(o, other.name), settingValue(base, other.name)) << s.name;
  }
}

TEST(OptionTable, RefusesUnknownNamesWithTheNearest) {
  AutoSkeletonOptions o = leafOff();
  try {
    applySetting(o, "radii.medianWindw=3");
    FAIL() << "no error";
  } catch (const OptionsError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("radii.medianWindw"), std::string::npos) << m;
    EXPECT_NE(m.find("nearest: radii.medianWindow"), std::string::npos) << m;
  }
  EXPECT_EQ(nearestSettingName("surfacebound"), "radii.surfaceBound");
  EXPECT_EQ(nearestSettingName("skeleton.trackstem"), "skeleton.trackStem");
}

TEST(OptionTable, RefusesBadValuesAndLeavesOptionsUnchanged) {
  const AutoSkeletonOptions base = leafOff();
  for (const char* bad :
       {"radii.medianWindow=0", "radii.medianWindow=2.5", "radii.medianWindow=", "radii.medianWindow", "=3",
        "skeleton.binWidthVoxels=nan", "skeleton.binWidthVoxels=inf", "skeleton.binWidthVoxels=2x",
        "radii.surfaceBound=maybe", "skeleton.graph.reach=4", "maxFitFlatFraction=1.5", "markedNoise.enabled=2",
        "markedNoise.enabled=noise", "markedNoise.enable=0"}) {
    AutoSkeletonOptions o = base;
    EXPECT_THROW(applySetting(o, bad), OptionsError) << bad;
    for (const SettingInfo& s : settingTable()) EXPECT_EQ(settingValue(o, s.name), settingValue(base, s.name)) << bad;
  }
  EXPECT_THROW(settingValue(base, "no.such"), OptionsError);
}

TEST(OptionTable, FormattedTableListsEveryNameWithItsValue) {
  AutoSkeletonOptions o = leafOff();
  applySetting(o, "radii.medianWindow=7");
  const std::string text = formatSettingTable(o);
  for (const SettingInfo& s : settingTable()) EXPECT_NE(text.find(s.name), std::string::npos) << s.name;
  const std::size_t line = text.find("radii.medianWindow");
  EXPECT_NE(text.substr(line, text.find('\n', line) - line).find("= 7"), std::string::npos);
}

}  // namespace
}  // namespace treesketch::skeleton
