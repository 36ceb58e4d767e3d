#include "treesketch/viewer/viewer_state.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "test_support.h"
#include "treesketch/gen/random.h"
#include "treesketch/io/sketch_file.h"
#include "treesketch/render/color_map.h"

namespace treesketch::viewer {
namespace {

using geom::Vec2;
using geom::Vec3;
using sketch::kNoNode;

constexpr double kRadius = 0.2;

/// A vertical trunk: points on a cylinder of radius 0.2 around the Y axis, y in [0, 4].
geom::PointCloud trunk(int n = 20000, std::uint64_t seed = 7) {
  gen::Rng rng(seed);
  geom::PointCloud cloud;
  for (int i = 0; i < n; ++i) {
    double a = rng.uniform(0, 2 * M_PI);
    cloud.positions.emplace_back(kRadius * std::cos(a), rng.uniform(0, 4), kRadius * std::sin(a));
  }
  return cloud;
}

struct Fixture {
  ViewerState state;
  Fixture() {
    state.view().setViewport(geom::Viewport{0, 0, 800, 600});
    EXPECT_TRUE(state.setCloud(trunk(), geom::UpAxis::Y));
    state.setTool(ViewerState::Tool::AddNodes);  // clicks add nodes (the default selects)
  }
  Vec2 screenOf(const Vec3& p) const { return state.view().camera().project(p).head<2>(); }
};

TEST(ViewerState, EmptyCloudIsAnErrorNotAnException) {
  ViewerState s;
  EXPECT_FALSE(s.setCloud(geom::PointCloud{}, geom::UpAxis::Y));
  EXPECT_EQ(s.status().errorCount(), 1u);
  EXPECT_TRUE(s.status().lastMessage().error);
  EXPECT_FALSE(s.addNodeAt(Vec2(10, 10)));
  EXPECT_FALSE(s.autoSketchUniform());
}

TEST(ViewerState, ClicksAddAChainOfNodesThatFitTheTrunk) {
  Fixture f;
  Vec2 a = f.screenOf(Vec3(0, 1, 0)), b = f.screenOf(Vec3(0, 2, 0)), c = f.screenOf(Vec3(0, 3, 0));
  f.state.clickAt(a);
  f.state.clickAt(b);
  f.state.clickAt(c);
  const sketch::Sketch& sk = f.state.sketch();
  ASSERT_EQ(sk.size(), 3u);
  EXPECT_EQ(sk.node(0).parent, kNoNode);
  EXPECT_EQ(sk.node(1).parent, 0);
  EXPECT_EQ(sk.node(2).parent, 1);
  EXPECT_NEAR((sk.node(1).screen - b).norm(), 0.0, 1e-12);
  EXPECT_EQ(f.state.tools().active(), 2);
  EXPECT_EQ(f.state.tools().selected(), 2);
  EXPECT_EQ(sk.cameras().size(), 1u);
  EXPECT_EQ(f.state.scene().fittedCount(), 3u);
  NodeFitView fit = f.state.scene().nodeFit(1);
  ASSERT_EQ(fit.status, NodeStatus::Fitted);
  EXPECT_NEAR(fit.circle.radius, kRadius, 0.02);
  EXPECT_NEAR(fit.circle.centre.y(), 2.0, 0.05);
  EXPECT_NEAR(std::hypot(fit.circle.centre.x(), fit.circle.centre.z()), 0.0, 0.03);
  EXPECT_FALSE(f.state.scene().mesh().empty());
  EXPECT_GE(f.state.lastRebuildMs(), 0.0);
  EXPECT_EQ(f.state.status().errorCount(), 0u);
}

TEST(ViewerState, ClickOnANodeSelectsItAndMakesItActive) {
  Fixture f;
  Vec2 a = f.screenOf(Vec3(0, 1, 0)), b = f.screenOf(Vec3(0, 2, 0));
  f.state.clickAt(a);
  f.state.clickAt(b);
  f.state.clickAt(a + Vec2(3, 0));  // within the pick radius of node 0
  EXPECT_EQ(f.state.sketch().size(), 2u);
  EXPECT_EQ(f.state.tools().selected(), 0);
  EXPECT_EQ(f.state.tools().active(), 0);
  f.state.clickAt(b, MouseButton::Left, kModCtrl);  // Ctrl: select node 1, node 0 stays active
  EXPECT_EQ(f.state.tools().selected(), 1);
  EXPECT_EQ(f.state.tools().active(), 0);
  f.state.clickAt(f.screenOf(Vec3(0, 3, 0)));  // a branch from node 0
  EXPECT_EQ(f.state.sketch().node(2).parent, 0);
  EXPECT_EQ(f.state.scene().nodeAt(Vec2(700, 20)), kNoNode);
}

TEST(ViewerState, DeleteReattachesOrRemovesTheSubtreeAndUndoRestores) {
  Fixture f;
  for (double y : {0.5, 1.5, 2.5, 3.5}) f.state.clickAt(f.screenOf(Vec3(0, y, 0)));
  ASSERT_TRUE(f.state.selectNode(1));
  EXPECT_TRUE(f.state.deleteSelected(false));
  EXPECT_EQ(f.state.sketch().size(), 3u);
  EXPECT_EQ(f.state.sketch().node(2).parent, 0);
  EXPECT_EQ(f.state.tools().selected(), 0);
  EXPECT_TRUE(f.state.undo());
  EXPECT_EQ(f.state.sketch().size(), 4u);
  EXPECT_EQ(f.state.sketch().node(2).parent, 1);
  ASSERT_TRUE(f.state.selectNode(1));
  // Shift+Delete shows what it will remove (nodes 1, 2, 3) and asks; no removes nothing.
  EXPECT_TRUE(f.state.keyPress("shift+delete"));
  ASSERT_TRUE(f.state.confirmationPending());
  EXPECT_EQ(f.state.sketch().size(), 4u);
  for (const NodeMarker& m : f.state.scene().nodeMarkers()) EXPECT_EQ(m.doomed, m.id != 0) << m.id;
  EXPECT_FALSE(f.state.answerConfirmation(false));
  EXPECT_EQ(f.state.sketch().size(), 4u);
  for (const NodeMarker& m : f.state.scene().nodeMarkers()) EXPECT_FALSE(m.doomed) << m.id;
  EXPECT_TRUE(f.state.keyPress("shift+delete"));
  EXPECT_TRUE(f.state.answerConfirmation(true));
  EXPECT_EQ(f.state.sketch().size(), 1u);
  EXPECT_TRUE(f.state.keyPress("ctrl+z"));
  EXPECT_EQ(f.state.sketch().size(), 4u);
  EXPECT_TRUE(f.state.keyPress("y", kModCtrl));
  EXPECT_EQ(f.state.sketch().size(), 1u);
  EXPECT_TRUE(f.state.redo() == false);  // nothing left to redo: an info message, no error
  EXPECT_EQ(f.state.status().errorCount(), 0u);
  f.state.selectNode(kNoNode);
  EXPECT_FALSE(f.state.deleteSelected(false));  // nothing selected: an error message
  EXPECT_EQ(f.state.status().errorCount(), 1u);
  EXPECT_EQ(f.state.sketch().size(), 1u);
}

TEST(ViewerState, DragMovesANodeAsOneUndoStep) {
  Fixture f;
  Vec2 a = f.screenOf(Vec3(0, 1, 0)), b = f.screenOf(Vec3(0, 2, 0));
  f.state.clickAt(a);
  f.state.clickAt(b);
  std::size_t undoBefore = f.state.history().undoCount();
  Vec2 to = f.screenOf(Vec3(0, 2.5, 0));
  f.state.dragTo(b, to);
  EXPECT_EQ(f.state.sketch().size(), 2u);
  EXPECT_NEAR((f.state.sketch().node(1).screen - to).norm(), 0.0, 1e-9);
  EXPECT_EQ(f.state.history().undoCount(), undoBefore + 1);
  EXPECT_NEAR(f.state.scene().nodeFit(1).circle.centre.y(), 2.5, 0.05);
  f.state.undo();
  EXPECT_NEAR((f.state.sketch().node(1).screen - b).norm(), 0.0, 1e-9);
}

TEST(ViewerState, SliderChangesMergeAndBadValuesAreRejected) {
  Fixture f;
  f.state.clickAt(f.screenOf(Vec3(0, 2, 0)));
  std::size_t undoBefore = f.state.history().undoCount();
  EXPECT_TRUE(f.state.setSliceHalfThickness(0.03));
  EXPECT_TRUE(f.state.setSliceHalfThickness(0.04));
  EXPECT_TRUE(f.state.setSliceHalfThickness(0.05));
  EXPECT_EQ(f.state.history().undoCount(), undoBefore + 1);
  EXPECT_DOUBLE_EQ(f.state.sketch().node(0).params.sliceHalfThickness, 0.05);
  f.state.finishEdit();
  EXPECT_TRUE(f.state.setLineEpsilon(0.3));
  EXPECT_EQ(f.state.history().undoCount(), undoBefore + 2);
  EXPECT_FALSE(f.state.setSliceHalfThickness(-1));
  EXPECT_FALSE(f.state.setLineEpsilon(std::nan("")));
  EXPECT_DOUBLE_EQ(f.state.sketch().node(0).params.sliceHalfThickness, 0.05);
  EXPECT_EQ(f.state.status().errorCount(), 2u);
  // No selection: the sizes of new nodes.
  f.state.selectNode(kNoNode);
  EXPECT_TRUE(f.state.setSliceHalfThickness(0.02));
  EXPECT_DOUBLE_EQ(f.state.sketch().defaults.sliceHalfThickness, 0.02);
}

TEST(ViewerState, NodesKeepTheirCameraAcrossViews) {
  Fixture f;
  Vec2 a = f.screenOf(Vec3(0, 1, 0));
  f.state.clickAt(a);
  f.state.view().presetView(geom::PresetView::Side);
  f.state.clickAt(f.screenOf(Vec3(0, 2.5, 0)));
  const sketch::Sketch& sk = f.state.sketch();
  ASSERT_EQ(sk.size(), 2u);
  EXPECT_EQ(sk.cameras().size(), 2u);
  EXPECT_NE(sk.node(0).camera, sk.node(1).camera);
  EXPECT_NEAR((sk.node(0).screen - a).norm(), 0.0, 1e-12);  // unchanged by the view change
  std::vector<NodeMarker> markers = f.state.scene().nodeMarkers();
  ASSERT_EQ(markers.size(), 2u);
  EXPECT_FALSE(markers[0].inCurrentView);
  EXPECT_TRUE(markers[1].inCurrentView);
  // Node 0's marker sits where its fitted centre projects in the side view.
  Vec2 expected = f.screenOf(f.state.scene().nodeFit(0).circle.centre);
  EXPECT_NEAR((markers[0].screen - expected).norm(), 0.0, 1e-6);
  EXPECT_EQ(f.state.scene().fittedCount(), 2u);
  // Moving node 0 in the side view keeps its own camera.
  EXPECT_TRUE(f.state.moveNodeTo(0, f.screenOf(Vec3(0, 1.5, 0))));
  EXPECT_EQ(f.state.sketch().node(0).camera, sk.node(0).camera);
  EXPECT_NEAR(f.state.scene().nodeFit(0).circle.centre.y(), 1.5, 0.05);
}

TEST(ViewerState, SelectedNodeShowsItsSamplingRegionAndSlice) {
  Fixture f;
  f.state.clickAt(f.screenOf(Vec3(0, 2, 0)));
  SamplingRegion r = f.state.scene().samplingRegion();
  ASSERT_TRUE(r.valid);
  EXPECT_TRUE(r.geometry.hasLine);
  std::vector<std::uint32_t> slice = f.state.scene().highlightedSlicePoints();
  ASSERT_FALSE(slice.empty());
  for (std::uint32_t i : slice) {
    double d = std::abs((f.state.cloud().positions[i] - r.geometry.planePoint).dot(r.geometry.planeNormal));
    EXPECT_LT(d, r.sliceHalfThickness);
  }
  EXPECT_FALSE(f.state.scene().highlightedInliers().empty());
  EXPECT_GT(f.state.scene().sceneLines().size(), 20u);  // circle + slab + cylinder
  f.state.selectNode(kNoNode);
  EXPECT_FALSE(f.state.scene().samplingRegion().valid);
  EXPECT_TRUE(f.state.scene().highlightedSlicePoints().empty());
}

TEST(ViewerState, ColourModes) {
  Fixture f;
  // Height colours are the renderer's (one colour module for pictures and the window).
  EXPECT_EQ(f.state.scene().pointColors(), render::heightColors(f.state.cloud().positions, f.state.up()));
  std::uint64_t v = f.state.scene().colorsVersion();
  f.state.view().setColorMode(ColorMode::Plain);
  EXPECT_EQ(f.state.scene().pointColors()[0], f.state.options().plainColor);
  EXPECT_GT(f.state.scene().colorsVersion(), v);
  f.state.clickAt(f.screenOf(Vec3(0, 2, 0)));
  f.state.view().setColorMode(ColorMode::CircleDistance);
  const auto& colors = f.state.scene().pointColors();
  // Trunk points near y = 2 lie on the fitted circle: the ramp's start; the ends are far.
  int near = 0, onCircle = 0;
  for (std::size_t i = 0; i < colors.size(); ++i) {
    if (std::abs(f.state.cloud().positions[i].y() - 2.0) < 0.005) {
      ++near;
      onCircle += colors[i] == render::viridis(0.0) || colors[i].b > 60;
    }
  }
  EXPECT_GT(near, 0);
  EXPECT_EQ(onCircle, near);
}

TEST(ViewerState, FailingActionsReportAndKeepTheSketch) {
  test::TempDir dir;
  Fixture f;
  f.state.clickAt(f.screenOf(Vec3(0, 2, 0)));
  EXPECT_FALSE(f.state.loadSketch(dir / "missing.json"));
  EXPECT_FALSE(f.state.saveSketch(dir / "no_such_dir" / "s.json"));
  test::writeText(dir / "bad.json", "{not json");
  EXPECT_FALSE(f.state.loadSketch(dir / "bad.json"));
  EXPECT_EQ(f.state.sketch().size(), 1u);
  EXPECT_EQ(f.state.status().errorCount(), 3u);
  EXPECT_TRUE(f.state.exportMesh(dir / "m.obj"));
  EXPECT_FALSE(f.state.exportMesh(dir / "m.xyz"));  // unsupported extension
  EXPECT_EQ(f.state.status().errorCount(), 4u);
  EXPECT_TRUE(std::filesystem::exists(dir / "m.obj"));
  // Save and load round trip.
  EXPECT_TRUE(f.state.saveSketch(dir / "s.json"));
  f.state.clickAt(f.screenOf(Vec3(0, 3, 0)));
  EXPECT_TRUE(f.state.loadSketch(dir / "s.json"));
  EXPECT_EQ(f.state.sketch().size(), 1u);
  EXPECT_TRUE(f.state.undo());  // loading is undoable
  EXPECT_EQ(f.state.sketch().size(), 2u);
}

TEST(ViewerState, ExportWithNoFittedNodeIsAnError) {
  test::TempDir dir;
  Fixture f;
  EXPECT_FALSE(f.state.exportMesh(dir / "m.obj"));
  EXPECT_FALSE(std::filesystem::exists(dir / "m.obj"));
}

TEST(ViewerState, ReconstructionFailureBecomesAMessage) {
  struct Throwing : ViewerReconstruction {
    geom::TriMesh m;
    void update(const sketch::Sketch&) override { throw std::runtime_error("boom"); }
    NodeFitView nodeFit(sketch::NodeId) const override { return {}; }
    std::vector<std::uint32_t> slicePoints(sketch::NodeId) const override { return {}; }
    std::vector<std::uint32_t> inlierPoints(sketch::NodeId) const override { return {}; }
    const geom::TriMesh& mesh() const override { return m; }
  };
  ViewerState s({}, [](const geom::PointCloud&) { return std::make_unique<Throwing>(); });
  s.view().setViewport(geom::Viewport{0, 0, 800, 600});
  s.setCloud(trunk(500), geom::UpAxis::Y);
  s.setTool(ViewerState::Tool::AddNodes);
  std::size_t before = s.status().errorCount();
  EXPECT_NO_THROW(s.clickAt(Vec2(400, 300)));
  EXPECT_EQ(s.sketch().size(), 1u);
  EXPECT_GT(s.status().errorCount(), before);
  EXPECT_NE(s.status().lastMessage().text.find("boom"), std::string::npos);
}

TEST(ViewerState, AutosavesBesideTheCloudOnEveryEdit) {
  test::TempDir dir;
  ViewerState s;
  s.view().setViewport(geom::Viewport{0, 0, 800, 600});
  ASSERT_TRUE(s.setCloud(trunk(2000), geom::UpAxis::Y, dir / "tree.xyz"));
  s.setTool(ViewerState::Tool::AddNodes);  // clicks add nodes (the default selects)
  EXPECT_EQ(s.document().autosavePath(), dir / "tree.xyz.autosave.sketch.json");
  s.clickAt(s.view().camera().project(Vec3(0, 1, 0)).head<2>());
  s.clickAt(s.view().camera().project(Vec3(0, 2, 0)).head<2>());
  sketch::Sketch saved = io::readSketch(s.document().autosavePath());
  EXPECT_EQ(saved.size(), 2u);
  s.undo();
  EXPECT_EQ(io::readSketch(s.document().autosavePath()).size(), 1u);
  // Ctrl+S saves to the sketch path: the cloud's own sketch file unless another is set; a save
  // removes the autosave (the work is in its file), the next edit writes it again.
  EXPECT_EQ(s.document().sketchPath(), dir / "tree.xyz.sketch.json");
  EXPECT_TRUE(s.keyPress("ctrl+s"));
  EXPECT_FALSE(s.status().lastMessage().error);
  EXPECT_EQ(io::readSketch(dir / "tree.xyz.sketch.json").size(), 1u);
  EXPECT_FALSE(std::filesystem::exists(s.document().autosavePath()));
  s.setSketchPath(dir / "mine.json");
  EXPECT_TRUE(s.keyPress("s", kModCtrl));
  EXPECT_EQ(io::readSketch(dir / "mine.json").size(), 1u);
  s.clickAt(s.view().camera().project(Vec3(0, 3, 0)).head<2>());
  EXPECT_EQ(io::readSketch(s.document().autosavePath()).size(), 2u);
  // A drag is saved when the button is released.
  Vec2 from = s.sketch().node(0).screen, to = from + Vec2(0, -20);
  s.mouseDown(from, MouseButton::Left);
  s.mouseMove(from + Vec2(0, -10));
  EXPECT_NEAR((io::readSketch(s.document().autosavePath()).node(0).screen - from).norm(), 0.0, 1e-9);
  s.mouseUp(to, MouseButton::Left);
  EXPECT_NEAR((io::readSketch(s.document().autosavePath()).node(0).screen - to).norm(), 0.0, 1e-9);
}

TEST(ViewerState, UniformAutoSketchAndViewKeys) {
  Fixture f;
  EXPECT_TRUE(f.state.autoSketchUniform(5));
  EXPECT_EQ(f.state.sketch().size(), 5u);
  EXPECT_GE(f.state.scene().fittedCount(), 3u);
  EXPECT_TRUE(f.state.keyPress("o"));
  EXPECT_TRUE(f.state.view().orbit().orthographic());
  EXPECT_TRUE(f.state.keyPress("3"));
  EXPECT_NEAR((f.state.view().camera().forward() - Vec3(0, -1, 0)).norm(), 0.0, 1e-9);
  EXPECT_FALSE(f.state.keyPress("q"));
  EXPECT_TRUE(f.state.undo());
  EXPECT_TRUE(f.state.sketch().empty());
}

TEST(ViewerState, SkeletonAutoSketchGivesPointNodesAlongTheTrunk) {
  Fixture f;
  ASSERT_TRUE(f.state.autoSketchSkeleton()) << f.state.status().lastMessage().text;
  const sketch::Sketch& sk = f.state.sketch();
  ASSERT_GE(sk.size(), 2u);
  for (const auto& [id, node] : sk.nodes()) {
    EXPECT_FALSE(node.isScreenNode());
    EXPECT_NEAR(std::hypot(node.point.x(), node.point.z()), 0.0, 0.1);  // on the trunk's axis
  }
  EXPECT_GE(f.state.scene().fittedCount(), sk.size() / 2);
  // Point nodes can be dragged in the view too.
  sketch::NodeId id = sk.root();
  Vec3 before = sk.node(id).point;
  EXPECT_TRUE(f.state.moveNodeTo(id, f.screenOf(before) + Vec2(0, -10)));
  EXPECT_GT(f.state.sketch().node(id).point.y(), before.y());
}

// The automatic skeleton sketch shows the automatic model (kept circles); an edit of a node's
// sizes, Refit or Refit all fit from the cloud, each one undo step.
TEST(ViewerState, SkeletonAutoSketchKeepsItsModelUntilRefit) {
  Fixture f;
  ASSERT_TRUE(f.state.autoSketchSkeleton()) << f.state.status().lastMessage().text;
  const std::size_t n = f.state.sketch().size();
  ASSERT_GE(n, 3u);
  const std::size_t kept = f.state.sketch().keptCircleCount();
  EXPECT_EQ(kept, n);  // every node is the model's circle
  const sketch::NodeId id = f.state.sketch().root();
  ASSERT_TRUE(f.state.scene().nodeFit(id).kept);
  EXPECT_EQ(f.state.scene().nodeFit(id).status, NodeStatus::Fitted);
  EXPECT_FALSE(f.state.refitSelected());  // nothing selected: an error, no change
  EXPECT_TRUE(f.state.status().lastMessage().error);
  ASSERT_TRUE(f.state.selectNode(id));
  ASSERT_TRUE(f.state.refitSelected());
  EXPECT_FALSE(f.state.scene().nodeFit(id).kept);
  EXPECT_EQ(f.state.sketch().keptCircleCount(), kept - 1);
  EXPECT_FALSE(f.state.refitSelected());  // fitted from the cloud already
  ASSERT_TRUE(f.state.undo());
  EXPECT_TRUE(f.state.scene().nodeFit(id).kept);
  // Editing a node's sizes refits that node.
  const sketch::NodeId other = f.state.sketch().node(id).children.at(0);
  ASSERT_TRUE(f.state.selectNode(other));
  ASSERT_TRUE(f.state.setLineEpsilon(f.state.sketch().node(other).params.lineEpsilon * 1.5));
  EXPECT_FALSE(f.state.scene().nodeFit(other).kept);
  EXPECT_TRUE(f.state.scene().nodeFit(id).kept);
  ASSERT_TRUE(f.state.refitAll());
  EXPECT_EQ(f.state.sketch().keptCircleCount(), 0u);
  EXPECT_FALSE(f.state.scene().nodeFit(id).kept);
  EXPECT_FALSE(f.state.refitAll());
  ASSERT_TRUE(f.state.undo());
  EXPECT_EQ(f.state.sketch().keptCircleCount(), kept - 1);
}

TEST(ViewerState, SkeletonAutoSketchInLeafIsOneUndoStep) {
  // A sparse trunk: on dense, randomly sampled surfaces the leaf-on settings' fine voxels split
  // rings into arcs and make thousands of nodes (see skeleton::leafOnSkeletonOptions).
  ViewerState state;
  state.view().setViewport(geom::Viewport{0, 0, 800, 600});
  // Bent, so that the chains' simplification (tolerances in voxels) keeps nodes: a straight trunk
  // is one straight chain in both settings.
  geom::PointCloud bent = trunk(3000);
  for (auto& p : bent.positions) p.x() += 0.4 * std::sin(p.y() * M_PI / 4);
  ASSERT_TRUE(state.setCloud(bent, geom::UpAxis::Y));
  state.setTool(ViewerState::Tool::AddNodes);  // clicks add nodes (the default selects)
  ASSERT_TRUE(state.autoSketchSkeleton(true)) << state.status().lastMessage().text;
  const sketch::Sketch& sk = state.sketch();
  ASSERT_GE(sk.size(), 2u);
  const std::size_t leafOnNodes = sk.size();
  EXPECT_TRUE(state.undo());
  EXPECT_TRUE(state.sketch().empty());
  // The leaf-on settings are really used: thinner level sets give another sketch.
  ASSERT_TRUE(state.autoSketchSkeleton(false));
  EXPECT_NE(state.sketch().size(), leafOnNodes);
}

TEST(ViewerState, OrbitAndPanGesturesDoNotEditTheSketch) {
  Fixture f;
  f.state.clickAt(f.screenOf(Vec3(0, 2, 0)));
  geom::Mat4 view = f.state.view().camera().view;
  f.state.dragTo(Vec2(400, 300), Vec2(500, 320), MouseButton::Right);
  EXPECT_FALSE(f.state.view().camera().view.isApprox(view));
  f.state.dragTo(Vec2(400, 300), Vec2(450, 300), MouseButton::Middle);
  f.state.scroll(2);
  EXPECT_EQ(f.state.sketch().size(), 1u);
  EXPECT_EQ(f.state.history().undoCount(), 1u);
  // Presses outside the viewport are ignored.
  f.state.clickAt(Vec2(-5, 900));
  EXPECT_EQ(f.state.sketch().size(), 1u);
}

}  // namespace
}  // namespace treesketch::viewer

namespace treesketch::viewer {
namespace {

TEST(ViewerState, OrthographicViewSketchesToo) {
  ViewerState s;
  s.view().setViewport(geom::Viewport{0, 0, 800, 600});
  ASSERT_TRUE(s.setCloud(trunk(), geom::UpAxis::Y));
  s.setTool(ViewerState::Tool::AddNodes);  // clicks add nodes (the default selects)
  s.view().setOrthographic(true);
  s.view().presetView(geom::PresetView::Front);
  for (double y : {1.0, 2.0, 3.0}) s.clickAt(s.view().camera().project(Vec3(0, y, 0)).head<2>());
  ASSERT_EQ(s.sketch().size(), 3u);
  EXPECT_TRUE(s.sketch().cameras()[0].isOrthographic());
  EXPECT_EQ(s.scene().fittedCount(), 3u);
  EXPECT_NEAR(s.scene().nodeFit(2).circle.radius, kRadius, 0.02);
}

}  // namespace
}  // namespace treesketch::viewer
