#include "treesketch/viewer/action_script.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>
#include <sstream>

#include "cli/cli_support.h"
#include "test_support.h"
#include "treesketch/gen/random.h"
#include "treesketch/io/point_cloud_io.h"
#include "treesketch/util/error.h"

namespace treesketch::viewer {
namespace {

using geom::Vec2;
using geom::Vec3;
using Kind = ScriptAction::Kind;

ActionScript parse(const std::string& text) {
  std::istringstream in(text);
  return parseActionScript(in, "script.json");
}

std::string parseError(const std::string& text) {
  try {
    parse(text);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(ActionScript, ParsesObjectsAndStrings) {
  ActionScript s = parse(R"({"window": [640, 480], "actions": [
    {"click": [10, 20.5], "button": "right", "mods": "shift+ctrl"},
    {"drag": [[1, 2], [3, 4]], "steps": 3},
    {"scroll": -2}, {"key": "ctrl+z"}, {"slider": "lineEpsilon", "value": 0.3},
    {"option": "showRegion", "value": false}, {"view": "top"}, {"select": 2}, {"button": "autoSketch"},
    {"save": null}, {"export": "m.ply"}, "screenshot shot.png", "undo", "wait 2",
    {"expect": {"nodes": 3, "fitted": 2}}]})");
  EXPECT_EQ(s.windowWidth, 640);
  EXPECT_EQ(s.windowHeight, 480);
  ASSERT_EQ(s.actions.size(), 15u);
  EXPECT_EQ(s.actions[0].kind, Kind::Click);
  EXPECT_EQ(s.actions[0].from, Vec2(10, 20.5));
  EXPECT_EQ(s.actions[0].button, MouseButton::Right);
  EXPECT_EQ(s.actions[0].mods, kModShift | kModCtrl);
  EXPECT_EQ(s.actions[1].kind, Kind::Drag);
  EXPECT_EQ(s.actions[1].to, Vec2(3, 4));
  EXPECT_EQ(s.actions[1].steps, 3);
  EXPECT_EQ(s.actions[2].value, -2);
  EXPECT_EQ(s.actions[3].name, "ctrl+z");
  EXPECT_EQ(s.actions[4].kind, Kind::Slider);
  EXPECT_EQ(s.actions[5].text, "false");
  EXPECT_EQ(s.actions[6].name, "top");
  EXPECT_EQ(s.actions[7].value, 2);
  EXPECT_EQ(s.actions[8].kind, Kind::Button);
  EXPECT_EQ(s.actions[9].kind, Kind::Save);
  EXPECT_TRUE(s.actions[9].path.empty());
  EXPECT_EQ(s.actions[10].path, "m.ply");
  EXPECT_EQ(s.actions[11].kind, Kind::Screenshot);
  EXPECT_EQ(s.actions[11].path, "shot.png");
  EXPECT_EQ(s.actions[12].name, "undo");
  EXPECT_EQ(s.actions[13].steps, 2);
  ASSERT_EQ(s.actions[14].expect.size(), 2u);
  EXPECT_EQ(describe(s.actions[0]), "click (10, 20.5) right");
  EXPECT_TRUE(parse("[]").actions.empty());
}

TEST(ActionScript, RejectsBadScriptsWithPositions) {
  EXPECT_NE(parseError("[{\"click\": [1, 2]").find("script.json"), std::string::npos);
  EXPECT_NE(parseError("[{\"click\": [1, 2]").find("offset"), std::string::npos);
  EXPECT_NE(parseError(R"([{"click": [1]}])").find("action 0"), std::string::npos);
  EXPECT_NE(parseError(R"(["undo", {"click": ["a", 2]}])").find("action 1"), std::string::npos);
  EXPECT_NE(parseError(R"([{"fly": 1}])").find("unknown action"), std::string::npos);
  EXPECT_NE(parseError(R"([{"click": [1, 2], "button": "fourth"}])").find("button"), std::string::npos);
  EXPECT_NE(parseError(R"([{"click": [1, 2], "mods": "hyper"}])").find("modifier"), std::string::npos);
  EXPECT_NE(parseError(R"([{"slider": "speed", "value": 1}])").find("slider"), std::string::npos);
  EXPECT_NE(parseError(R"([{"slider": "lineEpsilon"}])").find("value"), std::string::npos);
  EXPECT_NE(parseError(R"([{"view": "back"}])").find("view"), std::string::npos);
  EXPECT_NE(parseError(R"(["screenshot"])").find("PATH"), std::string::npos);
  EXPECT_NE(parseError(R"({"window": [0, 10], "actions": []})").find("window"), std::string::npos);
  EXPECT_NE(parseError(R"({"window": [10, 10]})").find("actions"), std::string::npos);
  EXPECT_NE(parseError("42").find("list"), std::string::npos);
  EXPECT_NE(parseError(R"([{"expect": {"colour": 1}}])").find("unknown key"), std::string::npos);
  test::TempDir dir;
  EXPECT_THROW(parseActionScript(dir / "missing.json"), InputError);
}

geom::PointCloud trunk() {
  gen::Rng rng(3);
  geom::PointCloud cloud;
  for (int i = 0; i < 8000; ++i) {
    double a = rng.uniform(0, 2 * M_PI);
    cloud.positions.emplace_back(0.2 * std::cos(a), rng.uniform(0, 4), 0.2 * std::sin(a));
  }
  return cloud;
}

TEST(ActionScript, RunsASessionAndReportsFailures) {
  test::TempDir dir;
  ViewerState state;
  state.view().setViewport(geom::Viewport{0, 0, 800, 600});
  ASSERT_TRUE(state.setCloud(trunk(), geom::UpAxis::Y));
  state.setTool(ViewerState::Tool::AddNodes);  // clicks add nodes (the default selects)
  Vec2 a = state.view().camera().project(Vec3(0, 1.5, 0)).head<2>();
  Vec2 b = state.view().camera().project(Vec3(0, 2.5, 0)).head<2>();
  std::ostringstream text;
  text << "[{\"click\": [" << a.x() << ", " << a.y() << "]}, {\"click\": [" << b.x() << ", " << b.y() << "]},"
       << R"({"expect": {"nodes": 2, "fitted": 2, "active": 1}}, "save", "export )" << (dir / "m.obj").string()
       << R"(", "screenshot )" << (dir / "s.png").string() << R"(", {"expect": {"nodes": 5}}, {"key": "q"},)"
       << R"("export )" << (dir / "m.txt").string() << R"(", "undo", {"expect": {"nodes": 1}}])";
  ActionScript script = parse(text.str());
  int frames = 0;
  std::vector<std::string> shots;
  ScriptHooks hooks;
  hooks.frame = [&] { ++frames; };
  hooks.screenshot = [&](const std::filesystem::path& p) { shots.push_back(p.string()); };
  hooks.sketchPath = dir / "s.json";
  ScriptReport report = runActionScript(state, script, hooks);
  EXPECT_EQ(report.actionsRun, script.actions.size());
  ASSERT_EQ(report.failures.size(), 3u);  // expect nodes 5, key q, export .txt
  EXPECT_NE(report.failures[0].find("action 6"), std::string::npos);
  EXPECT_NE(report.failures[0].find("nodes: expected 5, got 2"), std::string::npos);
  EXPECT_NE(report.failures[1].find("'q'"), std::string::npos);
  EXPECT_NE(report.failures[2].find("action 8"), std::string::npos);
  EXPECT_TRUE(std::filesystem::exists(dir / "s.json"));
  EXPECT_TRUE(std::filesystem::exists(dir / "m.obj"));
  ASSERT_EQ(shots.size(), 1u);
  EXPECT_EQ(shots[0], (dir / "s.png").string());
  EXPECT_GE(frames, static_cast<int>(script.actions.size()));
  EXPECT_EQ(state.sketch().size(), 1u);
}

// A sketch drawn in the desktop tool gives the same model files as the command line makes of the
// saved sketch: one model, one writer.
TEST(ActionScript, TheModelsOutputsAreTheCommandLines) {
  test::TempDir dir;
  const auto p = [&](const char* name) { return (dir / name).string(); };
  io::writePointCloud(dir / "trunk.xyz", trunk());
  ViewerState state;
  state.view().setViewport(geom::Viewport{0, 0, 800, 600});
  ASSERT_TRUE(state.setCloud(io::readPointCloud(dir / "trunk.xyz"), geom::UpAxis::Y));
  state.setTool(ViewerState::Tool::AddNodes);  // clicks add nodes (the default selects)
  std::ostringstream text;
  text << "[";
  for (double y : {0.5, 1.5, 2.5, 3.5}) {
    const Vec2 at = state.view().camera().project(Vec3(0, y, 0)).head<2>();
    text << "{\"click\": [" << at.x() << ", " << at.y() << "]}, ";
  }
  text << R"({"expect": {"nodes": 4, "fitted": 4}}, "save", )"
       << "\"export-cylinders " << p("gui.csv") << "\", \"export-qsm " << p("gui.txt") << "\", \"export-metrics "
       << p("gui_metrics.json") << "\", \"export-report " << p("gui_report.json") << "\"]";
  ScriptHooks hooks;
  hooks.sketchPath = dir / "s.json";
  const ScriptReport report = runActionScript(state, parse(text.str()), hooks);
  ASSERT_TRUE(report.failures.empty()) << report.failures.front();
  std::string out;
  ASSERT_EQ(test::runCommand(test::quoted(TS_CLI_PATH) + " reconstruct " + test::quoted(dir / "trunk.xyz") +
                                 " --sketch " + test::quoted(dir / "s.json") + " -o " + test::quoted(dir / "m.obj") +
                                 " --cylinders " + p("cli.csv") + " --qsm " + p("cli.txt") + " --metrics " +
                                 p("cli_metrics.json") + " --report " + p("cli_report.json"),
                             &out),
            0)
      << out;
  const std::string table = test::readText(dir / "gui.csv");
  EXPECT_EQ(table, test::readText(dir / "cli.csv"));
  EXPECT_EQ(std::count(table.begin(), table.end(), '\n'), 4);  // the header and three cylinders
  EXPECT_EQ(test::readText(dir / "gui.txt"), test::readText(dir / "cli.txt"));
  EXPECT_EQ(test::readText(dir / "gui_metrics.json"), test::readText(dir / "cli_metrics.json"));
  const auto gui = nlohmann::json::parse(test::readText(dir / "gui_report.json"));
  const auto cli = nlohmann::json::parse(test::readText(dir / "cli_report.json"));
  EXPECT_EQ(gui["model"], cli["model"]);
  EXPECT_EQ(gui["metrics"], cli["metrics"]);
  // Nothing to export before a node is fitted: an error, no file.
  ViewerState empty;
  EXPECT_FALSE(empty.exportModel(ViewerState::ModelFile::Cylinders, dir / "none.csv"));
  EXPECT_FALSE(std::filesystem::exists(dir / "none.csv"));
}

TEST(ActionScript, RefitButtonsDropKeptCircles) {
  ViewerState state;
  state.view().setViewport(geom::Viewport{0, 0, 800, 600});
  ASSERT_TRUE(state.setCloud(trunk(), geom::UpAxis::Y));
  state.setTool(ViewerState::Tool::AddNodes);  // clicks add nodes (the default selects)
  ScriptReport report = runActionScript(state, parse(R"(["autoSkeleton"])"));
  EXPECT_TRUE(report.failures.empty());
  const std::size_t kept = state.sketch().keptCircleCount();
  ASSERT_GE(kept, 2u);
  ASSERT_TRUE(state.sketch().node(0).kept.has_value());  // every node is the model's circle
  report = runActionScript(state, parse(R"([{"select": 0}, "refit"])"));
  EXPECT_TRUE(report.failures.empty());
  EXPECT_FALSE(state.sketch().node(0).kept.has_value());
  EXPECT_EQ(state.sketch().keptCircleCount(), kept - 1);
  report = runActionScript(state, parse(R"([{"button": "refitAll"}, {"expect": {"kept": 0}}, "undo"])"));
  EXPECT_TRUE(report.failures.empty());
  EXPECT_EQ(state.sketch().keptCircleCount(), kept - 1);
  report = runActionScript(state, parse(R"([{"expect": {"kept": 0}}])"));  // the check can fail
  ASSERT_EQ(report.failures.size(), 1u);
  EXPECT_NE(report.failures[0].find("kept"), std::string::npos);
}

TEST(ActionScript, ScreenshotWithoutAWindowFails) {
  ViewerState state;
  ScriptReport report = runActionScript(state, parse(R"(["screenshot a.png", "save"])"));
  ASSERT_EQ(report.failures.size(), 2u);
  EXPECT_NE(report.failures[0].find("window"), std::string::npos);
  EXPECT_NE(report.failures[1].find("sketch path"), std::string::npos);
}

}  // namespace
}  // namespace treesketch::viewer
