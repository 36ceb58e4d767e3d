// Degenerate inputs through the CLI: files that read correctly but from which nothing
// can be made — a zero-area mesh, a scan that hits nothing, clouds of equal, collinear, far or too
// few points — get a clear error and exit code 5 (kExitNoResult), never `nan` and never a
// "successful" empty or fit-less model. No output file is written.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <cmath>
#include <filesystem>
#include <sstream>
#include <string>

#include "cli_support.h"
#include "io/io_test_util.h"
#include "test_support.h"
#include "treesketch/io/sketch_file.h"
#include "treesketch/sketch/sketch.h"

namespace treesketch {
namespace {

namespace fs = std::filesystem;
using test::runCli;
using test::writeText;

constexpr int kExitNoResult = 5;  // apps/cli/commands.h

/// A triangle with collinear corners and one with three equal corners: area 0, bbox diagonal 2.
const char* kFlatObj = "v 0 0 0\nv 1 0 0\nv 2 0 0\nv 0 0 0\nf 1 2 3\nf 1 4 1\n";
/// A unit right triangle (area 0.5).
const char* kTriangleObj = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";

class DegenerateCli : public ::testing::Test {
 protected:
  std::string q(const std::string& name) const { return test::quoted(dir / name); }
  bool exists(const std::string& name) const { return fs::exists(dir / name); }
  test::TempDir dir;
};

TEST_F(DegenerateCli, CompareAgainstAZeroAreaMeshIsAnErrorNotNan) {
  writeText(dir / "flat.obj", kFlatObj);
  writeText(dir / "tri.obj", kTriangleObj);
  for (const std::string args : {"flat.obj tri.obj", "tri.obj flat.obj", "flat.obj flat.obj"}) {
    const std::string a = args.substr(0, args.find(' ')), b = args.substr(args.find(' ') + 1);
    std::string out;
    EXPECT_EQ(runCli("compare " + q(a) + " " + q(b) + " --json " + q("r.json"), &out), kExitNoResult) << out;
    EXPECT_NE(out.find("zero area"), std::string::npos) << out;
    EXPECT_NE(out.find("flat.obj"), std::string::npos) << out;
    EXPECT_EQ(out.find("nan"), std::string::npos) << out;
    EXPECT_FALSE(exists("r.json"));
  }
}

TEST_F(DegenerateCli, CompareAgainstACloudOfOnePointPrintsNoNan) {
  writeText(dir / "tri.obj", kTriangleObj);
  writeText(dir / "one.xyz", "0.5 0.5 1\n0.5 0.5 1\n");  // bounding-box diagonal 0: no percentages
  std::string out;
  ASSERT_EQ(runCli("compare " + q("tri.obj") + " " + q("one.xyz"), &out), 0) << out;
  EXPECT_EQ(out.find("nan"), std::string::npos) << out;
  EXPECT_NE(out.find("backward"), std::string::npos) << out;
  EXPECT_NE(out.find("Hausdorff distance: "), std::string::npos) << out;
}

TEST_F(DegenerateCli, ScanOfAZeroAreaMeshIsAnError) {
  writeText(dir / "flat.obj", kFlatObj);
  std::string out;
  EXPECT_EQ(runCli("scan " + q("flat.obj") + " -o " + q("c.ply"), &out), kExitNoResult) << out;
  EXPECT_NE(out.find("zero area"), std::string::npos) << out;
  EXPECT_FALSE(exists("c.ply"));
}

TEST_F(DegenerateCli, ScanThatHitsNothingIsAnError) {
  writeText(dir / "tri.obj", kTriangleObj);
  std::string out;
  // TLS stations 1 unit away with a 1 mm range: no ray reaches the triangle.
  EXPECT_EQ(runCli("scan " + q("tri.obj") + " -o " + q("c.ply") + " --pattern tls --max-range 0.001 --step 2", &out),
            kExitNoResult)
      << out;
  EXPECT_NE(out.find("rays hit"), std::string::npos) << out;
  EXPECT_FALSE(exists("c.ply"));
}

constexpr int kExitInput = 3;

/// Point clouds from which no circle can be fitted, and the exit code each gets: clouds of fewer
/// than 4 points are refused by the reader (3), the others read and fit nothing (5).
struct DegenerateCloud {
  const char* name;
  std::string xyz;
  int exitCode = kExitNoResult;
  /// The automatic model still makes a model of it, every radius inferred from its crown (a
  /// cloud with a width but no circle that fits), and says it is not to be trusted.
  bool inferredAutoModel = false;
};

std::vector<DegenerateCloud> degenerateClouds() {
  std::vector<DegenerateCloud> clouds;
  clouds.push_back({"four equal points", "1 2 3\n1 2 3\n1 2 3\n1 2 3\n"});
  std::ostringstream line, far;
  line.precision(17);
  far.precision(17);
  for (int i = 0; i < 1000; ++i) line << 0.001 * i << " " << 0.002 * i << " " << 0.5 << "\n";
  clouds.push_back({"1000 collinear points", line.str()});
  for (int i = 0; i < 1000; ++i) {  // a 0.2-radius cylinder shifted to 1e30: doubles collapse it
    const double a = 0.37 * i;
    far << 1e30 + 0.2 * std::cos(a) << " " << 1e30 + 0.003 * i << " " << 1e30 + 0.2 * std::sin(a) << "\n";
  }
  clouds.push_back({"points near 1e30", far.str()});
  std::ostringstream huge;  // a 2e29-radius cylinder around 1e30: representable, fits nothing
  huge.precision(17);
  for (int i = 0; i < 3000; ++i) {
    const double a = 0.37 * i;
    huge << 1e30 + 2e29 * std::cos(a) << " " << 1e30 + 3e27 * i << " " << 1e30 + 2e29 * std::sin(a) << "\n";
  }
  clouds.push_back({"a cylinder of radius 2e29 at 1e30", huge.str(), kExitNoResult, true});
  clouds.push_back({"one point", "0 0 0\n", kExitInput});
  clouds.push_back({"two points", "0 0 0\n0 1 0\n", kExitInput});
  clouds.push_back({"three points", "0 0 0\n0 1 0\n0.1 0.5 0\n", kExitInput});
  return clouds;
}

TEST_F(DegenerateCli, ReconstructAutoOfADegenerateCloudIsAnError) {
  for (const auto& c : degenerateClouds()) {
    SCOPED_TRACE(c.name);
    writeText(dir / "c.xyz", c.xyz);
    std::string out;
    const int rc = runCli("reconstruct " + q("c.xyz") + " --auto -o " + q("m.obj") + " --sketch " + q("s.json"), &out);
    if (c.inferredAutoModel) {
      EXPECT_EQ(rc, 0) << out;
      EXPECT_NE(out.find("0 % on fitted circles"), std::string::npos) << out;
      EXPECT_EQ(out.find("verdict: trusted"), std::string::npos) << out;
      fs::remove(dir / "m.obj");
      fs::remove(dir / "s.json");
      continue;
    }
    EXPECT_EQ(rc, c.exitCode) << out;
    EXPECT_NE(out.find("c.xyz"), std::string::npos) << out;
    EXPECT_FALSE(exists("m.obj"));
    EXPECT_FALSE(exists("s.json"));
  }
}

// `sketch auto --method skeleton` gets the automatic model's check too: no sketch of unfitted
// circles on equal or collinear points.
TEST_F(DegenerateCli, SketchAutoSkeletonOfADegenerateCloudIsAnError) {
  for (const auto& c : degenerateClouds()) {
    SCOPED_TRACE(c.name);
    writeText(dir / "c.xyz", c.xyz);
    std::string out;
    const int rc = runCli("sketch auto " + q("c.xyz") + " --method skeleton -o " + q("s.json"), &out);
    if (c.inferredAutoModel) {
      EXPECT_EQ(rc, 0) << out;
      fs::remove(dir / "s.json");
      continue;
    }
    EXPECT_EQ(rc, c.exitCode) << out;
    EXPECT_NE(out.find("c.xyz"), std::string::npos) << out;
    EXPECT_FALSE(exists("s.json"));
  }
}

// A cloud in millimetres and one far from its origin are named, with the fix, by `info` and by
// the automatic model (whose report keeps the warnings).
TEST_F(DegenerateCli, ImplausibleUnitsAndLostPrecisionAreNamedWithTheFix) {
  std::string mm, far;
  for (int z = 0; z < 400; ++z)
    for (int k = 0; k < 60; ++k) {
      const double a = 6.283185307179586 * k / 60, r = 200.0;  // a 0.2 m trunk in millimetres
      mm += std::to_string(r * std::cos(a)) + " " + std::to_string(r * std::sin(a)) + " " + std::to_string(10 * z) +
            "\n";
      far += std::to_string(1e15 + 0.2 * std::cos(a)) + " " + std::to_string(0.2 * std::sin(a)) + " " +
             std::to_string(0.01 * z) + "\n";
    }
  writeText(dir / "mm.xyz", mm);
  writeText(dir / "far.xyz", far);
  std::string out;
  ASSERT_EQ(runCli("info " + q("mm.xyz"), &out), 0) << out;
  EXPECT_NE(out.find("warning: the cloud is 3990 m across"), std::string::npos) << out;
  EXPECT_NE(out.find("--units-metres"), std::string::npos) << out;
  ASSERT_EQ(runCli("info " + q("far.xyz"), &out), 0) << out;
  EXPECT_NE(out.find("doubles step by 0.125"), std::string::npos) << out;
  EXPECT_NE(out.find("recentre"), std::string::npos) << out;
  runCli("reconstruct " + q("mm.xyz") + " --auto --report " + q("r.json") + " -o " + q("m.obj"), &out);
  EXPECT_NE(out.find("warning: the cloud is 3990 m across"), std::string::npos) << out;
  if (exists("r.json")) {
    const auto report = nlohmann::json::parse(test::readText(dir / "r.json"));
    ASSERT_EQ(report["warnings"].size(), 1u);
  }
}

TEST_F(DegenerateCli, ReconstructWithASketchOfADegenerateCloudIsAnError) {
  sketch::Sketch s;
  sketch::SamplingParams p;
  p.lineEpsilon = 0.4;
  const auto root = s.addPointNode(sketch::kNoNode, geom::Vec3(0, 0.2, 0), geom::Vec3::UnitY(), p);
  s.addPointNode(root, geom::Vec3(0, 0.8, 0), geom::Vec3::UnitY(), p);
  io::writeSketch(dir / "s.json", s);
  for (const auto& c : degenerateClouds()) {
    SCOPED_TRACE(c.name);
    writeText(dir / "c.xyz", c.xyz);
    std::string out;
    EXPECT_EQ(runCli("reconstruct " + q("c.xyz") + " --sketch " + q("s.json") + " -o " + q("m.obj"), &out), c.exitCode)
        << out;
    EXPECT_FALSE(exists("m.obj"));
  }
}

// A LAS whose header scale factor is 1e298 (a corrupt header, or a unit gone wrong): its points
// are read, 1e301 apart, and their bounding box's diagonal overflows to +inf. Every command that
// models, sketches or draws a cloud calls it a data error naming the file (exit 5) and writes
// nothing; it used to be "bad command line" (exit 2: a NaN camera, a non-finite node).
TEST_F(DegenerateCli, ACloudTooWideToMeasureIsADataErrorNamingTheFile) {
  io::testing::LasSpec las;
  las.scale = {1e298, 1e298, 1e298};
  for (int i = 0; i < 400; ++i) {
    const double a = 0.37 * i;
    las.points.push_back({static_cast<std::int32_t>(1000 * std::cos(a)), static_cast<std::int32_t>(1000 * std::sin(a)),
                          100 * i});
  }
  writeText(dir / "wide.las", io::testing::buildLas(las));
  const std::string cloud = q("wide.las");
  const std::vector<std::pair<std::string, std::string>> runs = {
      {"reconstruct " + cloud + " --auto -o " + q("m.obj"), "m.obj"},
      {"sketch auto " + cloud + " -o " + q("s.json"), "s.json"},
      {"sketch auto " + cloud + " --method skeleton -o " + q("s.json"), "s.json"},
      {"render --cloud " + cloud + " -o " + q("p.png"), "p.png"},
      {"classify " + cloud + " -o " + q("c.ply"), "c.ply"}};
  for (const auto& [args, output] : runs) {
    std::string out;
    EXPECT_EQ(runCli(args, &out), kExitNoResult) << args << "\n" << out;
    EXPECT_NE(out.find("wide.las"), std::string::npos) << out;
    EXPECT_NE(out.find("too far for areas and volumes"), std::string::npos) << out;
    EXPECT_FALSE(exists(output)) << args;
  }
}

}  // namespace
}  // namespace treesketch
