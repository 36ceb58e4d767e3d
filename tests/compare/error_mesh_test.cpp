#include "treesketch/compare/error_mesh.h"

#include <gtest/gtest.h>

#include <cmath>

#include "test_meshes.h"
#include "treesketch/util/error.h"

namespace treesketch::compare {
namespace {

using Rgb = std::array<std::uint8_t, 3>;
const Rgb kRed{255, 0, 0}, kYellow{255, 255, 0}, kGreen{0, 255, 0}, kCyan{0, 255, 255}, kBlue{0, 0, 255};

TEST(ErrorMesh, RampStops) {
  EXPECT_EQ(rampColor(0.0), kRed);
  EXPECT_EQ(rampColor(0.25), kYellow);
  EXPECT_EQ(rampColor(0.5), kGreen);
  EXPECT_EQ(rampColor(0.75), kCyan);
  EXPECT_EQ(rampColor(1.0), kBlue);
  EXPECT_EQ(rampColor(-3.0), kRed);
  EXPECT_EQ(rampColor(7.0), kBlue);
  EXPECT_EQ(rampColor(std::nan("")), kBlue);
  EXPECT_EQ(rampColor(0.125), (Rgb{255, 128, 0}));  // half way red -> yellow
}

geom::TriMesh triangle() {
  geom::TriMesh m;
  m.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  m.triangles = {{0, 1, 2}};
  return m;
}

TEST(ErrorMesh, ColoursFromMinToMax) {
  geom::TriMesh e = makeErrorMesh(triangle(), {1.0, 2.0, 3.0});
  ASSERT_EQ(e.colors.size(), 3u);
  EXPECT_EQ(e.colors[0], kRed);
  EXPECT_EQ(e.colors[1], kGreen);
  EXPECT_EQ(e.colors[2], kBlue);
  EXPECT_EQ(e.quality, (std::vector<double>{1.0, 2.0, 3.0}));
  EXPECT_EQ(e.vertices, triangle().vertices);
  EXPECT_EQ(e.triangles, triangle().triangles);
  EXPECT_NO_THROW(e.checkConsistent());
}

TEST(ErrorMesh, GivenRangeClampsBelowToRedAboveToBlue) {
  ErrorMeshOptions o;
  o.rangeMin = 1.5;
  o.rangeMax = 2.5;
  geom::TriMesh e = makeErrorMesh(triangle(), {1.0, 2.0, 3.0}, o);
  EXPECT_EQ(e.colors[0], kRed);
  EXPECT_EQ(e.colors[1], kGreen);
  EXPECT_EQ(e.colors[2], kBlue);
  // Only one bound given: the other comes from the data.
  ErrorMeshOptions half;
  half.rangeMax = 5.0;
  EXPECT_EQ(colorRange({1.0, 2.0, 3.0}, half), (std::array<double, 2>{1.0, 5.0}));
}

TEST(ErrorMesh, MissingDistancesAreBlueAndZeroWidthRanges) {
  const double inf = std::numeric_limits<double>::infinity();
  geom::TriMesh e = makeErrorMesh(triangle(), {0.5, inf, std::nan("")});
  EXPECT_EQ(e.colors[0], kRed);  // the only finite value: a zero-width range, at its minimum
  EXPECT_EQ(e.colors[1], kBlue);
  EXPECT_EQ(e.colors[2], kBlue);
  EXPECT_TRUE(std::isinf(e.quality[1]));
  EXPECT_EQ(colorRange({inf}, {}), (std::array<double, 2>{0.0, 0.0}));
}

TEST(ErrorMesh, BadInputThrows) {
  EXPECT_THROW(makeErrorMesh(triangle(), {1.0, 2.0}), OptionsError);
  ErrorMeshOptions o;
  o.rangeMin = 3;
  o.rangeMax = 1;
  EXPECT_THROW(makeErrorMesh(triangle(), {1.0, 2.0, 3.0}, o), OptionsError);
}

}  // namespace
}  // namespace treesketch::compare
