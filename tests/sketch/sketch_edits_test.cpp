#include "treesketch/sketch/sketch_edits.h"

#include <gtest/gtest.h>

#include "treesketch/util/error.h"

namespace treesketch::sketch {
namespace {

using geom::Vec2;
using geom::Vec3;

/// 0 - 1 - 2 - 3, with 4 under 1 and 5 under 4.
Sketch chain() {
  Sketch sk;
  NodeId a = sk.addPointNode(kNoNode, Vec3(0, 0, 0), Vec3::UnitY());
  NodeId b = sk.addPointNode(a, Vec3(0, 1, 0), Vec3::UnitY());
  NodeId c = sk.addPointNode(b, Vec3(0, 2, 0), Vec3::UnitY());
  sk.addPointNode(c, Vec3(0, 3, 0), Vec3::UnitY());
  NodeId d = sk.addPointNode(b, Vec3(1, 1.5, 0), Vec3::UnitX());
  sk.addPointNode(d, Vec3(2, 2, 0), Vec3::UnitX());
  return sk;
}

TEST(SketchEdits, DeleteSubtreeRemovesTheNodeAndEverythingBelow) {
  Sketch sk = chain();
  EXPECT_EQ(deleteSubtree(sk, 4), (std::vector<NodeId>{4, 5}));
  EXPECT_EQ(sk.size(), 4u);
  EXPECT_EQ(sk.node(1).children, (std::vector<NodeId>{2}));
  EXPECT_NO_THROW(sk.validate());
  EXPECT_THROW(deleteSubtree(sk, 4), OptionsError);
  EXPECT_EQ(deleteSubtree(sk, 0).size(), 4u);
  EXPECT_TRUE(sk.empty());
}

TEST(SketchEdits, ReattachMovesTheSubtreeAndRefusesCycles) {
  Sketch sk = chain();
  reattach(sk, 4, 2);
  EXPECT_EQ(sk.node(4).parent, 2);
  EXPECT_EQ(sk.node(5).parent, 4);
  EXPECT_NO_THROW(sk.validate());
  EXPECT_THROW(reattach(sk, 2, 5), OptionsError);  // 5 lies below 2 now
  EXPECT_THROW(reattach(sk, 0, 3), OptionsError);  // the root
  EXPECT_THROW(reattach(sk, 3, kNoNode), OptionsError);
  EXPECT_THROW(reattach(sk, 3, 77), OptionsError);
  EXPECT_EQ(sk.node(2).parent, 1);
}

TEST(SketchEdits, ReattachReversedTurnsALimbHungByItsTipRound) {
  // The limb 1 - 4 - 5 hung by its tip: the model made 1 -> 5 -> 4 (4 is the true base).
  Sketch sk = chain();
  reattach(sk, 5, 1);
  reattach(sk, 4, 5);
  ASSERT_EQ(sk.node(4).parent, 5);
  EXPECT_EQ(reattachReversed(sk, 4, 1), (std::vector<NodeId>{4, 5}));
  EXPECT_EQ(sk.node(4).parent, 1);  // the base grows from the trunk
  EXPECT_EQ(sk.node(5).parent, 4);  // the tip at the end
  EXPECT_NO_THROW(sk.validate());
  // The chain 1 - 2 - 3 turned round under 0 keeps 1's side branch (4) on 1.
  Sketch t = chain();
  EXPECT_EQ(reattachReversed(t, 3, 0), (std::vector<NodeId>{3, 2, 1}));
  EXPECT_EQ(t.node(3).parent, 0);
  EXPECT_EQ(t.node(2).parent, 3);
  EXPECT_EQ(t.node(1).parent, 2);
  EXPECT_EQ(t.node(4).parent, 1);
  EXPECT_NO_THROW(t.validate());
  EXPECT_THROW(reattachReversed(t, 0, 3), OptionsError);  // the root
  EXPECT_THROW(reattachReversed(t, 2, 1), OptionsError);  // 1 lies below 2 now
  EXPECT_THROW(reattachReversed(t, 2, kNoNode), OptionsError);
}

TEST(SketchEdits, GraftCopiesStructureAndKeptCirclesAndDropsRepeats) {
  Sketch target = chain();
  Sketch piece;
  NodeId r = piece.addPointNode(kNoNode, Vec3(0, 3, 0), Vec3::UnitY());  // repeats target node 3
  NodeId s = piece.addPointNode(r, Vec3(0, 4, 0), Vec3::UnitY());
  piece.setKeptCircle(s, KeptCircle{Vec3(0, 4, 0), 0.1});
  piece.addPointNode(s, Vec3(0, 5, 0), Vec3::UnitY());
  std::vector<NodeId> added = graft(target, piece, 3, {r});
  ASSERT_EQ(added.size(), 2u);
  EXPECT_EQ(target.node(added[0]).parent, 3);  // r dropped: s hangs under the attach node
  EXPECT_EQ(target.node(added[1]).parent, added[0]);
  ASSERT_TRUE(target.node(added[0]).kept);
  EXPECT_EQ(target.node(added[0]).kept->radius, 0.1);
  EXPECT_NO_THROW(target.validate());
  EXPECT_THROW(graft(target, piece, kNoNode), OptionsError);  // the target has a root
  Sketch empty;
  EXPECT_EQ(graft(empty, piece, kNoNode).size(), 3u);
  EXPECT_EQ(empty.root(), 0);
}

TEST(NotWoodLasso, PolygonTestAndValidation) {
  const std::vector<Vec2> square = {Vec2(0, 0), Vec2(10, 0), Vec2(10, 10), Vec2(0, 10)};
  EXPECT_TRUE(polygonContains(square, Vec2(5, 5)));
  EXPECT_FALSE(polygonContains(square, Vec2(15, 5)));
  EXPECT_FALSE(polygonContains({Vec2(0, 0), Vec2(1, 1)}, Vec2(0.5, 0.5)));
  Sketch sk;
  EXPECT_THROW(sk.addNotWoodLasso(0, square), OptionsError);  // no camera
  int cam = sk.addCamera(geom::presetCamera(geom::PresetView::Front, geom::BBox{Vec3(-1, 0, -1), Vec3(1, 2, 1)},
                                            geom::UpAxis::Y, geom::Viewport{0, 0, 100, 100}, false));
  EXPECT_THROW(sk.addNotWoodLasso(cam, {Vec2(0, 0), Vec2(1, 1)}), OptionsError);
  EXPECT_THROW(sk.addNotWoodLasso(cam, {Vec2(0, 0), Vec2(1, 1), Vec2(NAN, 1)}), OptionsError);
  // The left half of the view.
  sk.addNotWoodLasso(cam, {Vec2(0, 0), Vec2(50, 0), Vec2(50, 100), Vec2(0, 100)});
  EXPECT_TRUE(sk.isNotWood(Vec3(-0.5, 1, 0)));
  EXPECT_FALSE(sk.isNotWood(Vec3(0.5, 1, 0)));
  EXPECT_NO_THROW(sk.validate());
  sk.removeNotWoodLasso(0);
  EXPECT_FALSE(sk.isNotWood(Vec3(-0.5, 1, 0)));
  EXPECT_THROW(sk.removeNotWoodLasso(0), OptionsError);
}

// A wood lasso says the opposite of a not-wood lasso; where they overlap the one drawn last decides.
TEST(NotWoodLasso, WoodLassoAndTheLastLassoDecides) {
  Sketch sk;
  int cam = sk.addCamera(geom::presetCamera(geom::PresetView::Front, geom::BBox{Vec3(-1, 0, -1), Vec3(1, 2, 1)},
                                            geom::UpAxis::Y, geom::Viewport{0, 0, 100, 100}, false));
  EXPECT_THROW(sk.addWoodLasso(cam, {Vec2(0, 0), Vec2(1, 1)}), OptionsError);
  const Vec3 left(-0.5, 1, 0), right(0.5, 1, 0);
  EXPECT_EQ(sk.lassoClass(left), Sketch::LassoClass::None);
  sk.addNotWoodLasso(cam, {Vec2(0, 0), Vec2(100, 0), Vec2(100, 100), Vec2(0, 100)});  // the whole view
  EXPECT_TRUE(sk.isNotWood(left));
  EXPECT_TRUE(sk.isNotWood(right));
  sk.addWoodLasso(cam, {Vec2(0, 0), Vec2(50, 0), Vec2(50, 100), Vec2(0, 100)});  // then the left half as wood
  EXPECT_EQ(sk.lassoClass(left), Sketch::LassoClass::Wood);
  EXPECT_FALSE(sk.isNotWood(left));
  EXPECT_EQ(sk.lassoClass(right), Sketch::LassoClass::NotWood);
  EXPECT_EQ(sk.woodLassoCount(), 1u);
  EXPECT_EQ(sk.notWood().size(), 2u);
  EXPECT_NO_THROW(sk.validate());
  sk.addNotWoodLasso(cam, {Vec2(0, 0), Vec2(100, 0), Vec2(100, 100), Vec2(0, 100)});  // not wood again, on top
  EXPECT_TRUE(sk.isNotWood(left));
  EXPECT_EQ(sk.clearNotWood(), 3u);
  EXPECT_EQ(sk.woodLassoCount(), 0u);
}

}  // namespace
}  // namespace treesketch::sketch
