// Cylinder table readers: treesketch's CSV, SimpleForest, TreeQSM with and without a header,
// malformed tables (the error names the line and the column), and the published rTwig table.
#include "treesketch/io/cylinder_table.h"

#include <gtest/gtest.h>

#include <cmath>
#include <sstream>

#include "io_test_util.h"
#include "test_support.h"
#include "treesketch/model/tree_model.h"
#include "treesketch/util/error.h"

namespace treesketch::io {
namespace {

using geom::Vec3;
using testing::expectError;

CylinderTable parse(const std::string& text) { return parseCylinderTable(text, "t.csv"); }

TEST(CylinderTable, TreesketchCsvWithStartRadius) {
  // Node 1 is the root (not in the table); rows: 2 (from the root), 3 (child of 2), 4 (side child of 2).
  std::vector<skeleton::SkeletonNode> nodes(5);
  nodes[1].position = {0, 0, 0};
  nodes[1].radius = 0.3;
  nodes[0].position = {0, 0, -1};  // an unrelated root without children
  nodes[2].position = {0, 0, 1};
  nodes[2].radius = 0.2;
  nodes[2].parent = 1;
  nodes[3].position = {0, 0, 2};
  nodes[3].radius = 0.1;
  nodes[3].parent = 2;
  nodes[4].position = {1, 0, 1.5};
  nodes[4].radius = 0.05;
  nodes[4].parent = 2;
  nodes[4].branchOrder = 1;
  std::ostringstream out;
  const model::TreeModel m = model::fromSkeletonNodes(nodes, {}, geom::UpAxis::Z);
  io::writeCylinderCsv(out, m.cylinders, m.ids);
  const CylinderTable t = parse(out.str());
  EXPECT_EQ(t.format, CylinderTableFormat::Treesketch);
  ASSERT_EQ(t.model.size(), 3u);
  const auto& a = t.model.cylinders[0];
  EXPECT_EQ(a.start, Vec3(0, 0, 0));
  EXPECT_EQ(a.end, Vec3(0, 0, 1));
  EXPECT_DOUBLE_EQ(a.startRadius, 0.3);  // the root's radius, from start_radius
  EXPECT_DOUBLE_EQ(a.endRadius, 0.2);
  EXPECT_EQ(a.parent, -1);
  EXPECT_EQ(t.model.cylinders[1].parent, 0);
  EXPECT_DOUBLE_EQ(t.model.cylinders[2].startRadius, 0.05);  // a branch starts with its own radius
  EXPECT_DOUBLE_EQ(t.model.cylinders[1].startRadius, 0.2);   // the stem with its parent node's
  EXPECT_EQ(t.model.cylinders[2].parent, 0);
  EXPECT_EQ(t.model.cylinders[2].branchOrder, 1);
}

TEST(CylinderTable, FarCoordinatesKeepTheirMillimetres) {
  // Projected coordinates a million metres from the origin (a LAS file's usual frame): nine
  // significant digits alone would round them to the centimetre.
  geom::CylinderModel m;
  geom::ModelCylinder c;
  c.start = Vec3(1176139.2934, 2857173.9712, 0.6555);
  c.end = Vec3(1176139.2601, 2857173.9843, 1.0925);
  c.startRadius = c.endRadius = 0.17;
  m.cylinders.push_back(c);
  for (const bool qsm : {false, true}) {
    std::ostringstream out;
    if (qsm)
      io::writeTreeQsmCylinders(out, m, geom::UpAxis::Z);
    else
      io::writeCylinderCsv(out, m, {});
    const CylinderTable t = parse(out.str());
    ASSERT_EQ(t.model.size(), 1u) << out.str();
    EXPECT_LT((t.model.cylinders[0].start - c.start).norm(), 1e-5) << out.str();
    EXPECT_LT((t.model.cylinders[0].end - c.end).norm(), 1e-5) << out.str();
  }
  std::ostringstream small;  // small numbers keep their nine digits
  m.cylinders[0].start = Vec3(0.5, 0.25, 1.0 / 3.0);
  io::writeCylinderCsv(small, m, {});
  EXPECT_NE(small.str().find(",0.5,0.25,0.333333333,"), std::string::npos) << small.str();
}

TEST(CylinderTable, TreesketchCsvWithoutStartRadiusTakesTheParentRow) {
  const CylinderTable t = parse(
      "id,parent,start_x,start_y,start_z,end_x,end_y,end_z,radius,length,branch_order\n"
      "3,2,0,0,1,0,0,2,0.1,1,0\n"  // a child listed before its parent
      "2,-1,0,0,0,0,0,1,0.2,1,0\n");
  ASSERT_EQ(t.model.size(), 2u);
  EXPECT_EQ(t.model.cylinders[0].parent, 1);
  EXPECT_DOUBLE_EQ(t.model.cylinders[0].startRadius, 0.2);
  EXPECT_DOUBLE_EQ(t.model.cylinders[0].endRadius, 0.1);
  EXPECT_DOUBLE_EQ(t.model.cylinders[1].startRadius, 0.2);  // from the root: its own
}

TEST(CylinderTable, SimpleForestCsv) {
  const CylinderTable t = parse(
      " ID, parentID, startX, startY, startZ, endX, endY, endZ, radius, length, growthLength, "
      "averagePointDistance,segmentID, parentSegmentID, branchOrder, reverseBranchOrder, branchID\r\n"
      "0,-1,0.76,-16.35,253.88,0.75,-16.36,253.93,0.047,0.049,31.4,0.0058,0,-1,0,18,0\r\n"
      "1,0,0.75,-16.36,253.93,0.77,-16.35,253.98,0.048,0.052,31.3,0.0037,0,-1,0,18,0\r\n"
      "7,1,0.77,-16.35,253.98,0.8,-16.3,254.0,0.01,0.06,1.0,0.0037,1,0,2,1,1\r\n");
  EXPECT_EQ(t.format, CylinderTableFormat::SimpleForest);
  ASSERT_EQ(t.model.size(), 3u);
  EXPECT_EQ(t.model.cylinders[0].start, Vec3(0.76, -16.35, 253.88));
  EXPECT_EQ(t.model.cylinders[0].end, Vec3(0.75, -16.36, 253.93));
  EXPECT_DOUBLE_EQ(t.model.cylinders[1].startRadius, 0.048);  // plain cylinders
  EXPECT_DOUBLE_EQ(t.model.cylinders[1].endRadius, 0.048);
  EXPECT_EQ(t.model.cylinders[1].parent, 0);
  EXPECT_EQ(t.model.cylinders[2].parent, 1);
  EXPECT_EQ(t.model.cylinders[2].branchOrder, 2);
}

TEST(CylinderTable, TreeQsmWithoutHeader) {
  // radius length start(3) axis(3) parent extension added UnmodRadius branch BranchOrder PositionInBranch
  const CylinderTable t = parse(
      "0.1\t2\t1\t1\t0\t0\t0\t1\t0\t2\t0\t0.1\t1\t0\t1\n"
      "0.05\t1\t1\t1\t2\t0\t3\t4\t1\t0\t0\t0.05\t2\t1\t1\n");  // axis (0,3,4) → unit (0,0.6,0.8)
  EXPECT_EQ(t.format, CylinderTableFormat::TreeQsmNoHeader);
  ASSERT_EQ(t.model.size(), 2u);
  EXPECT_EQ(t.model.cylinders[0].end, Vec3(1, 1, 2));
  EXPECT_EQ(t.model.cylinders[0].parent, -1);  // 0 = none
  EXPECT_EQ(t.model.cylinders[0].branchOrder, 0);
  EXPECT_NEAR((t.model.cylinders[1].end - Vec3(1, 1.6, 2.8)).norm(), 0, 1e-15);
  EXPECT_EQ(t.model.cylinders[1].parent, 0);  // 1-based row 1
  EXPECT_EQ(t.model.cylinders[1].branchOrder, 1);
  // Eight columns (geometry only), space separated: no parents, no orders.
  const CylinderTable g = parse("0.1 2 1 1 0 0 0 1\n0.1 2 1 1 2 0 0 1\n");
  ASSERT_EQ(g.model.size(), 2u);
  EXPECT_EQ(g.model.cylinders[1].parent, -1);
  EXPECT_EQ(g.model.cylinders[1].branchOrder, -1);
}

TEST(CylinderTable, TreeQsmTextExportHeader) {
  // TreeQSM's save_model_text names start and axis once for three columns each, with units.
  const CylinderTable t = parse(
      "radius (m)\tlength (m)\tstart_point\taxis_direction\tparent\textension\tbranch\tbranch_order\t"
      "position_in_branch\tmad\tSurfCov\tadded\tUnmodRadius (m)\n"
      "0.1\t2\t1\t1\t0\t0\t0\t1\t0\t2\t1\t0\t1\t0.001\t1\t0\t0.1\n"
      "0.05\t1\t1\t1\t2\t1\t0\t0\t1\t0\t2\t1\t1\t0.001\t1\t0\t0.05\n");
  EXPECT_EQ(t.format, CylinderTableFormat::TreeQsm);
  ASSERT_EQ(t.model.size(), 2u);
  EXPECT_EQ(t.model.cylinders[0].end, Vec3(1, 1, 2));
  EXPECT_EQ(t.model.cylinders[1].end, Vec3(2, 1, 2));
  EXPECT_EQ(t.model.cylinders[1].parent, 0);
  EXPECT_EQ(t.model.cylinders[1].branchOrder, 1);
  // Named columns in any order, semicolons, a comment line.
  const CylinderTable n = parse(
      "# exported\nBranchOrder;axis_z;axis_y;axis_x;start_z;start_y;start_x;length;radius;parent\n"
      "0;1;0;0;0;0;0;3;0.2;0\n");
  ASSERT_EQ(n.model.size(), 1u);
  EXPECT_EQ(n.model.cylinders[0].end, Vec3(0, 0, 3));
  EXPECT_DOUBLE_EQ(n.model.cylinders[0].endRadius, 0.2);
}

TEST(CylinderTable, MalformedTablesNameTheLineAndColumn) {
  const std::string h = "id,parent,start_x,start_y,start_z,end_x,end_y,end_z,radius,length,branch_order\n";
  expectError([&] { parse(h + "1,-1,0,0,0,0,0,1,0.1,1,0\n2,1,0,0,1,0,0,x2,0.1,1,0\n"); },
              {"t.csv:3:", "'end_z'", "field 8", "expected a number", "'x2'"});
  expectError([&] { parse(h + "1,-1,0,0,0,0,0,1,0.1,1\n"); }, {"t.csv:2:", "expected 11 fields", "got 10"});
  expectError([&] { parse(h + "\n\n1,-1,0,0,0,0,0,1,-0.1,1,0\n"); }, {"t.csv:4:", "'radius'", "radius >= 0"});
  expectError([&] { parse(h + "1,7,0,0,0,0,0,1,0.1,1,0\n"); }, {"t.csv:2:", "'parent'", "parent 7 is no row's id"});
  expectError([&] { parse(h + "1,-1,0,0,0,0,0,1,0.1,1,0\n1,-1,0,0,0,0,0,1,0.1,1,0\n"); },
              {"t.csv:3:", "'id'", "unique"});
  expectError([&] { parse(h + "1,0.5,0,0,0,0,0,1,0.1,1,0\n"); }, {"t.csv:2:", "expected an integer"});
  expectError([&] { parse(h + "1,-1,0,0,0,0,0,nan,0.1,1,0\n"); }, {"t.csv:2:", "finite"});
  expectError([&] { parse("a,b,c\n1,2,3\n"); }, {"t.csv:1:", "no 'radius' column"});
  expectError([&] { parse("radius,start_x,start_y,start_z,axis_x,axis_y,axis_z\n1,0,0,0,0,0,1\n"); },
              {"t.csv:1:", "'length'"});
  expectError([&] { parse("radius,start_x,start_y,start_z,end_x,end_y\n1,0,0,0,0,0\n"); }, {"t.csv:1:", "end point"});
  expectError([&] { parse("0.1 2 1 1 0 0 0 1\n0.1 2 1 1 0 0 0 0\n"); }, {"t.csv:2:", "axis direction is zero"});
  expectError([&] { parse("0.1 2 1 1 0 0 0 1 0\n0.1 2 1 1 0 0 0 1 5\n"); },
              {"t.csv:2:", "'parent'", "past the last row"});
  expectError([&] { parse("0.1 2 1 1 0 0 0 1\n0.1 2 1 1 0 0 0\n"); }, {"t.csv:2:", "as on the first row"});
  expectError([&] { parse("1 2 3\n"); }, {"t.csv:1:", "header line", "at least 8"});
  expectError([&] { parse(""); }, {"t.csv", "empty"});
  expectError([&] { parse("# only a comment\n"); }, {"t.csv", "only comments"});
  // A header alone is an empty model, not an error.
  EXPECT_TRUE(parse(h).model.empty());
  expectError([] { readCylinderTable(std::filesystem::path("/nonexistent/q.csv")); }, {"q.csv", "not found"});
}

TEST(CylinderTable, DamagedTablesOnlyThrowInputErrors) {
  const std::string sf =
      " ID, parentID, startX, startY, startZ, endX, endY, endZ, radius, length, growthLength, branchOrder\n"
      "0,-1,0.76,-16.35,253.88,0.75,-16.36,253.93,0.047,0.049,31.4,0\n"
      "1,0,0.75,-16.36,253.93,0.77,-16.35,253.98,0.048,0.052,31.3,0\n"
      "7,1,0.77,-16.35,253.98,0.8,-16.3,254.0,0.01,0.06,1.0,2\n";
  const std::string tq =
      "0.1\t2\t1\t1\t0\t0\t0\t1\t0\t2\t0\t0.1\t1\t0\t1\n"
      "0.05\t1\t1\t1\t2\t0\t3\t4\t1\t0\t0\t0.05\t2\t1\t1\n";
  for (const std::string& bytes : {sf, tq})
    testing::expectOnlyInputErrors(bytes, [](const std::string& b) { parseCylinderTable(b, "fuzz"); });
  expectError([] { parse("radius,start_x,start_y,start_z,end_x,end_y,end_z,branch_order\n1,0,0,0,0,0,1,5e12\n"); },
              {"t.csv:2:", "'branch_order'", "at most"});
}

TEST(CylinderTable, PublishedSimpleForestModel) {
  const auto path = test::sharedDataDir() / "real" / "rtwig_QSM_simpleforest.csv";
  if (!std::filesystem::exists(path)) GTEST_SKIP() << path << " not present";
  const CylinderTable t = readCylinderTable(path);
  EXPECT_EQ(t.format, CylinderTableFormat::SimpleForest);
  ASSERT_EQ(t.model.size(), 1149u);  // ../shared/data/real/README.md
  double volume = 0, maxRadius = 0;
  for (const auto& c : t.model.cylinders) {
    volume += c.volume();
    maxRadius = std::max(maxRadius, c.endRadius);
  }
  EXPECT_NEAR(volume, 0.030, 0.0005);  // the README's Σπr²L
  EXPECT_NEAR(maxRadius, 0.048, 0.0005);
  EXPECT_EQ(t.model.cylinders[0].parent, -1);
  EXPECT_EQ(t.model.cylinders[1].parent, 0);
}

TEST(TreeQsmWriter, RoundTripKeepsGeometryLinksOrdersAndVolume) {
  // A stem of two frustums, a branch with two pieces, a sub-branch; parents before and after.
  geom::CylinderModel m;
  auto add = [&](Vec3 a, Vec3 b, double r0, double r1, std::int64_t parent) {
    geom::ModelCylinder c;
    c.start = a;
    c.end = b;
    c.startRadius = r0;
    c.endRadius = r1;
    c.parent = parent;
    m.cylinders.push_back(c);
  };
  add({0, 0, 0}, {0, 0, 1}, 0.3, 0.2, -1);
  add({0, 0, 1}, {0, 0.5, 2}, 0.2, 0.1, 0);
  add({0, 0, 1}, {1, 0, 1.5}, 0.08, 0.06, 0);
  add({1, 0, 1.5}, {2, 0, 2}, 0.06, 0.04, 2);
  add({1, 0, 1.5}, {1, 1, 1.7}, 0.02, 0.01, 2);
  std::ostringstream out;
  writeTreeQsmCylinders(out, m, geom::UpAxis::Z);
  const std::string text = out.str();
  EXPECT_EQ(text.substr(0, text.find('\n')), kTreeQsmCylinderHeader);
  const CylinderTable t = parse(text);
  EXPECT_EQ(t.format, CylinderTableFormat::TreeQsm);
  ASSERT_EQ(t.model.size(), m.size());
  const std::vector<std::int32_t> orders{0, 0, 1, 1, 2};
  double volume = 0, back = 0;
  for (std::size_t i = 0; i < m.size(); ++i) {
    const auto &a = m.cylinders[i], &b = t.model.cylinders[i];
    EXPECT_LT((a.start - b.start).norm(), 1e-8) << i;
    EXPECT_LT((a.end - b.end).norm(), 1e-8) << i;
    EXPECT_EQ(b.parent, a.parent) << i;
    EXPECT_EQ(b.branchOrder, orders[i]) << i;
    EXPECT_DOUBLE_EQ(b.startRadius, b.endRadius);  // TreeQSM's cylinders are plain
    volume += a.volume();
    back += b.volume();
  }
  EXPECT_NEAR(back, volume, 1e-8 * volume);  // the volume-keeping radius
  // Columns: extension of row 1 is row 2, of row 3 is row 4; the sub-branch is branch 3.
  std::istringstream lines(text);
  std::string line;
  std::getline(lines, line);
  std::vector<std::vector<double>> rows;
  while (std::getline(lines, line)) {
    std::istringstream f(line);
    rows.emplace_back();
    for (double v; f >> v;) rows.back().push_back(v);
    ASSERT_EQ(rows.back().size(), 17u) << line;
  }
  EXPECT_EQ(rows[0][9], 2);  // extension
  EXPECT_EQ(rows[2][9], 4);
  EXPECT_EQ(rows[4][10], 3);  // branch (1 stem, 2 the first branch)
  EXPECT_EQ(rows[3][12], 2);  // position in branch
}

TEST(TreeQsmWriter, EmptyModelIsHeaderOnlyAndBadLinksThrow) {
  std::ostringstream out;
  writeTreeQsmCylinders(out, {}, geom::UpAxis::Z);
  EXPECT_EQ(out.str(), std::string(kTreeQsmCylinderHeader) + "\n");
  EXPECT_EQ(parse(out.str()).model.size(), 0u);
  geom::CylinderModel bad;
  bad.cylinders.emplace_back();
  bad.cylinders[0].parent = 3;
  test::TempDir dir;
  EXPECT_THROW(writeTreeQsmCylinders(dir / "q.txt", bad, geom::UpAxis::Z), OptionsError);
  EXPECT_FALSE(std::filesystem::exists(dir / "q.txt"));
}

}  // namespace
}  // namespace treesketch::io
