// The desktop tool's wood/leaf classification (src/viewer/wood_classes.cpp): a background job,
// the colourings and their legend, the lassos that correct the classes, the fits and the automatic
// skeleton on the wood that follow them.
#include <gtest/gtest.h>

#include <set>
#include <sstream>

#include "treesketch/classify/classify.h"
#include "treesketch/io/sketch_file.h"
#include "treesketch/util/error.h"
#include "treesketch/viewer/action_script.h"
#include "treesketch/viewer/color_legend.h"
#include "treesketch/viewer/demo_scene.h"
#include "treesketch/viewer/viewer_state.h"

namespace treesketch::viewer {
namespace {

using geom::Vec2;

/// The demo tree in leaf (a sphere scan of its wood and leaves), once for every test.
const geom::PointCloud& leafyTree() {
  static const geom::PointCloud cloud = demoTreeCloud();
  return cloud;
}

struct Fixture {
  ViewerState state;
  Fixture() {
    state.view().setViewport(geom::Viewport{0, 0, 800, 600});
    EXPECT_TRUE(state.setCloud(leafyTree(), geom::UpAxis::Y));
  }
  /// A polygon around the whole view.
  static std::vector<Vec2> wholeView() { return {Vec2(-5, -5), Vec2(805, -5), Vec2(805, 605), Vec2(-5, 605)}; }
  /// The upper half of the view.
  static std::vector<Vec2> upperHalf() { return {Vec2(-5, -5), Vec2(805, -5), Vec2(805, 300), Vec2(-5, 300)}; }
  void classify() {
    ASSERT_TRUE(state.startClassifyJob());
    EXPECT_TRUE(state.jobs().busy());
    state.waitForJob();
    ASSERT_NE(state.woodClasses(), nullptr) << state.status().lastMessage().text;
  }
  /// The sum of the fitted radii: changes when any fit does.
  double fittedRadii() const {
    double sum = 0;
    for (sketch::NodeId id : state.sketch().ids()) {
      const NodeFitView f = state.scene().nodeFit(id);
      if (f.status == NodeStatus::Fitted && !f.kept) sum += f.circle.radius;
    }
    return sum;
  }
};

TEST(WoodClasses, ClassifyIsABackgroundJobAndTheColouringShowsIt) {
  Fixture f;
  EXPECT_EQ(f.state.woodClasses(), nullptr);
  EXPECT_TRUE(f.state.woodAfterLassos().empty());
  const std::size_t n = f.state.cloud().size();
  EXPECT_FALSE(colorModeAvailable(ColorMode::WoodClass, f.state.cloud(), false));
  f.classify();
  const std::size_t wood = f.state.woodPointCount();
  EXPECT_GT(wood, n / 50);  // the stem and limbs at least
  EXPECT_LT(wood, n);       // the leaves are not wood
  EXPECT_EQ(f.state.woodClasses()->woodPoints, wood);
  // The two colourings are offered once classified, and C reaches them.
  const std::vector<ColorMode> modes = availableColorModes(f.state.cloud(), true);
  EXPECT_NE(std::find(modes.begin(), modes.end(), ColorMode::WoodClass), modes.end());
  EXPECT_EQ(nextColorMode(ColorMode::WoodProbability, f.state.cloud(), true), ColorMode::WoodClass);
  f.state.view().display().colorMode = ColorMode::WoodClass;
  const std::vector<Rgb>& colors = f.state.scene().pointColors();
  std::size_t brown = 0;
  for (const Rgb& c : colors) brown += c == woodClassColor(true);
  EXPECT_EQ(brown, wood);
  const Legend l = colorLegend(f.state);
  ASSERT_EQ(l.classes.size(), 2u);
  EXPECT_EQ(l.classes[0].count, wood);
  EXPECT_EQ(l.classes[1].count, n - wood);
  f.state.view().display().colorMode = ColorMode::WoodProbability;
  EXPECT_EQ(colorLegend(f.state).kind, Legend::Kind::Scale);
  std::set<std::uint32_t> shades;
  for (const Rgb& c : f.state.scene().pointColors()) shades.insert((c.r << 16) | (c.g << 8) | c.b);
  EXPECT_GT(shades.size(), 10u);  // a ramp, not two classes
  // Another cloud drops the classification.
  ASSERT_TRUE(f.state.setCloud(leafyTree(), geom::UpAxis::Y));
  EXPECT_EQ(f.state.woodClasses(), nullptr);
}

TEST(WoodClasses, LassosCorrectTheClassesAndAreUndoable) {
  Fixture f;
  f.classify();
  const std::size_t n = f.state.cloud().size(), wood = f.state.woodPointCount();
  ASSERT_TRUE(f.state.lassoWood(Fixture::wholeView()));
  EXPECT_EQ(f.state.sketch().woodLassoCount(), 1u);
  EXPECT_EQ(f.state.woodPointCount(), n);
  ASSERT_TRUE(f.state.lassoNotWood(Fixture::upperHalf()));  // drawn last: it decides there
  const std::size_t lower = f.state.woodPointCount();
  EXPECT_LT(lower, n);
  EXPECT_GT(lower, 0u);
  ASSERT_TRUE(f.state.undo());
  EXPECT_EQ(f.state.woodPointCount(), n);
  ASSERT_TRUE(f.state.undo());
  EXPECT_EQ(f.state.woodPointCount(), wood);
  // The wood lasso is saved in the sketch.
  ASSERT_TRUE(f.state.redo());
  std::ostringstream out;
  io::writeSketch(out, f.state.sketch());
  std::istringstream in(out.str());
  EXPECT_EQ(io::readSketch(in, "mem").woodLassoCount(), 1u);
}

// The automatic skeleton on the wood (leaf-off preset) differs from the leaf-on one on every
// point, and a re-run follows a lasso; a person's fits (the skeleton's nodes refitted from the
// cloud) change when the lassos change the classes.
TEST(WoodClasses, TheSkeletonAndTheFitsFollowTheCorrectedClasses) {
  Fixture f;
  ASSERT_TRUE(f.state.startAutoSkeletonJob(true));
  f.state.waitForJob();
  const std::size_t leafOnNodes = f.state.sketch().size();
  ASSERT_GT(leafOnNodes, 0u);
  // Not classified yet: the wood-only skeleton classifies first and keeps the classification.
  ASSERT_TRUE(f.state.startWoodSkeletonJob());
  f.state.waitForJob();
  ASSERT_NE(f.state.woodClasses(), nullptr) << f.state.status().lastMessage().text;
  const std::size_t woodNodes = f.state.sketch().size();
  ASSERT_GT(woodNodes, 0u);
  EXPECT_NE(woodNodes, leafOnNodes);
  EXPECT_EQ(f.state.history().undoCount(), 2u);
  // A person fits every node from the cloud: the fits use the wood.
  ASSERT_TRUE(f.state.refitAll());
  const double onWood = f.fittedRadii();
  EXPECT_GT(onWood, 0.0);
  // Every point wood: the fits see the leaves again and change.
  ASSERT_TRUE(f.state.lassoWood(Fixture::wholeView()));
  const double onEverything = f.fittedRadii();
  EXPECT_NE(onEverything, onWood);
  ASSERT_TRUE(f.state.undo());
  EXPECT_DOUBLE_EQ(f.fittedRadii(), onWood);
  // The upper half not wood: the skeleton run again has only the lower half to model.
  ASSERT_TRUE(f.state.lassoNotWood(Fixture::upperHalf()));
  ASSERT_TRUE(f.state.startWoodSkeletonJob());
  f.state.waitForJob();
  EXPECT_LT(f.state.sketch().size(), woodNodes);
  EXPECT_EQ(f.state.sketch().notWood().size(), 1u);  // the person's lasso stays
}

// "Automatic in region" models the wood once the cloud is classified: fewer points.
TEST(WoodClasses, AutomaticInRegionModelsTheWood) {
  Fixture f;
  auto regionPoints = [&] {
    const std::string text = f.state.status().lastMessage().text;  // "... (N points)"
    const std::size_t end = text.rfind(" points)");
    const std::size_t start = text.rfind(' ', end - 1);
    return end == std::string::npos ? std::size_t(0) : std::size_t(std::stoul(text.substr(start + 1, end - start - 1)));
  };
  ASSERT_TRUE(f.state.automaticInRegion(Fixture::wholeView()));
  const std::size_t every = regionPoints();
  EXPECT_GT(every, f.state.cloud().size() / 2);
  ASSERT_TRUE(f.state.undo());
  f.classify();
  ASSERT_TRUE(f.state.automaticInRegion(Fixture::wholeView()));
  const std::size_t wood = regionPoints();
  EXPECT_LT(wood, every);
  EXPECT_LE(wood, f.state.woodPointCount());
  EXPECT_GT(wood, 0u);
}

TEST(WoodClasses, ScriptVerbsAndKeys) {
  Fixture f;
  std::istringstream bad(R"([{"start": "bogus"}])");
  EXPECT_THROW(parseActionScript(bad, "wood.json"), InputError);  // refused when parsed, naming the file
  std::istringstream good(R"([{"expect": {"classified": 0}}, {"button": "classify"},
    {"expect": {"classified": 1, "woodPoints": 100, "busy": 0}},
    {"option": "colorMode", "value": "wood-class"}, {"expect": {"legend": 1}},
    {"lassoWood": [[-5, -5], [805, -5], [805, 605]]}, {"expect": {"woodLassos": 1, "notWood": 1}},
    {"tool": "lassoWood"}, {"start": "autoSkeletonWood"}, {"wait": "job"}, {"expect": {"meshTriangles": 1}}])");
  const ScriptReport r = runActionScript(f.state, parseActionScript(good, "wood.json"));
  std::string failures;
  for (const auto& s : r.failures) failures += s + "\n";
  EXPECT_TRUE(r.failures.empty()) << failures;
  EXPECT_EQ(f.state.tools().tool(), ViewerState::Tool::LassoWood);
  // A script changes the model: the skeleton's nodes fitted from the wood, then a wood
  // lasso over the whole view (every point wood again) and the fits move.
  auto run = [&](const std::string& json) {
    std::istringstream in(json);
    const ScriptReport report = runActionScript(f.state, parseActionScript(in, "wood.json"));
    EXPECT_TRUE(report.failures.empty()) << (report.failures.empty() ? "" : report.failures.front());
  };
  run(R"([{"button": "refitAll"}, {"expect": {"kept": 0}}])");
  const double onWood = f.fittedRadii();
  run(R"([{"lassoWood": [[-5, -5], [805, -5], [805, 605], [-5, 605]]}, {"expect": {"woodLassos": 2}}])");
  EXPECT_NE(f.fittedRadii(), onWood);
  // Keys: Shift+X toggles the wood lasso, X the not-wood one; K starts the classification.
  EXPECT_TRUE(f.state.keyPress("shift+x"));
  EXPECT_EQ(f.state.tools().tool(), ViewerState::Tool::Select);
  EXPECT_TRUE(f.state.keyPress("x"));
  EXPECT_EQ(f.state.tools().tool(), ViewerState::Tool::Lasso);
  EXPECT_TRUE(f.state.keyPress("k"));
  EXPECT_TRUE(f.state.jobs().busy());
  f.state.waitForJob();
}

}  // namespace
}  // namespace treesketch::viewer
