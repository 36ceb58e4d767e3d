#include "treesketch/gen/skeleton_io.h"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <sstream>

#include "test_support.h"
#include "treesketch/gen/tree_generator.h"
#include "treesketch/util/error.h"

namespace treesketch::gen {
namespace {

using geom::Vec3;

void expectIdentical(const Skeleton& a, const Skeleton& b) {
  ASSERT_EQ(a.up, b.up);
  ASSERT_EQ(a.branches.size(), b.branches.size());
  for (std::size_t i = 0; i < a.branches.size(); ++i) {
    const SkeletonBranch &x = a.branches[i], &y = b.branches[i];
    EXPECT_EQ(x.id, y.id);
    EXPECT_EQ(x.parent, y.parent);
    EXPECT_EQ(x.parentSection, y.parentSection);
    EXPECT_EQ(x.level, y.level);
    ASSERT_EQ(x.sections.size(), y.sections.size());
    for (std::size_t k = 0; k < x.sections.size(); ++k) {
      EXPECT_EQ(x.sections[k].centre, y.sections[k].centre);  // bit-exact
      EXPECT_EQ(x.sections[k].radius, y.sections[k].radius);
      EXPECT_EQ(x.sections[k].axis, y.sections[k].axis);
    }
  }
}

Skeleton smallSkeleton() {
  TreeOptions o = presetOptions("sparse");
  o.seed = 9;
  o.up = geom::UpAxis::Z;
  return generateSkeleton(o);
}

std::string validText() {
  return R"({"format":"treesketch-skeleton","version":1,"up":"y","units":"m","branches":[
    {"id":0,"parent":-1,"parent_section":-1,"level":0,"sections":[
      {"center":[0,0,0],"radius":0.1,"axis":[0,1,0]},{"center":[0,1,0],"radius":0.05,"axis":[0,1,0]}]}]})";
}

Skeleton parse(const std::string& text) {
  std::istringstream in(text);
  return readSkeletonJson(in, "test.json");
}

TEST(SkeletonIo, StreamRoundTripIsExact) {
  Skeleton s = smallSkeleton();
  ASSERT_GT(s.branches.size(), 5u);
  for (bool pretty : {false, true}) {
    std::stringstream buffer;
    writeSkeletonJson(buffer, s, pretty);
    expectIdentical(s, readSkeletonJson(buffer, "memory"));
  }
}

TEST(SkeletonIo, FileRoundTripIsExactAndHasTheFormatTag) {
  test::TempDir dir;
  Skeleton s = smallSkeleton();
  writeSkeletonJson(dir / "s.json", s);
  expectIdentical(s, readSkeletonJson(dir / "s.json"));
  auto j = nlohmann::json::parse(test::readText(dir / "s.json"));
  EXPECT_EQ(j["format"], "treesketch-skeleton");
  EXPECT_EQ(j["version"], 1);
  EXPECT_EQ(j["up"], "z");
}

TEST(SkeletonIo, ReadsAHandWrittenFile) {
  Skeleton s = parse(validText());
  ASSERT_EQ(s.branches.size(), 1u);
  EXPECT_EQ(s.branches[0].sections[1].centre, Vec3(0, 1, 0));
  EXPECT_EQ(s.branches[0].sections[1].radius, 0.05);
  EXPECT_EQ(parse(R"({"format":"treesketch-skeleton","version":1,"up":"z","branches":[]})").branches.size(), 0u);
}

TEST(SkeletonIo, RejectsBadInput) {
  auto expectError = [](const std::string& text, const std::string& fragment) {
    try {
      parse(text);
      ADD_FAILURE() << "no error for: " << text;
    } catch (const InputError& e) {
      std::string what = e.what();
      EXPECT_NE(what.find("test.json"), std::string::npos) << what;
      EXPECT_NE(what.find(fragment), std::string::npos) << what;
    }
  };
  auto replaced = [](std::string text, const std::string& from, const std::string& to) {
    text.replace(text.find(from), from.size(), to);
    return text;
  };
  const std::string ok = validText();
  expectError("", "byte offset");
  expectError(ok.substr(0, ok.size() / 2), "byte offset");  // truncated
  expectError("[1,2]", "expected a JSON object");
  expectError(replaced(ok, "treesketch-skeleton", "other"), "format");
  expectError(replaced(ok, "\"version\":1", "\"version\":2"), "version");
  expectError(replaced(ok, "\"up\":\"y\"", "\"up\":\"x\""), "up");
  expectError(replaced(ok, "\"units\":\"m\"", "\"units\":\"mm\""), "units");
  expectError(replaced(ok, "\"radius\":0.05", "\"radius\":\"a\""), "branches[0].sections[1].radius");
  expectError(replaced(ok, "\"radius\":0.05", "\"radius\":-1"), "radius must be positive");
  expectError(replaced(ok, "\"radius\":0.05", "\"radius\":1e999"), "finite numbers");
  expectError(replaced(ok, "\"center\":[0,1,0]", "\"center\":[0,1]"), "branches[0].sections[1].center");
  expectError(replaced(ok, "\"axis\":[0,1,0]}]", "\"axis\":[0,0,0]}]"), "unit vector");
  expectError(replaced(ok, ",\"level\":0", ""), "missing field \"level\"");
  expectError(replaced(ok, "\"parent\":-1", "\"parent\":0"), "parent 0 does not come before");
  expectError(replaced(ok, "\"id\":0", "\"id\":0.5"), "expected an integer");
  expectError(replaced(ok, ",{\"center\":[0,1,0],\"radius\":0.05,\"axis\":[0,1,0]}", ""), "expected >= 2");
}

TEST(SkeletonIo, MissingFileIsAnInputError) {
  EXPECT_THROW(readSkeletonJson(std::filesystem::path("/nonexistent/dir/s.json")), InputError);
}

TEST(SkeletonIo, UnwritablePathIsAnOutputError) {
  EXPECT_THROW(writeSkeletonJson(std::filesystem::path("/nonexistent/dir/s.json"), smallSkeleton()), OutputError);
}

}  // namespace
}  // namespace treesketch::gen
