// A sketch tied to its cloud (SketchDocument through ViewerState): default names follow the cloud,
// a sketch made for another cloud is not loaded silently, another file is not replaced without a
// question, autosaves go when the work is saved, discarded or undone to nothing; the open cloud
// and a file that failed to load are never written; a cloud with no extent is refused, not a
// crash; clicks select by default; the not-wood lasso reaches the automatic model.
#include "treesketch/viewer/sketch_document.h"

#include <gtest/gtest.h>

#include <cmath>

#include "test_support.h"
#include "treesketch/gen/random.h"
#include "treesketch/geom/types.h"
#include "treesketch/io/sketch_file.h"
#include "treesketch/io/xyz.h"
#include "treesketch/render/color_map.h"
#include "treesketch/viewer/color_legend.h"
#include "treesketch/viewer/point_colors.h"
#include "treesketch/util/error.h"
#include "treesketch/viewer/viewer_state.h"
#include "forked_tree.h"

namespace treesketch::viewer {
namespace {

namespace fs = std::filesystem;
using geom::Vec2;
using geom::Vec3;

/// A vertical trunk of radius 0.2 (y in [0, 4]) shifted by `dx`: two clouds of one folder differ.
geom::PointCloud trunk(double dx = 0.0, int n = 6000) {
  gen::Rng rng(11);
  geom::PointCloud cloud;
  for (int i = 0; i < n; ++i) {
    double a = rng.uniform(0, 2 * M_PI);
    cloud.positions.emplace_back(dx + 0.2 * std::cos(a), rng.uniform(0, 4), 0.2 * std::sin(a));
  }
  return cloud;
}

struct OpenCloud {
  ViewerState state;
  explicit OpenCloud(const fs::path& cloudFile) {
    state.view().setViewport(geom::Viewport{0, 0, 800, 600});
    EXPECT_TRUE(state.openFile(cloudFile, geom::UpAxis::Y));
  }
  /// Shift+clicks (add a node) at `n` heights up the trunk's axis, each above the last (a click
  /// on an existing node's marker would select it).
  void addNodes(int n, double dx = 0.0) {
    for (int i = 0; i < n; ++i, ++clicks)
      state.clickAt(state.view().camera().project(Vec3(dx, 0.3 + 0.35 * clicks, 0)).head<2>(), MouseButton::Left,
                    kModShift);
  }
  int clicks = 0;
};

struct TwoClouds {
  test::TempDir dir;
  fs::path a = dir / "tree.xyz", b = dir / "tree.las.xyz";
  TwoClouds() {
    io::writeXyz(a, trunk(0.0));
    io::writeXyz(b, trunk(0.5, 5000));
  }
};

TEST(SketchDocument, DefaultNamesFollowTheWholeCloudFileName) {
  EXPECT_EQ(SketchDocument::sketchPathFor("d/tree.las"), fs::path("d/tree.las.sketch.json"));
  EXPECT_EQ(SketchDocument::sketchPathFor("d/tree.xyz"), fs::path("d/tree.xyz.sketch.json"));
  EXPECT_EQ(SketchDocument::autosavePathFor("tree.las"), fs::path("tree.las.autosave.sketch.json"));
  EXPECT_TRUE(SketchDocument::sketchPathFor("").empty());
}

TEST(SketchDocument, TheRecordNamesTheCloudByCountAndHash) {
  const geom::PointCloud c = trunk();
  geom::PointCloud moved = c;
  moved.positions[17].x() = std::nextafter(moved.positions[17].x(), 1.0);  // one bit of one coordinate
  EXPECT_EQ(io::cloudContentHash(c), io::cloudContentHash(trunk()));
  EXPECT_NE(io::cloudContentHash(c), io::cloudContentHash(moved));
  test::TempDir dir;
  sketch::Sketch sk;
  sk.addPointNode(sketch::kNoNode, Vec3(0, 1, 0), Vec3::UnitY());
  io::writeSketch(dir / "s.json", sk, io::makeCloudRecord(c, dir / "clouds" / "t.xyz", dir / "s.json"));
  io::SketchFile f = io::readSketchFile(dir / "s.json");
  ASSERT_TRUE(f.cloud.has_value());
  EXPECT_EQ(f.cloud->path, "clouds/t.xyz");  // relative to the sketch's folder
  EXPECT_EQ(f.cloud->points, c.size());
  EXPECT_EQ(f.sketch.size(), 1u);
  test::writeText(dir / "bad.json", R"({"format":"treesketch-sketch","version":1,"cloud":{"path":"t","points":-3,"hash":"x"},"cameras":[],"nodes":[]})");
  EXPECT_THROW(io::readSketchFile(dir / "bad.json"), treesketch::InputError);
}

TEST(SketchDocument, TwoCloudsInOneFolderKeepTheirOwnSketchesAndAutosaves) {
  TwoClouds t;
  {
    OpenCloud s(t.a);
    EXPECT_EQ(s.state.document().sketchPath(), t.dir / "tree.xyz.sketch.json");
    s.addNodes(3);
    ASSERT_EQ(s.state.sketch().size(), 3u);
    EXPECT_TRUE(fs::exists(s.state.document().autosavePath()));
    EXPECT_TRUE(s.state.keyPress("ctrl+s"));
    EXPECT_EQ(io::readSketch(t.dir / "tree.xyz.sketch.json").size(), 3u);
    EXPECT_FALSE(fs::exists(t.dir / "tree.xyz.autosave.sketch.json"));  // saved: nothing to bring back
  }
  OpenCloud s(t.b);
  EXPECT_EQ(s.state.document().sketchPath(), t.dir / "tree.las.xyz.sketch.json");
  s.addNodes(1, 0.5);
  EXPECT_TRUE(s.state.keyPress("ctrl+s"));
  EXPECT_EQ(io::readSketch(t.dir / "tree.xyz.sketch.json").size(), 3u);  // the other tree's is untouched
  EXPECT_EQ(io::readSketch(t.dir / "tree.las.xyz.sketch.json").size(), 1u);
  EXPECT_EQ(io::readSketchFile(t.dir / "tree.las.xyz.sketch.json").cloud->points, 5000u);
}

TEST(SketchDocument, ASketchForAnotherCloudIsNotLoadedSilently) {
  TwoClouds t;
  {
    OpenCloud a(t.a);
    a.addNodes(3);
    ASSERT_TRUE(a.state.saveSketch(a.state.document().sketchPath()));
  }
  OpenCloud s(t.b);
  s.addNodes(1, 0.5);
  const fs::path other = t.dir / "tree.xyz.sketch.json";
  EXPECT_FALSE(s.state.loadSketch(other));
  EXPECT_TRUE(s.state.confirmationPending());
  EXPECT_NE(s.state.confirmationQuestion().find("made for tree.xyz"), std::string::npos)
      << s.state.confirmationQuestion();
  EXPECT_EQ(s.state.sketch().size(), 1u);
  EXPECT_FALSE(s.state.answerConfirmation(false));
  EXPECT_EQ(s.state.sketch().size(), 1u);
  EXPECT_FALSE(s.state.loadSketch(other));
  EXPECT_TRUE(s.state.answerConfirmation(true));
  EXPECT_EQ(s.state.sketch().size(), 3u);
  // Saved, it goes to this cloud's own file; the other tree's sketch is untouched.
  EXPECT_TRUE(s.state.keyPress("ctrl+s"));
  EXPECT_EQ(io::readSketchFile(other).cloud->points, 6000u);
  EXPECT_EQ(io::readSketchFile(t.dir / "tree.las.xyz.sketch.json").cloud->points, 5000u);
}

TEST(SketchDocument, AnOldSketchWithoutARecordStillLoads) {
  TwoClouds t;
  OpenCloud s(t.a);
  sketch::Sketch sk;
  sk.addPointNode(sketch::kNoNode, Vec3(0, 1, 0), Vec3::UnitY());
  io::writeSketch(t.dir / "old.json", sk);
  EXPECT_TRUE(s.state.loadSketch(t.dir / "old.json"));
  EXPECT_FALSE(s.state.confirmationPending());
  EXPECT_EQ(s.state.sketch().size(), 1u);
}

TEST(SketchDocument, SavingOverAnotherFileAsks) {
  TwoClouds t;
  {
    OpenCloud a(t.a);
    a.addNodes(3);
    ASSERT_TRUE(a.state.saveSketch(a.state.document().sketchPath()));
  }
  const fs::path other = t.dir / "tree.xyz.sketch.json";
  const std::string before = test::readText(other);
  OpenCloud s(t.b);
  s.addNodes(1, 0.5);
  s.state.setSketchPath(other);  // as the old default, one name for every cloud
  EXPECT_TRUE(s.state.keyPress("ctrl+s"));
  EXPECT_TRUE(s.state.confirmationPending());
  EXPECT_EQ(test::readText(other), before);
  EXPECT_FALSE(s.state.answerConfirmation(false));
  EXPECT_EQ(test::readText(other), before);
  test::writeText(t.dir / "notes.json", "my notes");
  EXPECT_FALSE(s.state.saveSketch(t.dir / "notes.json"));
  EXPECT_TRUE(s.state.confirmationPending());
  EXPECT_TRUE(s.state.answerConfirmation(true));
  EXPECT_EQ(io::readSketch(t.dir / "notes.json").size(), 1u);
  // A file this document saved is its own: saved again without a question.
  s.addNodes(2, 0.5);
  EXPECT_TRUE(s.state.saveSketch(t.dir / "notes.json"));
  EXPECT_FALSE(s.state.confirmationPending());
}

TEST(SketchDocument, AutosavesGoWhenUndoneToNothingDiscardedOrTheCloudChanges) {
  TwoClouds t;
  OpenCloud s(t.a);
  const fs::path autosave = s.state.document().autosavePath();
  s.addNodes(2);
  ASSERT_TRUE(fs::exists(autosave));
  s.state.undo();
  EXPECT_TRUE(fs::exists(autosave));
  s.state.undo();  // back to nothing: no work to offer back at the next start
  EXPECT_TRUE(s.state.sketch().empty());
  EXPECT_FALSE(fs::exists(autosave));
  s.addNodes(1);
  ASSERT_TRUE(fs::exists(autosave));
  s.state.discardUnsavedWork();  // the unsaved-work prompt's Discard
  EXPECT_FALSE(fs::exists(autosave));
  {
    OpenCloud next(t.a);
    EXPECT_FALSE(next.state.document().recoveryPending());
  }
  // Saved work, an edit undone back to it, then another cloud: nothing unsaved, so the first
  // cloud's autosave does not stay behind.
  s.addNodes(1);
  ASSERT_TRUE(s.state.saveSketch(s.state.document().sketchPath()));
  EXPECT_FALSE(fs::exists(autosave));
  s.addNodes(1);
  s.state.undo();
  ASSERT_TRUE(fs::exists(autosave));
  ASSERT_TRUE(s.state.openFile(t.b, geom::UpAxis::Y));
  EXPECT_FALSE(fs::exists(autosave));
  EXPECT_EQ(s.state.document().autosavePath(), t.dir / "tree.las.xyz.autosave.sketch.json");
}

TEST(SketchDocument, NeverWritesOverTheOpenCloudOrAFileThatFailedToLoad) {
  TwoClouds t;
  const std::string cloudBytes = test::readText(t.a);
  OpenCloud s(t.a);
  s.addNodes(3);
  EXPECT_FALSE(s.state.saveSketch(t.a));
  EXPECT_FALSE(s.state.saveSketch(t.dir / "." / "tree.xyz", true));  // another spelling, confirmed
  EXPECT_FALSE(s.state.exportMesh(t.a));
  EXPECT_FALSE(s.state.exportModel(ViewerState::ModelFile::Cylinders, t.a));
  s.state.setAutosavePath(t.a);
  EXPECT_NE(s.state.document().autosavePath(), t.a);
  EXPECT_EQ(test::readText(t.a), cloudBytes);
  // A sketch file that does not parse: loading fails, and saving there is refused.
  test::writeText(t.dir / "broken.json", "{ not json");
  EXPECT_FALSE(s.state.loadSketch(t.dir / "broken.json"));
  s.state.setSketchPath(t.dir / "broken.json");
  EXPECT_FALSE(s.state.keyPress("ctrl+s") && !s.state.status().lastMessage().error);
  EXPECT_TRUE(s.state.status().lastMessage().error);
  EXPECT_EQ(test::readText(t.dir / "broken.json"), "{ not json");
  s.state.setAutosavePath(t.dir / "broken.json");
  s.addNodes(1);
  EXPECT_EQ(test::readText(t.dir / "broken.json"), "{ not json");
}

TEST(SketchDocument, ACloudWithNoExtentIsRefusedNotACrash) {
  const double scales[] = {0.0, 1e-300};
  for (double scale : scales) {
    ViewerState s;
    s.view().setViewport(geom::Viewport{0, 0, 800, 600});
    geom::PointCloud flat = trunk();
    for (Vec3& p : flat.positions) p *= scale;
    EXPECT_FALSE(s.setCloud(flat, geom::UpAxis::Y)) << scale;
    EXPECT_TRUE(s.status().lastMessage().error);
    s.clickAt(Vec2(400, 300), MouseButton::Left, kModShift);
    EXPECT_FALSE(s.autoSketchSkeleton());
    EXPECT_FALSE(s.startAutoSkeletonJob());
    s.waitForJob();
    EXPECT_TRUE(s.sketch().empty());
    // With a cloud open, a failed open keeps it and its sketch working.
    ASSERT_TRUE(s.setCloud(trunk(), geom::UpAxis::Y));
    s.clickAt(s.view().camera().project(Vec3(0, 1, 0)).head<2>(), MouseButton::Left, kModShift);
    EXPECT_EQ(s.sketch().size(), 1u);
    EXPECT_FALSE(s.setCloud(flat, geom::UpAxis::Y));
    EXPECT_EQ(s.cloud().size(), 6000u);
    s.clickAt(s.view().camera().project(Vec3(0, 2, 0)).head<2>(), MouseButton::Left, kModShift);
    EXPECT_EQ(s.sketch().size(), 2u);
    EXPECT_EQ(s.scene().fittedCount(), 2u);
  }
}

TEST(SketchDocument, ClicksSelectByDefaultAndAMissAddsNothing) {
  ViewerState s;
  s.view().setViewport(geom::Viewport{0, 0, 800, 600});
  ASSERT_TRUE(s.setCloud(trunk(), geom::UpAxis::Y));
  const Vec2 onTrunk = s.view().camera().project(Vec3(0, 1, 0)).head<2>();
  s.clickAt(onTrunk);  // the default tool selects: no node
  EXPECT_TRUE(s.sketch().empty());
  EXPECT_NE(s.status().lastMessage().text.find("nothing added"), std::string::npos) << s.status().lastMessage().text;
  s.clickAt(onTrunk, MouseButton::Left, kModShift);  // Shift adds
  ASSERT_EQ(s.sketch().size(), 1u);
  EXPECT_TRUE(s.keyPress("n"));
  EXPECT_EQ(s.tools().tool(), ViewerState::Tool::AddNodes);
  // Empty space beside the trunk: the view ray meets no points, so nothing is added.
  const Vec2 empty = s.view().camera().project(Vec3(1.5, 1, 0)).head<2>();
  s.clickAt(empty);
  EXPECT_EQ(s.sketch().size(), 1u);
  EXPECT_NE(s.status().lastMessage().text.find("meets no points"), std::string::npos) << s.status().lastMessage().text;
  s.clickAt(s.view().camera().project(Vec3(0, 2, 0)).head<2>());
  EXPECT_EQ(s.sketch().size(), 2u);
  EXPECT_TRUE(s.keyPress("escape"));
  EXPECT_EQ(s.tools().tool(), ViewerState::Tool::Select);
}

TEST(SketchDocument, APickAmongOverlappingMarkersTakesTheNearestInDepth) {
  test::TempDir dir;
  ViewerState s;
  s.view().setViewport(geom::Viewport{0, 0, 800, 600});
  ASSERT_TRUE(s.setCloud(trunk(), geom::UpAxis::Y));
  // Two nodes on one view ray, 1.5 m apart in depth, the far one last in the sketch (a pick by
  // screen distance alone took the last of equals).
  const Vec2 at = s.view().camera().project(Vec3(0, 2, 0)).head<2>();
  const Vec3 nearP = s.view().camera().unproject(at, 0.2),
             farP = nearP + 1.5 * (s.view().camera().unproject(at, 0.9) - nearP).normalized();
  sketch::Sketch sk;
  const sketch::NodeId nearId = sk.addPointNode(sketch::kNoNode, nearP, Vec3::UnitY());
  const sketch::NodeId farId = sk.addPointNode(nearId, farP, Vec3::UnitY());
  sk.setKeptCircle(farId, sketch::KeptCircle{farP, 0.1});
  sk.setKeptCircle(nearId, sketch::KeptCircle{nearP, 0.1});
  io::writeSketch(dir / "two.json", sk);
  ASSERT_TRUE(s.loadSketch(dir / "two.json"));
  EXPECT_EQ(s.scene().nodeAt(at + Vec2(1, 0)), nearId);
  EXPECT_EQ(s.scene().markersAt(at), 2u);
  s.clickAt(at + Vec2(1, 0));
  EXPECT_EQ(s.tools().selected(), nearId);
  EXPECT_NE(s.status().lastMessage().text.find("nearest to the eye of 2 markers"), std::string::npos)
      << s.status().lastMessage().text;
}

TEST(SketchDocument, TheDistanceColouringIsZeroOnTheModelsSurface) {
  // The function: a frustum from (0,0,0) to (0,2,0), radius 0.2; scale 0.1.
  geom::CylinderModel model;
  model.cylinders.push_back(geom::ModelCylinder{Vec3::Zero(), Vec3(0, 2, 0), 0.2, 0.2});
  geom::PointCloud probe;
  probe.positions = {Vec3(0.2, 1, 0), Vec3(0.25, 1, 0), Vec3(0.15, 1, 0), Vec3(3, 1, 0)};
  const std::vector<Rgb> c = surfaceDistanceColors(probe, model, 0.1);
  EXPECT_EQ(c[0], render::viridis(0.0));  // on the surface
  EXPECT_EQ(c[1], render::viridis(0.5));  // 5 cm outside
  EXPECT_EQ(c[2], render::viridis(0.5));  // 5 cm inside
  EXPECT_EQ(c[3], render::viridis(1.0));  // far: the ramp's end
  EXPECT_EQ(surfaceDistanceColors(probe, geom::CylinderModel{}, 0.1)[0], render::viridis(1.0));
  DistanceColorGrid grid;
  const geom::PointCloud cloud = trunk(0.0, 3000);
  grid.build(cloud, 0.1);
  std::vector<Rgb> fromGrid;
  grid.surfaceColors(model, fromGrid);
  EXPECT_EQ(fromGrid, surfaceDistanceColors(cloud, model, 0.1));

  // In the window: trunk points halfway between two fitted circles 2 m apart lie on the tube.
  ViewerState s;
  s.view().setViewport(geom::Viewport{0, 0, 800, 600});
  ASSERT_TRUE(s.setCloud(trunk(0.0, 20000), geom::UpAxis::Y));
  s.view().setColorMode(ColorMode::CircleDistance);
  for (double y : {1.0, 3.0})
    s.clickAt(s.view().camera().project(Vec3(0, y, 0)).head<2>(), MouseButton::Left, kModShift);
  ASSERT_EQ(s.scene().fittedCount(), 2u);
  const std::vector<Rgb>& colors = s.scene().pointColors();
  const double scale = s.options().distanceColorScale * s.bounds().diagonal();
  int between = 0, onSurface = 0;
  for (std::size_t i = 0; i < colors.size(); ++i) {
    if (std::abs(s.cloud().positions[i].y() - 2.0) > 0.05) continue;
    ++between;
    // Within 2 cm of the surface (viridis' green grows along the ramp).
    onSurface += colors[i].g <= render::viridis(std::min(0.02 / scale, 1.0)).g;
  }
  EXPECT_GT(between, 100);
  EXPECT_EQ(onSurface, between);
  const Legend legend = colorLegend(s);
  EXPECT_NE(legend.title.find("model's surface"), std::string::npos) << legend.title;
  EXPECT_NE(legend.note.find("% of the cloud's"), std::string::npos) << legend.note;
}

// In the window, the distance colouring kept from edit to edit is the colouring measured from
// scratch on the model the edits leave: nodes dragged, one added, one undone.
TEST(SketchDocument, TheDistanceColouringAfterEditsIsTheFullMeasure) {
  ViewerState s;
  s.view().setViewport(geom::Viewport{0, 0, 800, 600});
  ASSERT_TRUE(s.setCloud(trunk(0.0, 20000), geom::UpAxis::Y));
  s.view().setColorMode(ColorMode::CircleDistance);
  for (double y : {0.5, 1.5, 2.5})
    s.clickAt(s.view().camera().project(Vec3(0, y, 0)).head<2>(), MouseButton::Left, kModShift);
  ASSERT_EQ(s.scene().fittedCount(), 3u);
  const double scale = s.options().distanceColorScale * s.bounds().diagonal();
  auto check = [&](const char* what) {
    const std::vector<Rgb> colors = s.scene().pointColors();
    const geom::CylinderModel model = s.scene().treeModel().cylinders;
    ASSERT_FALSE(model.empty()) << what;
    EXPECT_EQ(colors, surfaceDistanceColors(s.cloud(), model, scale)) << what;
  };
  check("three nodes");
  const sketch::NodeId middle = s.scene().nodeAt(s.view().camera().project(Vec3(0, 1.5, 0)).head<2>());
  ASSERT_NE(middle, sketch::kNoNode);
  const Vec2 at = s.sketch().node(middle).screen;
  ASSERT_TRUE(s.moveNodeTo(middle, at + Vec2(6, -4)));
  check("middle node dragged");
  EXPECT_GT(s.scene().distanceColorGrid().lastPointsMeasured(), 0u);
  s.clickAt(s.view().camera().project(Vec3(0, 3.5, 0)).head<2>(), MouseButton::Left, kModShift);
  check("a node added on top");
  ASSERT_TRUE(s.undo());
  check("the node undone");
  ASSERT_TRUE(s.moveNodeTo(middle, at));
  check("dragged back");
}

TEST(SketchDocument, ReattachsFirstClickNamesTheNodeAndShiftTurnsTheLimbRound) {
  test::TempDir dir;
  ViewerState s;
  s.view().setViewport(geom::Viewport{0, 0, 800, 600});
  ASSERT_TRUE(s.setCloud(trunk(), geom::UpAxis::Y));
  // 0 (trunk) -> 1 (the limb's tip, far out) -> 2 (its base, near the trunk): hung by its tip.
  sketch::Sketch sk;
  const sketch::NodeId root = sk.addPointNode(sketch::kNoNode, Vec3(0, 1, 0), Vec3::UnitY());
  const sketch::NodeId tip = sk.addPointNode(root, Vec3(-1.2, 3.2, 0), Vec3::UnitY());
  const sketch::NodeId base = sk.addPointNode(tip, Vec3(-0.3, 2.2, 0), Vec3::UnitY());
  io::writeSketch(dir / "hung.json", sk);
  ASSERT_TRUE(s.loadSketch(dir / "hung.json"));
  auto at = [&](sketch::NodeId id) {
    for (const NodeMarker& m : s.scene().nodeMarkers())
      if (m.id == id) return m.screen;
    return Vec2(-1, -1);
  };
  ASSERT_TRUE(s.selectNode(tip));  // selected before the tool: the first click must not move it
  s.setTool(ViewerState::Tool::Reattach);
  s.clickAt(at(base));
  EXPECT_EQ(s.sketch().node(tip).parent, root) << "the first click moved the node selected before";
  EXPECT_EQ(s.tools().selected(), base);
  s.clickAt(at(root), MouseButton::Left, kModShift);
  EXPECT_EQ(s.sketch().node(base).parent, root);
  EXPECT_EQ(s.sketch().node(tip).parent, base);
  EXPECT_TRUE(s.undo());
  EXPECT_EQ(s.sketch().node(base).parent, tip);
}


TEST(SketchDocument, AStrokeSaysHowManyNodesFittedAndWhyOthersDidNot) {
  // A trunk and a sparse limb (150 points over 1.5 m) from (0, 2, 0) towards +x and up.
  geom::PointCloud cloud = trunk(0.0, 20000);
  gen::Rng rng(3);
  const Vec3 from(0, 2, 0), dir = Vec3(1, 0.8, 0).normalized();
  for (int i = 0; i < 150; ++i) {
    const double t = rng.uniform(0.15, 1.5), a = rng.uniform(0, 2 * M_PI);
    cloud.positions.push_back(from + t * dir + 0.04 * (std::cos(a) * Vec3::UnitZ() + std::sin(a) * dir.cross(Vec3::UnitZ())));
  }
  ViewerState s;
  s.view().setViewport(geom::Viewport{0, 0, 800, 600});
  ASSERT_TRUE(s.setCloud(cloud, geom::UpAxis::Y));
  for (double y : {1.0, 2.0, 3.0})
    s.clickAt(s.view().camera().project(Vec3(0, y, 0)).head<2>(), MouseButton::Left, kModShift);
  ASSERT_EQ(s.sketch().size(), 3u);
  std::vector<Vec2> stroke;
  for (double t = 0.0; t <= 1.45; t += 0.1) stroke.push_back(s.view().camera().project(from + t * dir).head<2>());
  ASSERT_TRUE(s.strokeLimb(stroke));
  const std::size_t added = s.sketch().size() - 3;
  std::string said;
  for (const StatusMessage& m : s.status().messages())
    if (m.text.rfind("drew a limb", 0) == 0) said = m.text;
  EXPECT_NE(said.find(" of " + std::to_string(added) + " fitted"), std::string::npos) << said;
  std::size_t fitted = 0;
  for (const auto& [id, node] : s.sketch().nodes())
    fitted += id >= 3 && s.scene().nodeFit(id).status == NodeStatus::Fitted;
  EXPECT_NE(said.find(std::to_string(fitted) + " of "), std::string::npos) << said;
  if (fitted < added) EXPECT_NE(said.find(" not: "), std::string::npos) << said;
}

TEST(SketchDocument, TheNotWoodLassoChangesTheAutomaticModel) {
  ViewerState s;
  s.view().setViewport(geom::Viewport{0, 0, 800, 600});
  ASSERT_TRUE(s.setCloud(test::forkedTree(), geom::UpAxis::Y));
  // The lasso: around the outer part of the -x limb, away from the trunk and the other limb.
  auto at = [&](double x, double y) { return Vec2(s.view().camera().project(Vec3(x, y, 0)).head<2>()); };
  const std::vector<Vec2> lasso = {at(-1.4, 2.75), at(-0.3, 2.75), at(-0.3, 4.0), at(-1.4, 4.0)};
  auto nodesInLasso = [&] {
    sketch::Sketch probe;
    probe.addNotWoodLasso(probe.addCamera(s.view().camera()), lasso);
    int n = 0;
    for (const auto& [id, node] : s.sketch().nodes()) n += node.kept && probe.isNotWood(node.kept->centre);
    return n;
  };
  ASSERT_TRUE(s.startAutoSkeletonJob());
  s.waitForJob();
  const int before = nodesInLasso();
  ASSERT_GE(before, 3) << "the automatic model models the lassoed limb";
  ASSERT_TRUE(s.lassoNotWood(lasso));
  EXPECT_EQ(nodesInLasso(), 0) << "a model circle inside the lasso is fitted again";
  ASSERT_TRUE(s.startAutoSkeletonJob());
  s.waitForJob();
  EXPECT_EQ(s.sketch().notWood().size(), 1u) << "the lasso stays";
  // At most a node at the lasso's edge, whose circle is fitted to the points outside it.
  EXPECT_LE(nodesInLasso(), 1) << "the automatic model leaves the lassoed points out (" << before << " before)";
}

}  // namespace
}  // namespace treesketch::viewer
