#include "treesketch/viewer/undo_stack.h"

#include <gtest/gtest.h>

namespace treesketch::viewer {
namespace {

sketch::Sketch withPointNodes(int n) {
  sketch::Sketch s;
  sketch::NodeId parent = sketch::kNoNode;
  for (int i = 0; i < n; ++i) parent = s.addPointNode(parent, geom::Vec3(0, i, 0), geom::Vec3(0, 1, 0));
  return s;
}

TEST(UndoStack, UndoRedoRestoreSnapshots) {
  UndoStack stack;
  sketch::Sketch current = withPointNodes(1);
  stack.push(current, "add node 1");
  current = withPointNodes(2);
  stack.push(current, "add node 2");
  current = withPointNodes(3);
  EXPECT_EQ(stack.undoLabel(), "add node 2");
  EXPECT_EQ(stack.undo(current), "add node 2");
  EXPECT_EQ(current.size(), 2u);
  EXPECT_EQ(stack.undo(current), "add node 1");
  EXPECT_EQ(current.size(), 1u);
  EXPECT_FALSE(stack.canUndo());
  EXPECT_EQ(stack.undo(current), "");
  EXPECT_EQ(current.size(), 1u);
  EXPECT_EQ(stack.redo(current), "add node 1");
  EXPECT_EQ(current.size(), 2u);
  EXPECT_EQ(stack.redo(current), "add node 2");
  EXPECT_EQ(current.size(), 3u);
  EXPECT_FALSE(stack.canRedo());
  EXPECT_EQ(stack.redo(current), "");
}

TEST(UndoStack, NewEditClearsRedo) {
  UndoStack stack;
  sketch::Sketch current = withPointNodes(1);
  stack.push(current, "a");
  current = withPointNodes(2);
  stack.undo(current);
  EXPECT_TRUE(stack.canRedo());
  stack.push(current, "b");
  EXPECT_FALSE(stack.canRedo());
  EXPECT_EQ(stack.undoCount(), 1u);
}

TEST(UndoStack, LimitDropsOldestSteps) {
  UndoStack stack(2);
  sketch::Sketch current;
  for (int i = 1; i <= 4; ++i) {
    stack.push(current, "step " + std::to_string(i));
    current = withPointNodes(i);
  }
  EXPECT_EQ(stack.undoCount(), 2u);
  stack.undo(current);
  stack.undo(current);
  EXPECT_EQ(current.size(), 2u);  // the snapshot before step 3
  EXPECT_FALSE(stack.canUndo());
  UndoStack zero(0);  // taken as 1
  zero.push(current, "x");
  EXPECT_EQ(zero.undoCount(), 1u);
  zero.clear();
  EXPECT_FALSE(zero.canUndo());
}

}  // namespace
}  // namespace treesketch::viewer
