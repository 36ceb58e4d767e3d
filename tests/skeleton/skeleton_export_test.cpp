#include "treesketch/skeleton/skeleton_export.h"

#include <gtest/gtest.h>

#include <algorithm>

#include <fstream>
#include <sstream>

#include "synthetic_tree.h"
#include "test_support.h"
#include "treesketch/io/cylinder_table.h"
#include "treesketch/model/tree_model.h"
#include "treesketch/util/error.h"

using namespace treesketch;

TEST(SkeletonExport, CsvAndObjParseBack) {
  const auto cloud = test::sampleCylinders(test::threeLevelTree(), 0.02, 0.003, 4);
  const auto s = skeleton::extractSkeleton(cloud);
  ASSERT_GT(s.nodes.size(), 5u);
  test::TempDir dir;
  const model::TreeModel m = model::fromSkeletonNodes(s.nodes, {}, geom::UpAxis::Y);
  model::TreeModel flagged = m;  // every other piece measured: the column follows the flags
  for (std::size_t i = 0; i < flagged.measured.size(); ++i) flagged.measured[i] = static_cast<char>(i % 2);
  ASSERT_EQ(flagged.measured.size(), m.cylinders.size());
  io::writeCylinderCsv(dir / "cyl.csv", m.cylinders, m.ids, flagged.measured);
  skeleton::writeSkeletonObj(dir / "skel.obj", s.nodes);

  std::istringstream csv(test::readText(dir / "cyl.csv"));
  std::string line;
  std::getline(csv, line);
  EXPECT_EQ(line, std::string(io::kCylinderCsvHeader) + "," + io::kCylinderCsvMeasuredColumn);
  std::size_t rows = 0;
  while (std::getline(csv, line)) {
    std::istringstream row(line);
    std::vector<double> v;
    std::string cell;
    while (std::getline(row, cell, ',')) v.push_back(std::stod(cell));
    ASSERT_EQ(v.size(), 13u);
    const auto id = static_cast<std::size_t>(v[0]);
    ASSERT_LT(id, s.nodes.size());
    const auto& n = s.nodes[id];
    const auto& p = s.nodes[n.parent];
    EXPECT_EQ(static_cast<int>(v[1]), p.parent < 0 ? -1 : n.parent);
    EXPECT_NEAR(v[2], p.position.x(), 1e-6);
    EXPECT_NEAR(v[6], n.position.y(), 1e-6);
    EXPECT_NEAR(v[8], n.radius, 1e-6);
    EXPECT_NEAR(v[9], (n.position - p.position).norm(), 1e-6);
    EXPECT_EQ(static_cast<int>(v[10]), n.branchOrder);
    // The parent's radius; a branch's first row its own (no cone of the parent's thickness).
    EXPECT_NEAR(v[11], n.branchOrder > p.branchOrder ? std::min(p.radius, n.radius) : p.radius, 1e-6);
    EXPECT_EQ(static_cast<int>(v[12]), static_cast<int>(rows % 2));
    ++rows;
  }
  EXPECT_EQ(rows, s.nodes.size() - 1);

  std::istringstream obj(test::readText(dir / "skel.obj"));
  std::size_t vs = 0, ls = 0;
  while (std::getline(obj, line)) {
    std::istringstream in(line);
    std::string tag;
    in >> tag;
    if (tag == "v") {
      double x, y, z;
      ASSERT_TRUE(in >> x >> y >> z);
      EXPECT_NEAR(y, s.nodes[vs].position.y(), 1e-6);
      ++vs;
    } else if (tag == "l") {
      int a, b;
      ASSERT_TRUE(in >> a >> b);
      EXPECT_EQ(s.nodes[b - 1].parent, a - 1);
      ++ls;
    }
  }
  EXPECT_EQ(vs, s.nodes.size());
  EXPECT_EQ(ls, s.nodes.size() - 1);
}

TEST(SkeletonExport, UnwritablePathThrowsAndLeavesNothing) {
  test::TempDir dir;
  const auto bad = dir / "missing_dir" / "cyl.csv";
  EXPECT_THROW(io::writeCylinderCsv(bad, geom::CylinderModel{}), OutputError);
  EXPECT_THROW(skeleton::writeSkeletonObj(dir / "missing_dir" / "s.obj", {}), OutputError);
  EXPECT_FALSE(std::filesystem::exists(bad));
  // Empty skeleton: header only.
  io::writeCylinderCsv(dir / "empty.csv", geom::CylinderModel{});
  EXPECT_EQ(test::readText(dir / "empty.csv"), std::string(io::kCylinderCsvHeader) + "\n");
}
TEST(SkeletonExport, SkeletonModelIsFrustumsBetweenNodes) {
  std::vector<skeleton::SkeletonNode> nodes(4);
  nodes[0].position = {0, 0, 0};
  nodes[0].radius = 0.3;
  nodes[1].position = {0, 0, 1};
  nodes[1].radius = 0.2;
  nodes[1].parent = 0;
  nodes[2].position = {0, 0, 2};
  nodes[2].radius = 0.1;
  nodes[2].parent = 1;
  nodes[3].position = {1, 0, 1};
  nodes[3].radius = 0.05;
  nodes[3].parent = 1;
  nodes[3].branchOrder = 1;
  const geom::CylinderModel m = skeleton::cylinderModelFromSkeleton(nodes);
  ASSERT_EQ(m.size(), 3u);
  EXPECT_EQ(m.cylinders[0].start, geom::Vec3(0, 0, 0));
  EXPECT_DOUBLE_EQ(m.cylinders[0].startRadius, 0.3);
  EXPECT_DOUBLE_EQ(m.cylinders[0].endRadius, 0.2);
  EXPECT_EQ(m.cylinders[0].parent, -1);
  EXPECT_EQ(m.cylinders[1].parent, 0);
  // A side branch starts with its own radius at its fork (not a cone of the fork's thickness).
  EXPECT_DOUBLE_EQ(m.cylinders[2].startRadius, 0.05);
  EXPECT_DOUBLE_EQ(m.cylinders[1].startRadius, 0.2);  // the stem continues with its own
  EXPECT_EQ(m.cylinders[2].parent, 0);
  EXPECT_EQ(m.cylinders[2].branchOrder, 1);
  nodes[3].parent = 9;
  EXPECT_THROW(skeleton::cylinderModelFromSkeleton(nodes), OptionsError);
}
