// The one table of keys (viewer::keyBindings) is what ViewerState::keyPress binds and what the
// key table of docs/gui.md lists, row for row.
#include "treesketch/viewer/key_bindings.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <set>
#include <sstream>

#include "treesketch/viewer/viewer_state.h"

namespace treesketch::viewer {
namespace {

/// The docs/gui.md row for a binding (what its key table must contain).
std::string readmeRow(const KeyBinding& k) { return "| " + k.keys + " | " + k.action + " |"; }

TEST(KeyBindings, EveryKeyInTheTableIsBound) {
  ViewerState s;
  s.view().setViewport(geom::Viewport{0, 0, 800, 600});
  geom::PointCloud cloud;
  for (int i = 0; i < 500; ++i) cloud.positions.emplace_back(0.1 * std::cos(i), 0.01 * i, 0.1 * std::sin(i));
  ASSERT_TRUE(s.setCloud(cloud, geom::UpAxis::Y));
  std::set<std::string> keys;
  for (const KeyBinding& k : keyBindings()) {
    EXPECT_FALSE(k.keys.empty());
    EXPECT_FALSE(k.action.empty());
    EXPECT_TRUE(keys.insert(k.keys).second) << "listed twice: " << k.keys;
    if (!k.keyName.empty()) EXPECT_TRUE(s.keyPress(k.keyName)) << k.keys << " (" << k.keyName << ") is not bound";
  }
  EXPECT_FALSE(s.keyPress("q"));  // the check can fail: an unbound key
}

TEST(KeyBindings, TheReadmeListsEveryRowOfTheTable) {
  // TS_TEST_DATA_DIR is <source>/tests/data (the folder may not exist): the docs are two up.
  std::string data = TS_TEST_DATA_DIR;
  const std::string suffix = "/tests/data";
  ASSERT_EQ(data.compare(data.size() - suffix.size(), suffix.size(), suffix), 0) << data;
  std::ifstream in(data.substr(0, data.size() - suffix.size()) + "/docs/gui.md");
  ASSERT_TRUE(in) << "docs/gui.md not found";
  std::stringstream text;
  text << in.rdbuf();
  for (const KeyBinding& k : keyBindings())
    EXPECT_NE(text.str().find(readmeRow(k)), std::string::npos) << "docs/gui.md lacks the row\n" << readmeRow(k);
}

}  // namespace
}  // namespace treesketch::viewer
