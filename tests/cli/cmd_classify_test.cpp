// `treesketch classify` as a process: a cloud in, the classified cloud out (PLY and LAS) with one
// class and probability per point; bad input gives the documented exit codes and names the file.
#include <gtest/gtest.h>

#include "cli_support.h"
#include "skeleton/synthetic_tree.h"
#include "test_support.h"
#include "treesketch/io/point_cloud_io.h"

namespace treesketch {
namespace {

using test::quoted;

TEST(ClassifyCli, WritesEveryPointWithItsClassAsPlyAndLas) {
  test::TempDir dir;
  const geom::PointCloud cloud = test::sampleCylinders(test::threeLevelTree(), 0.02, 0.002, 3);
  io::writePointCloud(dir / "tree.ply", cloud);
  for (const char* out : {"c.las", "c.ply"}) {
    std::string text;
    ASSERT_EQ(test::runCli("classify " + quoted(dir / "tree.ply") + " -o " + quoted(dir / out), &text), 0) << text;
    EXPECT_NE(text.find("up axis: y, as the file declares"), std::string::npos) << text;
    const geom::PointCloud back = io::readPointCloud(dir / out);
    ASSERT_EQ(back.size(), cloud.size()) << out;
    ASSERT_EQ(back.classification.size(), cloud.size()) << out;
    std::size_t wood = 0, stem = 0, stemWood = 0;
    for (std::size_t i = 0; i < back.size(); ++i) {
      const std::uint8_t c = back.classification[i];
      ASSERT_TRUE(c == 64 || c == 65) << int(c);
      wood += c == 64;
      if (back.positions[i].y() < 2.0) {  // the lower trunk
        ++stem;
        stemWood += c == 64;
      }
    }
    EXPECT_GT(static_cast<double>(stemWood) / stem, 0.9) << out << ": " << text;
    EXPECT_GT(wood, stemWood);
  }
  // The classes as a picture, and a cloud without classes refused for it.
  std::string text;
  EXPECT_EQ(test::runCli("render --cloud " + quoted(dir / "c.ply") + " --color-by class --up y --size 200x200 -o " +
                             quoted(dir / "c.png"),
                         &text),
            0)
      << text;
  EXPECT_TRUE(std::filesystem::exists(dir / "c.png"));
  EXPECT_EQ(test::runCli("render --cloud " + quoted(dir / "tree.ply") + " --color-by class -o " + quoted(dir / "d.png"),
                         &text),
            3)
      << text;
  // The same cloud as text reads too (every format the project reads).
  io::writePointCloud(dir / "tree.xyz", cloud);
  EXPECT_EQ(test::runCli("classify " + quoted(dir / "tree.xyz") + " --up y -o " + quoted(dir / "x.ply"), &text), 0)
      << text;
}

TEST(ClassifyCli, TheContextPassClassifiesAsTheWoodOnlyModelDoes) {
  test::TempDir dir;
  io::writePointCloud(dir / "tree.ply", test::sampleCylinders(test::threeLevelTree(), 0.02, 0.002, 3));
  std::string plain, context;
  ASSERT_EQ(test::runCli("classify " + quoted(dir / "tree.ply") + " -o " + quoted(dir / "a.ply"), &plain), 0) << plain;
  ASSERT_EQ(test::runCli("classify " + quoted(dir / "tree.ply") + " --context -o " + quoted(dir / "b.ply"), &context), 0)
      << context;
  EXPECT_EQ(plain.find("(context pass)"), std::string::npos) << plain;
  EXPECT_NE(context.find("threshold 0.750 (context pass)"), std::string::npos) << context;
  EXPECT_EQ(io::readPointCloud(dir / "b.ply").classification.size(), io::readPointCloud(dir / "a.ply").size());
  // The first pass alone is smoothed over the graph and called at its own threshold; --no-smoothing
  // gives the model's probabilities and threshold as they come.
  EXPECT_NE(plain.find("threshold 0.825 (probabilities smoothed over the graph)"), std::string::npos) << plain;
  std::string raw;
  const std::string noSmoothing = "classify " + quoted(dir / "tree.ply") + " --no-smoothing -o " + quoted(dir / "c.ply");
  ASSERT_EQ(test::runCli(noSmoothing, &raw), 0) << raw;
  EXPECT_NE(raw.find("threshold 0.875\n"), std::string::npos) << raw;
}

TEST(ClassifyCli, BadInputAndOptionsGiveClearErrors) {
  test::TempDir dir;
  std::string out;
  EXPECT_EQ(test::runCli("classify " + quoted(dir / "missing.ply") + " -o " + quoted(dir / "o.ply"), &out), 3) << out;
  EXPECT_NE(out.find("missing.ply"), std::string::npos) << out;
  test::writeText(dir / "bad.xyz", "1 2 3\n4 5 x\n");
  EXPECT_EQ(test::runCli("classify " + quoted(dir / "bad.xyz") + " -o " + quoted(dir / "o.ply"), &out), 3) << out;
  EXPECT_NE(out.find("bad.xyz"), std::string::npos) << out;
  test::writeText(dir / "few.xyz", "0 0 0\n1 0 0\n0 1 0\n0 0 1\n1 1 1\n");
  EXPECT_EQ(test::runCli("classify " + quoted(dir / "few.xyz") + " -o " + quoted(dir / "o.ply"), &out), 5) << out;
  io::writePointCloud(dir / "tree.ply", test::sampleCylinders(test::yTree(), 0.05, 0.002, 1));
  EXPECT_EQ(test::runCli("classify " + quoted(dir / "tree.ply") + " -o " + quoted(dir / "o.obj"), &out), 2) << out;
  EXPECT_EQ(test::runCli("classify " + quoted(dir / "tree.ply"), &out), 2) << out;
  EXPECT_EQ(test::runCli("classify " + quoted(dir / "tree.ply") + " -o " + quoted(dir / "tree.ply"), &out), 4) << out;
  test::writeText(dir / "m.json", "{\"features\": 3}");
  EXPECT_EQ(test::runCli("classify " + quoted(dir / "tree.ply") + " --model " + quoted(dir / "m.json") + " -o " +
                             quoted(dir / "o.ply"),
                         &out),
            3)
      << out;
  EXPECT_NE(out.find("m.json"), std::string::npos) << out;
  EXPECT_EQ(test::runCli("classify --evaluate " + quoted(dir / "r.md"), &out), 2) << out;  // no --trees
  EXPECT_EQ(test::runCli("classify --train-context " + quoted(dir / "c.json"), &out), 2) << out;
  EXPECT_NE(out.find("--trees"), std::string::npos) << out;
  EXPECT_EQ(test::runCli("classify --train-context " + quoted(dir / "c.json") + " --evaluate " + quoted(dir / "r.md") +
                             " --trees " + quoted(dir.path()),
                         &out),
            2)
      << out;
  EXPECT_NE(out.find("separate runs"), std::string::npos) << out;
  // The training's size options are checked before anything is scanned.
  for (const char* bad : {" --depth 0", " --rounds 0", " --learning-rate 2", " --rows-per-scan 10"})
    EXPECT_EQ(test::runCli("classify --train " + quoted(dir / "c.json") + " --trees " + quoted(dir.path()) + bad, &out),
              2)
        << bad << ": " << out;
  EXPECT_FALSE(std::filesystem::exists(dir / "c.json"));
  EXPECT_FALSE(std::filesystem::exists(dir / "o.ply"));
}

/// Writes a one-triangle tree named `name` into `folder`, in the developer trees' layout.
void writeTinyTree(const std::filesystem::path& folder, const std::string& name) {
  std::filesystem::create_directories(folder);
  test::writeText(folder / (name + ".branches.obj"), "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  test::writeText(folder / (name + ".json"), "{\"skeleton\": {\"limbs\": [ {\"sections\": [ {\"center\": [0, 0, 0]} ]} ]}}");
}

TEST(ClassifyCli, MoreTrainingTreesNeverIncludeAHeldOutDeveloperTree) {
  test::TempDir dir;
  writeTinyTree(dir / "dev", "aspen_small_s914");  // a tuning tree's name
  writeTinyTree(dir / "more", "oak_small_s6120");  // a held-out tree's name
  std::string out;
  EXPECT_EQ(test::runCli("classify --train " + quoted(dir / "m.json") + " --trees " + quoted(dir / "dev") +
                             " --more-trees " + quoted(dir / "more"),
                         &out),
            2)
      << out;
  EXPECT_NE(out.find("oak_small_s6120 is a held-out developer tree"), std::string::npos) << out;
  EXPECT_FALSE(std::filesystem::exists(dir / "m.json"));
}

}  // namespace
}  // namespace treesketch
