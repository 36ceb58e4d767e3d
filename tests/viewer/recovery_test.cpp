// Crash recovery of the viewer's autosave (src/viewer/recovery.cpp): one autosave per cloud file,
// offered back on the next start, never overwritten before the person's choice.
#include <gtest/gtest.h>

#include <cmath>

#include "test_support.h"
#include "treesketch/gen/random.h"
#include "treesketch/io/sketch_file.h"
#include "treesketch/viewer/viewer_state.h"

namespace treesketch::viewer {
namespace {

using geom::Vec2;
using geom::Vec3;
using Choice = ViewerState::RecoveryChoice;

geom::PointCloud trunk(int n = 3000) {
  gen::Rng rng(3);
  geom::PointCloud cloud;
  for (int i = 0; i < n; ++i) {
    double a = rng.uniform(0, 2 * M_PI);
    cloud.positions.emplace_back(0.2 * std::cos(a), rng.uniform(0, 4), 0.2 * std::sin(a));
  }
  return cloud;
}

/// A session on `file` (the cloud is the same whatever the name, for one `points`) with `clicks`
/// nodes up the trunk.
std::unique_ptr<ViewerState> session(const std::filesystem::path& file, int clicks, int points = 3000) {
  auto s = std::make_unique<ViewerState>();
  s->view().setViewport(geom::Viewport{0, 0, 800, 600});
  s->setTool(ViewerState::Tool::AddNodes);  // clicks add nodes (the default selects)
  EXPECT_TRUE(s->setCloud(trunk(points), geom::UpAxis::Y, file));
  for (int i = 1; i <= clicks; ++i) s->clickAt(s->view().camera().project(Vec3(0, 0.8 * i, 0)).head<2>());
  return s;
}

TEST(Recovery, EachCloudFileHasItsOwnAutosave) {
  test::TempDir dir;
  auto las = session(dir / "tree.las", 3);
  auto xyz = session(dir / "tree.xyz", 1);
  EXPECT_EQ(las->document().autosavePath(), dir / "tree.las.autosave.sketch.json");
  EXPECT_EQ(xyz->document().autosavePath(), dir / "tree.xyz.autosave.sketch.json");
  EXPECT_EQ(io::readSketch(las->document().autosavePath()).size(), 3u);
  EXPECT_EQ(io::readSketch(xyz->document().autosavePath()).size(), 1u);
}

TEST(Recovery, AnAutosaveIsOfferedAndNotOverwrittenBeforeTheChoice) {
  test::TempDir dir;
  { auto crashed = session(dir / "tree.las", 3); }  // no closeSession: as after kill -9
  auto s = session(dir / "tree.las", 0);
  ASSERT_TRUE(s->document().recoveryPending());
  EXPECT_EQ(s->document().recoveryNodes(), 3u);
  EXPECT_TRUE(s->sketch().empty());
  // The first click edits the view's sketch, but the autosave keeps the earlier work.
  s->clickAt(s->view().camera().project(Vec3(0, 1, 0)).head<2>());
  EXPECT_EQ(s->sketch().size(), 1u);
  EXPECT_EQ(io::readSketch(s->document().autosavePath()).size(), 3u);
  ASSERT_TRUE(s->resolveRecovery(Choice::Restore));
  EXPECT_FALSE(s->document().recoveryPending());
  EXPECT_EQ(s->sketch().size(), 3u);
  EXPECT_EQ(io::readSketch(s->document().autosavePath()).size(), 3u);
  ASSERT_TRUE(s->undo());  // the restore is one undoable edit
  EXPECT_EQ(s->sketch().size(), 1u);
  EXPECT_FALSE(s->resolveRecovery(Choice::Restore));  // nothing pending any more
}

TEST(Recovery, AnAutosaveOfAnotherCloudIsNotOfferedAndIsKept) {
  test::TempDir dir;
  { auto crashed = session(dir / "tree.las", 3); }  // its autosave records the 3000-point cloud
  // Another cloud under the same name (the file was replaced): the autosave is not its work.
  auto s = session(dir / "tree.las", 0, 2500);
  EXPECT_FALSE(s->document().recoveryPending());
  EXPECT_EQ(s->document().recoveryNodes(), 0u);
  EXPECT_NE(s->status().lastMessage().text.find("not for this cloud"), std::string::npos)
      << s->status().lastMessage().text;
  // Kept aside under a name of its own, whole; this cloud's edits autosave to the usual name.
  std::vector<std::filesystem::path> kept;
  for (const auto& e : std::filesystem::directory_iterator(dir.path()))
    if (e.path().filename().string().find(".kept-") != std::string::npos) kept.push_back(e.path());
  ASSERT_EQ(kept.size(), 1u);
  EXPECT_EQ(io::readSketch(kept[0]).size(), 3u);
  s->clickAt(s->view().camera().project(Vec3(0, 1, 0)).head<2>());
  EXPECT_EQ(io::readSketch(s->document().autosavePath()).size(), 1u);
  EXPECT_EQ(io::readSketch(kept[0]).size(), 3u);
  // The same cloud again is offered its own autosave.
  auto again = session(dir / "tree.las", 0, 2500);
  EXPECT_TRUE(again->document().recoveryPending());
  EXPECT_EQ(again->document().recoveryNodes(), 1u);
}

TEST(Recovery, DiscardDeletesAndKeepRenames) {
  test::TempDir dir;
  { auto crashed = session(dir / "a.xyz", 2); }
  auto s = session(dir / "a.xyz", 0);
  ASSERT_TRUE(s->document().recoveryPending());
  ASSERT_TRUE(s->resolveRecovery(Choice::Discard));
  EXPECT_FALSE(std::filesystem::exists(s->document().autosavePath()));

  { auto crashed = session(dir / "b.xyz", 2); }
  auto k = session(dir / "b.xyz", 0);
  ASSERT_TRUE(k->resolveRecovery(Choice::Keep));
  int kept = 0;
  for (const auto& e : std::filesystem::directory_iterator(dir.path())) {
    std::string name = e.path().filename().string();
    if (name.rfind("b.xyz.autosave.kept-", 0) == 0) {
      ++kept;
      EXPECT_EQ(io::readSketch(e.path()).size(), 2u) << name;
    }
  }
  EXPECT_EQ(kept, 1);
  k->clickAt(k->view().camera().project(Vec3(0, 1, 0)).head<2>());  // autosave works again
  EXPECT_EQ(io::readSketch(k->document().autosavePath()).size(), 1u);
}

TEST(Recovery, AnUnreadableAutosaveIsReportedAndCanBeDiscarded) {
  test::TempDir dir;
  test::writeText(dir / "c.xyz.autosave.sketch.json", "{ not json");
  auto s = session(dir / "c.xyz", 0);
  ASSERT_TRUE(s->document().recoveryPending());
  EXPECT_FALSE(s->document().recoveryError().empty());
  EXPECT_TRUE(s->status().lastMessage().error);
  EXPECT_FALSE(s->resolveRecovery(Choice::Restore));
  EXPECT_TRUE(s->document().recoveryPending());
  EXPECT_TRUE(s->resolveRecovery(Choice::Discard));
}

TEST(Recovery, ACleanCloseDropsTheAutosaveOnlyWhenNothingIsUnsaved) {
  test::TempDir dir;
  {
    auto s = session(dir / "d.xyz", 2);
    EXPECT_TRUE(s->hasUnsavedChanges());
    s->closeSession();
    EXPECT_TRUE(std::filesystem::exists(s->document().autosavePath()));  // unsaved: offered next time
  }
  auto s = session(dir / "d.xyz", 0);
  ASSERT_TRUE(s->resolveRecovery(Choice::Restore));
  ASSERT_TRUE(s->saveSketch(dir / "mine.json"));
  EXPECT_FALSE(s->hasUnsavedChanges());
  s->closeSession();
  EXPECT_FALSE(std::filesystem::exists(s->document().autosavePath()));
}

}  // namespace
}  // namespace treesketch::viewer
