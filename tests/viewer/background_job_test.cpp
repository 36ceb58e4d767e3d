// The automatic skeleton on a worker thread (src/viewer/background_job.cpp): the state stays
// usable, progress is reported, Cancel leaves the sketch exactly as it was, the result is one
// undoable edit.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <sstream>
#include <thread>

#include "treesketch/gen/random.h"
#include "treesketch/io/sketch_file.h"
#include "treesketch/viewer/action_script.h"
#include "treesketch/viewer/viewer_state.h"
#include "forked_tree.h"

namespace treesketch::viewer {
namespace {

using geom::Vec3;

std::string text(const sketch::Sketch& s) {
  std::ostringstream out;
  io::writeSketch(out, s);
  return out.str();
}

struct Fixture {
  ViewerState state;
  Fixture() {
    state.view().setViewport(geom::Viewport{0, 0, 800, 600});
    EXPECT_TRUE(state.setCloud(test::forkedTree(), geom::UpAxis::Y));
    state.setTool(ViewerState::Tool::AddNodes);  // clicks add nodes (the default selects)
    for (int i = 1; i <= 3; ++i) state.clickAt(state.view().camera().project(Vec3(0, 0.8 * i, 0)).head<2>());
  }
};

TEST(BackgroundJob, CancelLeavesTheSketchAsItWasAndTheStateUsable) {
  Fixture f;
  const std::string before = text(f.state.sketch());
  const std::size_t undoBefore = f.state.history().undoCount();
  f.state.jobs().hold(true);
  ASSERT_TRUE(f.state.startAutoSkeletonJob());
  EXPECT_TRUE(f.state.jobs().busy());
  EXPECT_FALSE(f.state.pollJob());
  // The view moves; edits and a second job are refused with a message, not lost silently.
  f.state.dragTo(geom::Vec2(500, 300), geom::Vec2(540, 280), MouseButton::Right);
  const std::size_t errors = f.state.status().errorCount();
  EXPECT_FALSE(f.state.addNodeAt(geom::Vec2(400, 300)));
  EXPECT_FALSE(f.state.startAutoSkeletonJob());
  EXPECT_EQ(f.state.status().errorCount(), errors + 2);
  EXPECT_NE(f.state.status().lastMessage().text.find("busy"), std::string::npos);
  f.state.jobs().cancel();
  EXPECT_TRUE(f.state.jobs().progress().cancelling);
  f.state.waitForJob();
  EXPECT_FALSE(f.state.jobs().busy());
  EXPECT_EQ(text(f.state.sketch()), before);
  EXPECT_EQ(f.state.history().undoCount(), undoBefore);
  EXPECT_NE(f.state.status().lastMessage().text.find("cancelled"), std::string::npos);
}

TEST(BackgroundJob, TheResultIsOneUndoableEditAndProgressIsReported) {
  Fixture f;
  const std::size_t nodes = f.state.sketch().size();
  ASSERT_TRUE(f.state.startAutoSkeletonJob());
  double seen = 0.0;
  while (!f.state.pollJob()) {
    seen = std::max(seen, f.state.jobs().progress().fraction);
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  EXPECT_GT(seen, 0.0);
  EXPECT_FALSE(f.state.jobs().busy());
  EXPECT_GT(f.state.sketch().keptCircleCount(), 0u);
  EXPECT_FALSE(f.state.hasHandEdits());
  ASSERT_TRUE(f.state.undo());
  EXPECT_EQ(f.state.sketch().size(), nodes);
}

// The window's frame takes a finished job in itself (main.cpp calls pollJob every frame); a
// script's {"wait": "job"} must end then too, not wait for a result nobody will hand it again
// (it hung CI's gui.background_job when a frame happened to take the result first). Here the
// job is held until the wait's first frame, which lets it go and takes its result itself.
TEST(BackgroundJob, AScriptWaitEndsWhenAFrameTookTheResult) {
  Fixture f;
  std::istringstream text(
      R"([{"option": "holdJobs", "value": true}, {"start": "autoSkeleton"}, {"wait": "job"}, {"expect": {"busy": 0}}])");
  const ActionScript script = parseActionScript(text, "wait.json");
  ScriptHooks hooks;
  int frames = 0;
  bool took = false;
  hooks.frame = [&] {
    if (++frames < 3) return;  // after the option and the start; the third is the wait's
    f.state.jobs().hold(false);
    for (int i = 0; i < 6000 && f.state.jobs().busy(); ++i) {
      if (f.state.pollJob()) took = true;
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
  };
  const ScriptReport report = runActionScript(f.state, script, hooks);
  EXPECT_TRUE(report.failures.empty()) << report.failures.front();
  EXPECT_TRUE(took);
  EXPECT_FALSE(f.state.jobs().busy());
  EXPECT_GT(f.state.sketch().keptCircleCount(), 0u);
}

TEST(BackgroundJob, DestroyingTheStateStopsARunningJob) {
  auto s = std::make_unique<Fixture>();
  s->state.jobs().hold(true);
  ASSERT_TRUE(s->state.startAutoSkeletonJob());
  s.reset();  // must not hang or crash
  SUCCEED();
}

}  // namespace
}  // namespace treesketch::viewer
