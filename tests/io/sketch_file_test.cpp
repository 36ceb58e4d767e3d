// Tests of io/sketch_file: sketch and camera files round-trip bit-exactly; bad files are InputErrors
// whose messages say where and what.
#include "treesketch/io/sketch_file.h"

#include <gtest/gtest.h>

#include <cstring>
#include <limits>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "io_test_util.h"
#include "test_support.h"
#include "treesketch/util/error.h"

namespace treesketch::io {
namespace {

using geom::Vec2;
using geom::Vec3;
using sketch::kNoNode;
using sketch::NodeId;
using sketch::Sketch;

bool bitEqual(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

/// A sketch with awkward doubles (no short decimal form), two cameras, a point node and a
/// re-parented node so the child order differs from the id order.
Sketch awkwardSketch() {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  geom::BBox box;
  box.add(Vec3(-0.3, 0, -0.3));
  box.add(Vec3(0.3, 7.123456789, 0.3));
  Sketch sk;
  sk.up = geom::UpAxis::Z;
  sk.defaults.sliceHalfThickness = 0.1 / 3.0;
  sk.defaults.lineEpsilon = std::sqrt(2.0) / 7.0;
  sk.defaults.lineEpsilonStep = 1e-300;
  int c0 = sk.addCamera(geom::presetCamera(geom::PresetView::Front, box, geom::UpAxis::Y, {0, 0, 1023, 767}, false));
  int c1 = sk.addCamera(geom::presetCamera(geom::PresetView::Side, box, geom::UpAxis::Y, {3.5, 1.25, 640, 480}, true));
  NodeId r = sk.addScreenNode(kNoNode, c0, Vec2(500 + u(rng), 600 + u(rng)));
  NodeId a = sk.addScreenNode(r, c0, Vec2(500 + u(rng), 400 + u(rng)));
  NodeId b = sk.addScreenNode(r, c1, Vec2(300 + u(rng), 200 + u(rng)));
  sketch::SamplingParams p;
  p.sliceHalfThickness = u(rng) + 2;
  p.lineEpsilon = 1.0 / 3.0;
  p.lineEpsilonStep = 5e-324 * 1e10;
  p.enabled = false;
  p.maxGrowthSteps = 3;
  NodeId pn = sk.addPointNode(a, Vec3(u(rng), u(rng), 1e17 * u(rng)), Vec3(u(rng), 1, u(rng)), p);
  sk.setParent(a, b);  // r's children: [b]; b's children: [a]
  sk.setKeptCircle(pn, sketch::KeptCircle{Vec3(u(rng), 1.0 / 7.0, -1e-17 * u(rng)), std::sqrt(3.0) / 11.0});
  return sk;
}

void expectBitIdentical(const Sketch& x, const Sketch& y) {
  ASSERT_EQ(x.ids(), y.ids());
  EXPECT_EQ(x.up, y.up);
  EXPECT_EQ(x.defaults, y.defaults);
  ASSERT_EQ(x.cameras().size(), y.cameras().size());
  for (std::size_t i = 0; i < x.cameras().size(); ++i) {
    const auto &a = x.cameras()[i], &b = y.cameras()[i];
    for (int k = 0; k < 16; ++k) {
      EXPECT_TRUE(bitEqual(a.view.data()[k], b.view.data()[k]));
      EXPECT_TRUE(bitEqual(a.projection.data()[k], b.projection.data()[k]));
    }
    EXPECT_TRUE(bitEqual(a.viewport.x, b.viewport.x) && bitEqual(a.viewport.y, b.viewport.y) &&
                bitEqual(a.viewport.width, b.viewport.width) && bitEqual(a.viewport.height, b.viewport.height));
  }
  for (NodeId id : x.ids()) {
    const auto &a = x.node(id), &b = y.node(id);
    EXPECT_EQ(a.parent, b.parent);
    EXPECT_EQ(a.children, b.children);
    EXPECT_EQ(a.camera, b.camera);
    for (int k = 0; k < 2; ++k) EXPECT_TRUE(bitEqual(a.screen[k], b.screen[k])) << "node " << id;
    for (int k = 0; k < 3; ++k) EXPECT_TRUE(bitEqual(a.point[k], b.point[k]) && bitEqual(a.normal[k], b.normal[k]));
    EXPECT_TRUE(bitEqual(a.params.sliceHalfThickness, b.params.sliceHalfThickness));
    EXPECT_TRUE(bitEqual(a.params.lineEpsilon, b.params.lineEpsilon));
    EXPECT_TRUE(bitEqual(a.params.lineEpsilonStep, b.params.lineEpsilonStep));
    EXPECT_EQ(a.params.enabled, b.params.enabled);
    EXPECT_EQ(a.params.maxGrowthSteps, b.params.maxGrowthSteps);
    ASSERT_EQ(a.kept.has_value(), b.kept.has_value()) << "node " << id;
    if (a.kept) {
      for (int k = 0; k < 3; ++k) EXPECT_TRUE(bitEqual(a.kept->centre[k], b.kept->centre[k])) << "node " << id;
      EXPECT_TRUE(bitEqual(a.kept->radius, b.kept->radius)) << "node " << id;
    }
    EXPECT_EQ(x.geometry(id), y.geometry(id));
  }
}

TEST(SketchFile, RoundTripIsBitExact) {
  Sketch sk = awkwardSketch();
  std::stringstream ss;
  writeSketch(ss, sk);
  Sketch back = readSketch(ss, "mem");
  expectBitIdentical(sk, back);
  // And through a file (atomic write), then once more: the text is stable.
  test::TempDir dir;
  writeSketch(dir / "s.json", back);
  Sketch again = readSketch(dir / "s.json");
  expectBitIdentical(sk, again);
  std::stringstream s2;
  writeSketch(s2, again);
  EXPECT_EQ(test::readText(dir / "s.json"), s2.str());
}

TEST(SketchFile, EmptySketchRoundTrips) {
  Sketch sk;
  std::stringstream ss;
  writeSketch(ss, sk);
  Sketch back = readSketch(ss, "mem");
  EXPECT_TRUE(back.empty());
  EXPECT_TRUE(back.cameras().empty());
}

TEST(SketchFile, WriteRefusesInvalidSketch) {
  Sketch sk;
  sketch::Node n;
  n.id = 3;
  n.point = Vec3(NAN, 0, 0);
  n.normal = Vec3(0, 1, 0);
  sk.insertRaw(n);
  std::stringstream ss;
  EXPECT_THROW(writeSketch(ss, sk), OptionsError);
  test::TempDir dir;
  EXPECT_THROW(writeSketch(dir / "bad.json", sk), OptionsError);
  EXPECT_FALSE(std::filesystem::exists(dir / "bad.json"));
}

// Found by fuzz/sketch_roundtrip_fuzz.cpp (fuzz/regressions/sketch_roundtrip/): the writer
// accepted defaults the reader refuses (a step of 0), so a saved sketch could not be opened again.
TEST(SketchFile, WriteRefusesDefaultsTheReaderWouldRefuse) {
  Sketch sk;
  sk.addPointNode(kNoNode, Vec3(0, 0, 0), Vec3(0, 1, 0));
  for (double bad : {0.0, -1.0}) {
    sk.defaults.lineEpsilonStep = bad;
    std::stringstream ss;
    EXPECT_THROW(writeSketch(ss, sk), OptionsError);
  }
}

// Found by fuzz/sketch_roundtrip_fuzz.cpp: a node's maxGrowthSteps above 1e9 passed validate and was
// written, but the reader refused it. Every int >= -1 now reads back.
TEST(SketchFile, LargestGrowthCapRoundTrips) {
  Sketch sk;
  sketch::SamplingParams p;
  p.maxGrowthSteps = std::numeric_limits<int>::max();
  sk.addPointNode(kNoNode, Vec3(0, 0, 0), Vec3(0, 1, 0), p);
  std::stringstream ss;
  writeSketch(ss, sk);
  EXPECT_EQ(readSketch(ss, "mem").node(sk.root()).params.maxGrowthSteps, std::numeric_limits<int>::max());
}

// Found by fuzz/sketch_roundtrip_fuzz.cpp: a node with no growth cap (-1) under defaults with a cap
// was written without "maxGrowthSteps" and so read back with the defaults' cap.
TEST(SketchFile, UncappedNodeUnderCappedDefaultsRoundTrips) {
  Sketch sk;
  sk.defaults.maxGrowthSteps = 3;
  sketch::SamplingParams uncapped;
  uncapped.maxGrowthSteps = -1;
  const NodeId root = sk.addPointNode(kNoNode, Vec3(0, 0, 0), Vec3(0, 1, 0), uncapped);
  const NodeId child = sk.addPointNode(root, Vec3(0, 1, 0), Vec3(0, 1, 0), sk.defaults);
  std::stringstream ss;
  writeSketch(ss, sk);
  const Sketch back = readSketch(ss, "mem");
  EXPECT_EQ(back.node(root).params.maxGrowthSteps, -1);
  EXPECT_EQ(back.node(child).params.maxGrowthSteps, 3);
  EXPECT_EQ(back.defaults.maxGrowthSteps, 3);
}

const char* kCamera =
    R"({"view":[1,0,0,0, 0,1,0,0, 0,0,1,-10, 0,0,0,1],"projection":[1,0,0,0, 0,1,0,0, 0,0,-0.1,-1, 0,0,0,1],)"
    R"("viewport":[0,0,800,600]})";

std::string fileWith(const std::string& nodes, const std::string& cameras = std::string("[") + kCamera + "]",
                     const std::string& head = R"("format":"treesketch-sketch","version":1)") {
  return "{" + head + R"(,"up":"y","cameras":)" + cameras + R"(,"nodes":)" + nodes + "}";
}

/// Reading `text` must throw an InputError whose message names the file and contains every `needle`.
void expectBad(const std::string& text, std::vector<std::string> needles) {
  SCOPED_TRACE("file text: " + text);
  needles.push_back("bad.json");
  std::istringstream in(text);
  testing::expectError([&] { readSketch(in, "bad.json"); }, needles);
}

TEST(SketchFile, GoodMinimalFileReads) {
  std::istringstream in(fileWith(
      R"([{"id":0,"parent":-1,"camera":0,"screen":[400,300]},{"id":4,"parent":0,"point":[0,1,0],"normal":[0,1,0],)"
      R"("params":{"lineEpsilon":0.5}}])"));
  Sketch sk = readSketch(in, "good.json");
  EXPECT_EQ(sk.size(), 2u);
  EXPECT_EQ(sk.node(4).params.lineEpsilon, 0.5);
  EXPECT_EQ(sk.node(4).params.sliceHalfThickness, sketch::SamplingParams{}.sliceHalfThickness);
  EXPECT_EQ(sk.node(4).params.maxGrowthSteps, -1);  // absent: unlimited
  EXPECT_EQ(sk.node(0).children, (std::vector<NodeId>{4}));
}

TEST(SketchFile, RejectsBadStructure) {
  expectBad(fileWith(R"([{"id":0,"parent":-1,"camera":0,"screen":[1,2]},{"id":1,"parent":2,"camera":0,"screen":[1,2]},)"
                     R"({"id":2,"parent":1,"camera":0,"screen":[1,2]}])"),
            {"node 1", "cycle"});
  expectBad(
      fileWith(R"([{"id":0,"parent":-1,"camera":0,"screen":[1,2]},{"id":5,"parent":9,"camera":0,"screen":[1,2]}])"),
      {"node 5", "parent 9 does not exist"});
  expectBad(
      fileWith(R"([{"id":0,"parent":-1,"camera":0,"screen":[1,2]},{"id":6,"parent":-1,"camera":0,"screen":[1,2]}])"),
      {"node 6", "second root"});
  expectBad(
      fileWith(R"([{"id":0,"parent":-1,"camera":0,"screen":[1,2]},{"id":0,"parent":-1,"camera":0,"screen":[1,2]}])"),
      {"node 0", "duplicate"});
}

TEST(SketchFile, RejectsNonNumbers) {
  expectBad(fileWith(R"([{"id":3,"parent":-1,"camera":0,"screen":[null,2]}])"), {"node 3", "screen", "null"});
  expectBad(fileWith(R"([{"id":3,"parent":-1,"camera":0,"screen":["1",2]}])"), {"node 3", "screen", "string"});
  expectBad(fileWith(R"([{"id":3,"parent":-1,"camera":0,"screen":[1]}])"), {"node 3", "screen"});
  expectBad(fileWith(R"([{"id":3,"parent":-1,"point":[0,0,0],"normal":[0,0,0]}])"), {"node 3", "normal", "zero"});
  expectBad(fileWith(R"([{"id":3,"parent":-1,"camera":0,"screen":[1,2],"params":{"lineEpsilon":null}}])"),
            {"node 3", "lineEpsilon"});
  expectBad(fileWith(R"([{"id":3,"parent":-1,"camera":0,"screen":[1,2],"params":{"lineEpsilon":-1}}])"),
            {"node 3", "lineEpsilon must be > 0"});
  expectBad(fileWith(R"([{"id":3,"parent":-1,"camera":0,"screen":[1,2],"params":{"enabled":1}}])"),
            {"node 3", "enabled"});
  expectBad(fileWith(R"([{"id":3,"parent":-1,"camera":0,"screen":[1,2],"params":{"maxGrowthSteps":-2}}])"),
            {"node 3", "maxGrowthSteps"});
  expectBad(fileWith(R"([{"id":3,"parent":-1,"camera":0,"screen":[1,2],"params":{"maxGrowthSteps":1.5}}])"),
            {"node 3", "maxGrowthSteps"});
  expectBad(fileWith(R"([{"id":3.5,"parent":-1,"camera":0,"screen":[1,2]}])"), {"node #0", "id", "integer"});
  expectBad(fileWith(R"([{"parent":-1,"camera":0,"screen":[1,2]}])"), {"node #0", "missing \"id\""});
  expectBad(fileWith(R"([{"id":2,"parent":-1,"screen":[1,2]}])"), {"node 2", "camera"});
  expectBad(fileWith(R"([{"id":2,"parent":-1}])"), {"node 2"});
  expectBad(fileWith(R"([{"id":2,"parent":-1,"camera":0,"screen":[1,2],"point":[1,2,3]}])"), {"node 2", "both"});
  // Overflow to infinity is not a finite number.
  // (nlohmann refuses it while parsing, without a position: the message quotes the number.)
  expectBad(fileWith(R"([{"id":3,"parent":-1,"camera":0,"screen":[1e999,2]}])"), {"1e999", "overflow"});
}

TEST(SketchFile, KeptCirclesReadAndBadOnesAreRejected) {
  std::istringstream in(
      fileWith(R"([{"id":0,"parent":-1,"point":[0,1,0],"normal":[0,1,0],"circle":{"centre":[0.5,1,0],"radius":0.25}},)"
               R"({"id":1,"parent":0,"point":[0,2,0],"normal":[0,1,0]}])"));
  Sketch sk = readSketch(in, "kept.json");
  ASSERT_TRUE(sk.node(0).kept.has_value());
  EXPECT_EQ(sk.node(0).kept->centre, Vec3(0.5, 1, 0));
  EXPECT_EQ(sk.node(0).kept->radius, 0.25);
  EXPECT_FALSE(sk.node(1).kept.has_value());
  EXPECT_EQ(sk.keptCircleCount(), 1u);
  const std::string point = R"({"id":4,"parent":-1,"point":[0,1,0],"normal":[0,1,0],"circle":)";
  expectBad(fileWith("[" + point + R"({"centre":[0,1,0],"radius":0}}])"), {"node 4", "circle", "radius", "> 0"});
  expectBad(fileWith("[" + point + R"({"centre":[0,1,0],"radius":-2}}])"), {"node 4", "radius"});
  expectBad(fileWith("[" + point + R"({"centre":[0,1],"radius":1}}])"), {"node 4", "circle", "centre", "3 numbers"});
  expectBad(fileWith("[" + point + R"({"radius":1}}])"), {"node 4", "circle", "missing \"centre\""});
  expectBad(fileWith("[" + point + R"({"centre":[0,1,0]}}])"), {"node 4", "circle", "missing \"radius\""});
  expectBad(fileWith("[" + point + R"(0.5}])"), {"node 4", "circle", "expected an object"});
  expectBad(fileWith(R"([{"id":5,"parent":-1,"camera":0,"screen":[1,2],"circle":{"centre":[0,1,0],"radius":1}}])"),
            {"node 5", "circle", "point node"});
}

TEST(SketchFile, NotWoodLassosRoundTripAndOldFilesStillRead) {
  Sketch sk = awkwardSketch();
  sk.addNotWoodLasso(0, {Vec2(1.0 / 3.0, 2), Vec2(400, 7.25), Vec2(300, 500.125)});
  sk.addNotWoodLasso(1, {Vec2(0, 0), Vec2(10, 0), Vec2(10, 10), Vec2(0, 10)});
  std::stringstream ss;
  writeSketch(ss, sk);
  EXPECT_NE(ss.str().find("\"notWood\""), std::string::npos);
  Sketch back = readSketch(ss, "mem");
  expectBitIdentical(sk, back);
  ASSERT_EQ(back.notWood().size(), 2u);
  EXPECT_EQ(back.notWood(), sk.notWood());
  // A sketch without lassos writes no "notWood" key (files as before), and a file without one
  // (every file written before lassos existed) reads with none.
  std::stringstream plain;
  writeSketch(plain, awkwardSketch());
  EXPECT_EQ(plain.str().find("notWood"), std::string::npos);
  std::istringstream old(fileWith(R"([{"id":0,"parent":-1,"camera":0,"screen":[400,300]}])"));
  EXPECT_TRUE(readSketch(old, "old.json").notWood().empty());
}

// A wood lasso is kept in drawing order with the not-wood ones; its file is version 2, so that a
// reader of version 1 (which would read it as a not-wood lasso) refuses it.
TEST(SketchFile, WoodLassosRoundTripAsVersionTwo) {
  Sketch sk = awkwardSketch();
  sk.addNotWoodLasso(0, {Vec2(0, 0), Vec2(10, 0), Vec2(10, 10)});
  sk.addWoodLasso(1, {Vec2(1, 2), Vec2(30, 2), Vec2(30, 40.5)});
  std::stringstream ss;
  writeSketch(ss, sk);
  EXPECT_NE(ss.str().find("\"wood\":true"), std::string::npos) << ss.str();
  EXPECT_NE(ss.str().find("\"version\": 2"), std::string::npos);
  Sketch back = readSketch(ss, "mem");
  ASSERT_EQ(back.notWood().size(), 2u);
  EXPECT_EQ(back.notWood(), sk.notWood());
  EXPECT_FALSE(back.notWood()[0].wood);
  EXPECT_TRUE(back.notWood()[1].wood);
  // Without a wood lasso the file stays version 1.
  std::stringstream plain;
  writeSketch(plain, awkwardSketch());
  EXPECT_NE(plain.str().find("\"version\": 1"), std::string::npos);
  const std::string nodes = R"([{"id":0,"parent":-1,"camera":0,"screen":[400,300]}])";
  std::string f = fileWith(nodes);
  expectBad(f.substr(0, f.size() - 1) + R"(,"notWood":[{"camera":0,"wood":"yes","polygon":[[0,0],[5,0],[5,5]]}]})",
            {"not-wood lasso 0", "\"wood\"", "true or false"});
}

TEST(SketchFile, RejectsBadNotWoodLassos) {
  const std::string nodes = R"([{"id":0,"parent":-1,"camera":0,"screen":[400,300]}])";
  auto withLasso = [&](const std::string& lasso) {
    std::string f = fileWith(nodes);
    return f.substr(0, f.size() - 1) + R"(,"notWood":)" + lasso + "}";
  };
  EXPECT_NO_THROW({
    std::istringstream in(withLasso(R"([{"camera":0,"polygon":[[0,0],[5,0],[5,5]]}])"));
    readSketch(in, "ok.json");
  });
  expectBad(withLasso(R"({"camera":0})"), {"notWood", "expected an array"});
  expectBad(withLasso(R"([{"camera":3,"polygon":[[0,0],[5,0],[5,5]]}])"), {"not-wood lasso 0", "camera 3"});
  expectBad(withLasso(R"([{"camera":0,"polygon":[[0,0],[5,0]]}])"), {"not-wood lasso 0", "at least 3"});
  expectBad(withLasso(R"([{"camera":0,"polygon":[[0,0],[5,0],[5,null]]}])"), {"not-wood lasso 0", "vertex 2"});
  expectBad(withLasso(R"([{"polygon":[[0,0],[5,0],[5,5]]}])"), {"not-wood lasso 0", "missing \"camera\""});
}

TEST(SketchFile, RejectsBadCameras) {
  std::string node = R"([{"id":8,"parent":-1,"camera":1,"screen":[1,2]}])";
  expectBad(fileWith(node), {"node 8", "camera 1 does not exist"});
  expectBad(fileWith(R"([{"id":8,"parent":-1,"camera":-2,"screen":[1,2]}])"), {"node 8", "camera"});
  expectBad(
      fileWith("[]",
               R"([{"view":[1,0,0,0, 0,1,0,0, 0,0,1,0, 0,0,0,1],"projection":[1,0,0,0, 0,1,0,0, 0,0,1,0, 0,0,0,1],)"
               R"("viewport":[0,0,0,600]}])"),
      {"camera 0", "viewport"});
  expectBad(
      fileWith("[]",
               R"([{"view":[1,0,0,0, 0,1,0,0, 0,0,1,0, 0,0,0,1],"projection":[0,0,0,0, 0,0,0,0, 0,0,0,0, 0,0,0,0],)"
               R"("viewport":[0,0,800,600]}])"),
      {"camera 0", "singular"});
  expectBad(
      fileWith("[]", R"([{"view":[1,0,0],"projection":[1,0,0,0, 0,1,0,0, 0,0,1,0, 0,0,0,1],"viewport":[0,0,8,6]}])"),
      {"camera 0", "view"});
  expectBad(fileWith("[]", R"([{"projection":[1,0,0,0, 0,1,0,0, 0,0,1,0, 0,0,0,1],"viewport":[0,0,8,6]}])"),
            {"camera 0", "missing \"view\""});
  expectBad(fileWith("[]", "{}"), {"cameras", "array"});
}

TEST(SketchFile, RejectsWrongHeaderAndMalformedJson) {
  expectBad(fileWith("[]", "[]", R"("format":"something-else","version":1)"), {"format"});
  expectBad(fileWith("[]", "[]", R"("format":"treesketch-sketch","version":3)"), {"unsupported version 3"});
  expectBad(fileWith("[]", "[]", R"("format":"treesketch-sketch")"), {"missing \"version\""});
  expectBad(R"({"format":"treesketch-sketch","version":1,"up":"x","cameras":[],"nodes":[]})", {"up"});
  expectBad(R"({"format":"treesketch-sketch","version":1,"cameras":[],"nodes":[}])",
            {"byte offset 65", "malformed JSON"});  // the '}' is the 65th byte
  expectBad("", {"malformed JSON"});
  expectBad("[1,2]", {"top level"});
  std::string truncated = fileWith(R"([{"id":0,"parent":-1,"camera":0,"screen":[1,2]}])");
  truncated.resize(truncated.size() - 10);
  expectBad(truncated, {"malformed JSON", "byte offset"});
}

TEST(SketchFile, LargerSketchRoundTrips) {
  // 3,000 nodes in a chain with side shoots (kept small: JSON parsing is slow under sanitizers).
  Sketch sk;
  int c = sk.addCamera(geom::presetCamera(
      geom::PresetView::Front,
      [] {
        geom::BBox b;
        b.add(Vec3(0, 0, 0));
        b.add(Vec3(1, 1, 1));
        return b;
      }(),
      geom::UpAxis::Y, {}, true));
  NodeId prev = sk.addScreenNode(kNoNode, c, Vec2(0, 0));
  for (int i = 1; i < 3000; ++i) {
    NodeId n = sk.addScreenNode(prev, c, Vec2(i, i));
    if (i % 2) prev = n;
  }
  std::stringstream ss;
  writeSketch(ss, sk);
  Sketch back = readSketch(ss, "mem");
  EXPECT_EQ(back.size(), sk.size());
  EXPECT_EQ(back.node(1).children, sk.node(1).children);
}

TEST(SketchFile, MissingFile) {
  test::TempDir dir;
  EXPECT_THROW(readSketch(dir / "nope.json"), InputError);
  EXPECT_THROW(readCamera(dir / "nope.json"), InputError);
}

TEST(CameraFile, RoundTripAndErrors) {
  geom::BBox box;
  box.add(Vec3(0, 0, 0));
  box.add(Vec3(1, 3, 1));
  geom::Camera cam = geom::presetCamera(geom::PresetView::Top, box, geom::UpAxis::Y, {0, 0, 640, 480}, false);
  test::TempDir dir;
  writeCamera(dir / "cam.json", cam);
  geom::Camera back = readCamera(dir / "cam.json");
  EXPECT_TRUE(back.view == cam.view && back.projection == cam.projection);
  EXPECT_EQ(back.viewport.width, 640);
  std::istringstream bad(
      R"({"view":[1,0,0,0, 0,1,0,0, 0,0,1,0, 0,0,0,1],"projection":[1,0,0,0, 0,1,0,0, 0,0,1,0, 0,0,0,1]})");
  testing::expectError([&] { readCamera(bad, "c.json"); }, {"c.json: camera: missing \"viewport\""});
}

}  // namespace
}  // namespace treesketch::io
