// The ground under a tree: the terrain's points set aside whatever its slope and roughness, and
// nothing of a tree without terrain (a stem's foot, a level limb, a crown's flat underside).
#include "treesketch/cloud/ground.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>

#include "treesketch/cloud/stray_points.h"
#include "treesketch/util/error.h"

namespace treesketch::cloud {
namespace {

using geom::Vec3;

/// The surface of a vertical cylinder (radius r) from height z0 to z1, sampled every `step`.
void addStem(geom::PointCloud& c, double r, double z0, double z1, double step) {
  const int around = static_cast<int>(std::ceil(2 * std::numbers::pi * r / step));
  for (double z = z0; z <= z1; z += step)
    for (int k = 0; k < around; ++k) {
      const double a = 2 * std::numbers::pi * k / around;
      c.positions.emplace_back(r * std::cos(a), r * std::sin(a), z);
    }
}

/// A terrain of radius `extent` round the origin: height slope·x plus bumps, range noise `noise`,
/// `perSquareMetre` points at random; none inside the stem's circle (the stem stands on it).
void addTerrain(geom::PointCloud& c, double extent, double slope, double noise, double perSquareMetre, double stemR,
                std::mt19937& rng) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::normal_distribution<double> gauss(0.0, noise);
  const auto n = static_cast<std::size_t>(std::numbers::pi * extent * extent * perSquareMetre);
  for (std::size_t k = 0; k < n; ++k) {
    const double r = extent * std::sqrt(unit(rng)), a = 2 * std::numbers::pi * unit(rng);
    const double x = r * std::cos(a), y = r * std::sin(a);
    if (r < stemR) continue;
    const double h = slope * x + 0.03 * std::sin(2 * x) * std::cos(3 * y) + gauss(rng);
    c.positions.emplace_back(x, y, h);
  }
}

/// How many of the indices [from, to) `g` holds.
std::size_t countIn(const Ground& g, std::size_t from, std::size_t to) {
  std::size_t n = 0;
  for (std::uint32_t p : g.points) n += (p >= from && p < to) ? 1 : 0;
  return n;
}

TEST(Ground, LevelSlopedAndRoughTerrainIsSetAsideAndTheStemKept) {
  for (const double slope : {0.0, 0.3, 0.6}) {  // level, 17° and 31°
    std::mt19937 rng(7);
    geom::PointCloud c;
    addStem(c, 0.15, 0.0, 6.0, 0.01);
    const std::size_t stem = c.size();
    addTerrain(c, 3.0, slope, 0.01, 2500, 0.15, rng);
    const Ground g = findGround(c, geom::UpAxis::Z, 0.0);
    const std::size_t terrain = c.size() - stem;
    EXPECT_GE(countIn(g, stem, c.size()), static_cast<std::size_t>(0.98 * static_cast<double>(terrain)))
        << "slope " << slope;
    // The stem loses at most its foot: points within the height rule of the terrain.
    EXPECT_LE(countIn(g, 0, stem), stem / 40) << "slope " << slope;
    EXPECT_GT(g.columns, 24u);
  }
}

TEST(Ground, ATreeWithoutTerrainKeepsEveryPoint) {
  geom::PointCloud c;
  addStem(c, 0.15, 0.0, 6.0, 0.01);  // clipped at its foot: the bottom is a ring of bark
  // A level limb at 2 m, 0.3 m thick, sampled all round.
  for (double x = 0.2; x < 3.0; x += 0.01)
    for (int k = 0; k < 94; ++k) {
      const double a = 2 * std::numbers::pi * k / 94;
      c.positions.emplace_back(x, 0.3 * std::cos(a), 2.0 + 0.3 * std::sin(a));
    }
  // A crown with a flat, densely scanned underside at 3 m, 4 m across.
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> unit(-2.0, 2.0);
  for (int k = 0; k < 60000; ++k) {
    const double x = unit(rng), y = unit(rng);
    if (x * x + y * y > 4) continue;
    c.positions.emplace_back(x, y, 3.0 + 0.005 * unit(rng));
  }
  const Ground g = findGround(c, geom::UpAxis::Z, 0.0);
  EXPECT_TRUE(g.points.empty()) << g.points.size() << " points taken for ground";
}

TEST(Ground, AStemsCutFaceSeenFromBelowIsNotGround) {
  // A trunk capped at its foot, scanned from every side (the thesis's sphere pattern sees the cap
  // from below): a filled, level disc at the cloud's bottom, the stem's width, under a wide crown.
  geom::PointCloud c;
  addStem(c, 0.4, 0.0, 6.0, 0.005);
  for (double x = -0.4; x <= 0.4; x += 0.005)
    for (double y = -0.4; y <= 0.4; y += 0.005)
      if (x * x + y * y <= 0.16) c.positions.emplace_back(x, y, 0.0);
  for (int limb = 0; limb < 36; ++limb) {  // limbs out to 4 m all round
    const double a = 2 * std::numbers::pi * limb / 36;
    for (double r = 0.4; r <= 4.0; r += 0.005) c.positions.emplace_back(r * std::cos(a), r * std::sin(a), 4.0 + 0.3 * r);
  }
  const Ground g = findGround(c, geom::UpAxis::Z, 0.0);
  EXPECT_TRUE(g.points.empty()) << g.points.size() << " points taken for ground";
}

TEST(Ground, UpIsTheCloudsOwnAxis) {
  std::mt19937 rng(11);
  geom::PointCloud z;
  addStem(z, 0.15, 0.0, 6.0, 0.01);
  const std::size_t stem = z.size();
  addTerrain(z, 3.0, 0.1, 0.005, 2500, 0.15, rng);
  geom::PointCloud y;  // the same, Y up
  for (const Vec3& p : z.positions) y.positions.emplace_back(p.x(), p.z(), -p.y());
  const Ground gz = findGround(z, geom::UpAxis::Z, 0.0), gy = findGround(y, geom::UpAxis::Y, 0.0);
  EXPECT_GT(countIn(gy, stem, y.size()), static_cast<std::size_t>(0.98 * static_cast<double>(y.size() - stem)));
  EXPECT_NEAR(static_cast<double>(gy.points.size()), static_cast<double>(gz.points.size()),
              0.01 * static_cast<double>(gz.points.size()));
  // Read with the wrong up, the terrain is a wall: not ground.
  EXPECT_LT(findGround(z, geom::UpAxis::Y, 0.0).points.size(), stem / 10);
}

TEST(Ground, PointsTheFileClassifiesAsGroundAreGround) {
  geom::PointCloud c;
  addStem(c, 0.15, 0.0, 2.0, 0.01);
  c.classification.assign(c.size(), 1);
  for (std::size_t i = 0; i < 50; ++i) c.classification[i] = 2;
  const Ground g = findGround(c, geom::UpAxis::Z, 0.0);
  EXPECT_EQ(g.classified, 50u);
  ASSERT_EQ(g.points.size(), 50u);
  EXPECT_EQ(g.points.front(), 0u);
  GroundOptions off;
  off.enabled = false;
  EXPECT_TRUE(findGround(c, geom::UpAxis::Z, 0.0, off).points.empty());
}

TEST(Ground, JoinsTheStrayPointsAsGround) {
  std::mt19937 rng(5);
  geom::PointCloud c;
  addStem(c, 0.15, 0.0, 6.0, 0.01);
  const std::size_t stem = c.size();
  addTerrain(c, 2.0, 0.0, 0.005, 2500, 0.15, rng);
  c.positions.emplace_back(500.0, 0.0, 3.0);  // a stray, far out
  StrayPoints s = findStrayPoints(c);
  ASSERT_EQ(s.far, 1u);
  const Ground g = findGround(c, geom::UpAxis::Z, s.spacing);
  addGround(s, g.points);
  EXPECT_EQ(s.ground, g.points.size());
  EXPECT_EQ(s.far, 1u);
  EXPECT_EQ(s.count(), g.points.size() + 1);
  EXPECT_TRUE(std::is_sorted(s.setAside.begin(), s.setAside.end()));
  EXPECT_NE(strayPointsLine(s).find("on the ground"), std::string::npos);
  const geom::PointCloud kept = keptPoints(c, s);
  EXPECT_GE(kept.size(), stem - stem / 40);
  EXPECT_LE(kept.size(), stem);
}

// Points the file marks as noise are set aside whatever their place (on the stem, where no
// rule would find them; under the terrain; far above the crown), counted apart, and kept on request.
TEST(Ground, PointsTheFileMarksAsNoiseAreSetAsideFirstAndKeptOnRequest) {
  std::mt19937 rng(11);
  geom::PointCloud c;
  addStem(c, 0.15, 0.0, 6.0, 0.01);
  const std::size_t stem = c.size();
  addTerrain(c, 2.0, 0.0, 0.005, 2500, 0.15, rng);
  const std::size_t terrain = c.size() - stem;
  c.positions.emplace_back(0.5, 0.5, -1.5);   // a low point under the terrain
  c.positions.emplace_back(0.0, 0.0, 40.0);   // a high one over the crown
  c.positions.emplace_back(300.0, 0.0, 2.0);  // a stray the file did not mark
  c.classification.assign(c.size(), 1);
  std::vector<std::uint32_t> marked;
  for (std::size_t i = stem / 10; i < stem; i += 97) marked.push_back(static_cast<std::uint32_t>(i));  // on the stem,
  // above its foot (which the ground may take)
  marked.push_back(static_cast<std::uint32_t>(stem + terrain));
  marked.push_back(static_cast<std::uint32_t>(stem + terrain + 1));
  for (std::size_t k = 0; k < marked.size(); ++k)
    c.classification[marked[k]] = k % 3 ? kLowNoiseClass : kHighNoiseClass;

  const StrayPoints s = findStrayAndGroundPoints(c, geom::UpAxis::Z);
  EXPECT_EQ(s.markedNoise, marked.size());
  EXPECT_TRUE(std::is_sorted(s.setAside.begin(), s.setAside.end()));
  for (std::uint32_t m : marked) {
    const auto it = std::lower_bound(s.setAside.begin(), s.setAside.end(), m);
    ASSERT_TRUE(it != s.setAside.end() && *it == m) << m;
    EXPECT_EQ(s.reasons[static_cast<std::size_t>(it - s.setAside.begin())], StrayReason::MarkedNoise) << m;
  }
  EXPECT_EQ(s.far, 1u);  // the unmarked stray
  EXPECT_GT(s.ground, terrain / 2);
  EXPECT_EQ(s.count(), s.markedNoise + s.ground + s.far + s.isolated);
  EXPECT_NE(strayPointsLine(s).find(std::to_string(marked.size()) + " marked as noise by the file"), std::string::npos)
      << strayPointsLine(s);

  MarkedNoiseOptions keep;
  keep.enabled = false;
  const StrayPoints kept = findStrayAndGroundPoints(c, geom::UpAxis::Z, {}, {}, keep);
  EXPECT_EQ(kept.markedNoise, 0u);
  std::size_t stemSetAside = 0;
  for (std::uint32_t i : kept.setAside) stemSetAside += i < stem && c.classification[i] != 1;
  EXPECT_EQ(stemSetAside, 0u);  // the marked points on the stem stay in the model
  // Without marks the cloud gives what it gives with the option off.
  geom::PointCloud unmarked = c;
  unmarked.classification.clear();
  const StrayPoints plain = findStrayAndGroundPoints(unmarked, geom::UpAxis::Z);
  EXPECT_EQ(plain.setAside, kept.setAside);
  EXPECT_EQ(plain.reasons, kept.reasons);
}

TEST(Ground, OptionsOutOfRangeAreRefused) {
  geom::PointCloud c;
  addStem(c, 0.15, 0.0, 1.0, 0.01);
  GroundOptions o;
  o.subColumns = 1;
  EXPECT_THROW(findGround(c, geom::UpAxis::Z, 0.0, o), OptionsError);
  o = {};
  o.maxSlopeDeg = 90;
  EXPECT_THROW(findGround(c, geom::UpAxis::Z, 0.0, o), OptionsError);
}

}  // namespace
}  // namespace treesketch::cloud
