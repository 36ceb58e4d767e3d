// The correction tools in the viewer: driven by `--script` verbs and by the mouse and
// keys, each one undoable.
#include <gtest/gtest.h>

#include <random>
#include <sstream>

#include "../fit/synthetic_cylinder.h"
#include "test_support.h"
#include "treesketch/io/sketch_file.h"
#include "treesketch/util/error.h"
#include "treesketch/viewer/action_script.h"
#include "treesketch/viewer/viewer_state.h"

namespace treesketch::viewer {
namespace {

using geom::Vec2;
using geom::Vec3;

const Vec3 kFork(0, 2, 0);
const Vec3 kDir = Vec3(1, 0.6, 0).normalized();

/// A trunk (Y axis, radius 0.2, y in [0, 4]) and a branch of radius 0.08 from (0, 2, 0).
geom::PointCloud tree() {
  std::mt19937_64 rng(5);
  geom::PointCloud c;
  test::addCylinder(c, {Vec3::Zero(), Vec3::UnitY(), 0.2, 4.0, 20000, 0.003}, rng);
  test::addCylinder(c, {kFork, kDir, 0.08, 1.6, 6000, 0.002}, rng);
  return c;
}

struct Fixture {
  ViewerState state;
  Fixture() {
    state.view().setViewport(geom::Viewport{0, 0, 1280, 800});
    EXPECT_TRUE(state.setCloud(tree(), geom::UpAxis::Y));
    state.setTool(ViewerState::Tool::AddNodes);  // clicks add nodes (the default selects)
  }
  Vec2 at(const Vec3& p) const { return state.view().camera().project(p).head<2>(); }
  std::string pt(const Vec3& p) const {
    Vec2 s = at(p);
    std::ostringstream o;
    o << "[" << s.x() << "," << s.y() << "]";
    return o.str();
  }
  ScriptReport run(const std::string& json) {
    std::istringstream in(json);
    return runActionScript(state, parseActionScript(in, "tools.json"));
  }
};

std::string joinReport(const ScriptReport& r) {
  std::string s;
  for (const auto& f : r.failures) s += f + "\n";
  return s;
}

TEST(ViewerTools, ScriptVerbsStrokeLassoReattachDeleteAndUndo) {
  Fixture f;
  // Three trunk clicks, then a stroke along the branch from the fork.
  std::string script = "[{\"click\":" + f.pt(Vec3(0, 1, 0)) + "},{\"click\":" + f.pt(Vec3(0, 2, 0)) +
                       "},{\"click\":" + f.pt(Vec3(0, 3, 0)) + "},{\"expect\":{\"nodes\":3}}," + "{\"stroke\":[" +
                       f.pt(kFork) + "," + f.pt(kFork + 0.7 * kDir) + "," + f.pt(kFork + 1.5 * kDir) + "]}]";
  ScriptReport r = f.run(script);
  ASSERT_TRUE(r.ok()) << joinReport(r);
  const sketch::Sketch& sk = f.state.sketch();
  ASSERT_GE(sk.size(), 5u);
  // The limb hangs under the trunk node nearest the stroke's start (node 1 at y = 2).
  const sketch::NodeId first = 3;
  EXPECT_EQ(sk.node(first).parent, 1);
  EXPECT_FALSE(sk.node(first).isScreenNode());
  int fitted = 0;
  for (const auto& [id, n] : sk.nodes())
    if (id >= first && f.state.scene().nodeFit(id).status == NodeStatus::Fitted) {
      ++fitted;
      EXPECT_NEAR(f.state.scene().nodeFit(id).circle.radius, 0.08, 0.03);
    }
  EXPECT_GE(fitted, int(sk.size()) - 4);
  const std::size_t withLimb = sk.size();

  // Re-attach the limb to the root, then undo; delete it as a subtree, then undo.
  r = f.run("[{\"reattach\":[3,0]}]");
  ASSERT_TRUE(r.ok()) << joinReport(r);
  EXPECT_EQ(f.state.sketch().node(3).parent, 0);
  r = f.run("[\"undo\",{\"deleteSubtree\":3},{\"expect\":{\"nodes\":3}},\"undo\"]");
  ASSERT_TRUE(r.ok()) << joinReport(r);
  EXPECT_EQ(f.state.sketch().size(), withLimb);
  EXPECT_EQ(f.state.sketch().node(3).parent, 1);
  // A cycle is refused with an error, and the sketch is kept.
  r = f.run("[{\"reattach\":[3,4]}]");
  EXPECT_FALSE(r.ok());
  EXPECT_EQ(f.state.sketch().node(3).parent, 1);

  // A lasso around the limb: its nodes lose their points; undo brings them back.
  const Vec2 a = f.at(kFork + 0.2 * kDir), b = f.at(kFork + 1.6 * kDir);
  std::ostringstream lasso;
  lasso << "[{\"lasso\":[[" << a.x() - 15 << "," << b.y() - 30 << "],[" << b.x() + 30 << "," << b.y() - 30 << "],["
        << b.x() + 30 << "," << a.y() + 15 << "],[" << a.x() - 15 << "," << a.y() + 15
        << "]]},{\"expect\":{\"notWood\":1}}]";
  r = f.run(lasso.str());
  ASSERT_TRUE(r.ok()) << joinReport(r);
  EXPECT_LT(f.state.scene().fittedCount(), std::size_t(3 + fitted));
  r = f.run("[\"undo\",{\"expect\":{\"notWood\":0}}]");
  ASSERT_TRUE(r.ok()) << joinReport(r);
  EXPECT_EQ(f.state.scene().fittedCount(), std::size_t(3 + fitted));
}

TEST(ViewerTools, LassoIsSavedWithTheSketch) {
  Fixture f;
  test::TempDir dir;
  ScriptReport r =
      f.run("[{\"click\":" + f.pt(Vec3(0, 1, 0)) + "},{\"lasso\":[[10,10],[200,10],[200,200]]},{\"save\":\"" +
            (dir / "s.json").string() + "\"}]");
  ASSERT_TRUE(r.ok()) << joinReport(r);
  EXPECT_EQ(io::readSketch(dir / "s.json").notWood().size(), 1u);
}

TEST(ViewerTools, MouseDragsUseTheChosenTool) {
  Fixture f;
  f.state.clickAt(f.at(Vec3(0, 1, 0)));
  f.state.clickAt(f.at(Vec3(0, 2, 0)));
  ASSERT_TRUE(f.state.keyPress("g"));
  EXPECT_EQ(f.state.tools().tool(), ViewerState::Tool::Stroke);
  f.state.dragTo(f.at(kFork), f.at(kFork + 1.5 * kDir), MouseButton::Left, kModNone, 12);
  EXPECT_GE(f.state.sketch().size(), 4u);
  EXPECT_TRUE(f.state.tools().toolPath().empty());
  EXPECT_TRUE(f.state.canUndo());
  // Re-attach tool: click the limb's first node, then the root.
  ASSERT_TRUE(f.state.keyPress("p"));
  f.state.selectNode(sketch::kNoNode);
  f.state.clickAt(f.at(f.state.scene().nodeFit(2).circle.centre));
  EXPECT_EQ(f.state.tools().selected(), 2);
  f.state.clickAt(f.at(f.state.scene().nodeFit(0).circle.centre));
  EXPECT_EQ(f.state.sketch().node(2).parent, 0);
  // Escape goes back to sketching; a drag with the lasso tool adds a lasso.
  f.state.keyPress("escape");
  EXPECT_EQ(f.state.tools().tool(), ViewerState::Tool::Select);
  f.state.keyPress("x");
  f.state.mouseDown(Vec2(10, 10), MouseButton::Left);
  f.state.mouseMove(Vec2(200, 10));
  f.state.mouseMove(Vec2(200, 200));
  f.state.mouseUp(Vec2(10, 200), MouseButton::Left);
  EXPECT_EQ(f.state.sketch().notWood().size(), 1u);
}

TEST(ViewerTools, NotWoodPointsAreDrawnDarkUntilTheLassoIsUndone) {
  Fixture f;
  auto darkCount = [&] {
    std::size_t n = 0;
    for (const Rgb& c : f.state.scene().pointColors()) n += c == Rgb{60, 50, 70};
    return n;
  };
  EXPECT_EQ(darkCount(), 0u);
  const Vec2 t = f.at(Vec3(0, 3.5, 0));
  ASSERT_TRUE(f.state.lassoNotWood({t + Vec2(-60, -60), t + Vec2(60, -60), t + Vec2(60, 60), t + Vec2(-60, 60)}));
  const std::size_t dark = darkCount();
  EXPECT_GT(dark, 100u);
  EXPECT_LT(dark, f.state.cloud().size() / 2);
  ASSERT_TRUE(f.state.undo());
  EXPECT_EQ(darkCount(), 0u);
}

TEST(ViewerTools, ScriptRejectsBadToolArguments) {
  auto bad = [](const std::string& json) {
    std::istringstream in(json);
    EXPECT_THROW(parseActionScript(in, "bad.json"), InputError) << json;
  };
  bad(R"([{"stroke":[[1,2]]}])");
  bad(R"([{"lasso":[[1,2],[3,4]]}])");
  bad(R"([{"reattach":[1]}])");
  bad(R"([{"tool":"pencil"}])");
  bad(R"([{"deleteSubtree":"x"}])");
}

}  // namespace
}  // namespace treesketch::viewer
