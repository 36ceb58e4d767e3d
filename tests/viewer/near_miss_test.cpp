// Where a click that misses every marker attaches its node (in a dense automatic
// skeleton a near miss once added a node under the root, far from where the person clicked).
#include <gtest/gtest.h>

#include <cmath>

#include "treesketch/gen/random.h"
#include "treesketch/viewer/viewer_state.h"

namespace treesketch::viewer {
namespace {

using geom::Vec2;
using geom::Vec3;

geom::PointCloud trunk() {
  gen::Rng rng(5);
  geom::PointCloud cloud;
  for (int i = 0; i < 6000; ++i) {
    double a = rng.uniform(0, 2 * M_PI);
    cloud.positions.emplace_back(0.2 * std::cos(a), rng.uniform(0, 4), 0.2 * std::sin(a));
  }
  return cloud;
}

struct Fixture {
  ViewerState state;
  Fixture() {
    state.view().setViewport(geom::Viewport{0, 0, 800, 600});
    EXPECT_TRUE(state.setCloud(trunk(), geom::UpAxis::Y));
    state.setTool(ViewerState::Tool::AddNodes);  // clicks add nodes (the default selects)
    EXPECT_TRUE(state.autoSketchUniform(12));  // the active node is a default, not the person's
  }
  Vec2 markerOf(sketch::NodeId id) const {
    for (const NodeMarker& m : state.scene().nodeMarkers())
      if (m.id == id) return m.screen;
    ADD_FAILURE() << "no marker for node " << id;
    return Vec2::Zero();
  }
  sketch::NodeId lastAdded() const {
    sketch::NodeId last = sketch::kNoNode;
    for (sketch::NodeId id : state.sketch().ids()) last = std::max(last, id);
    return last;
  }
};

TEST(NearMiss, AClickBesideAMarkerAttachesToThatNodeNotTheDefault) {
  Fixture f;
  const std::size_t before = f.state.sketch().size();
  const sketch::NodeId target = 5;
  // Just outside the pick radius, to the right of node 5's marker.
  Vec2 at = f.markerOf(target) + Vec2(f.state.options().pickRadiusPx + 5.0, 0.0);
  ASSERT_EQ(f.state.scene().nodeAt(at), sketch::kNoNode);
  f.state.clickAt(at);
  ASSERT_EQ(f.state.sketch().size(), before + 1);
  EXPECT_EQ(f.state.sketch().node(f.lastAdded()).parent, target);
  EXPECT_NE(f.state.status().lastMessage().text.find("under node 5"), std::string::npos)
      << f.state.status().lastMessage().text;
}

TEST(NearMiss, AClickWithinThePickRadiusSelectsTheNearestNode) {
  Fixture f;
  Vec2 a = f.markerOf(4), b = f.markerOf(5);
  // Nearer to 5 than to 4 and within the radius of 5: picks 5 and adds nothing.
  Vec2 at = b + 0.3 * (a - b).normalized() * std::min((a - b).norm(), f.state.options().pickRadiusPx);
  const std::size_t before = f.state.sketch().size();
  f.state.clickAt(at);
  EXPECT_EQ(f.state.sketch().size(), before);
  EXPECT_EQ(f.state.tools().selected(), 5);
}

TEST(NearMiss, ANodeThePersonMadeActiveIsTheParentWhereverTheClick) {
  Fixture f;
  ASSERT_TRUE(f.state.selectNode(2));
  // On the trunk between two markers (away from both): the view ray meets points there.
  f.state.clickAt(0.5 * (f.markerOf(9) + f.markerOf(10)));
  EXPECT_EQ(f.state.sketch().node(f.lastAdded()).parent, 2);
  // The chain of clicks goes on from the node just added.
  sketch::NodeId first = f.lastAdded();
  f.state.clickAt(0.5 * (f.markerOf(10) + f.markerOf(11)));
  EXPECT_EQ(f.state.sketch().node(f.lastAdded()).parent, first);
}

}  // namespace
}  // namespace treesketch::viewer
