// Signed distances to cylinder models, the fit report's shares and median, the QSM figures.
#include "treesketch/compare/model_fit.h"

#include <gtest/gtest.h>
#include <tbb/parallel_for.h>

#include "test_support.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>

#include "treesketch/util/error.h"

namespace treesketch::compare {
namespace {

using geom::CylinderModel;
using geom::ModelCylinder;
using geom::Vec3;

using test::modelPiece;

// A cylinder along z from 0 to 2, radius 0.5.
const ModelCylinder kCyl = modelPiece({0, 0, 0}, {0, 0, 2}, 0.5, 0.5);

TEST(ModelFitDistance, CylinderOnInsideOutside) {
  EXPECT_DOUBLE_EQ(signedDistance({0.5, 0, 1}, kCyl), 0.0);             // on the side
  EXPECT_DOUBLE_EQ(signedDistance({0, -0.5, 1.5}, kCyl), 0.0);          // on the side, another azimuth
  EXPECT_DOUBLE_EQ(signedDistance({0.2, 0, 2}, kCyl), 0.0);             // on the end cap
  EXPECT_DOUBLE_EQ(signedDistance({0.2, 0, 1}, kCyl), -0.3);            // inside, nearest the side
  EXPECT_DOUBLE_EQ(signedDistance({0, 0, 0.1}, kCyl), -0.1);            // inside, nearest the start cap
  EXPECT_DOUBLE_EQ(signedDistance({0, 0, 1}, kCyl), -0.5);              // on the axis, mid-length
  EXPECT_DOUBLE_EQ(signedDistance({1.5, 0, 1}, kCyl), 1.0);             // outside, beside
  EXPECT_DOUBLE_EQ(signedDistance({0, 0, 3}, kCyl), 1.0);               // beyond the end, on the axis
  EXPECT_DOUBLE_EQ(signedDistance({0.3, 0, -0.25}, kCyl), 0.25);        // below the start cap
  EXPECT_DOUBLE_EQ(signedDistance({1.5, 0, 3}, kCyl), std::sqrt(2.0));  // past the rim
  // Rotated: the same cylinder along (1,1,1) from (1,2,3).
  const Vec3 u = Vec3(1, 1, 1).normalized(), n = Vec3(1, -1, 0).normalized();
  const ModelCylinder tilted = modelPiece({1, 2, 3}, Vec3(1, 2, 3) + 2 * u, 0.5, 0.5);
  EXPECT_NEAR(signedDistance(Vec3(1, 2, 3) + u + 0.2 * n, tilted), -0.3, 1e-12);
  EXPECT_NEAR(signedDistance(Vec3(1, 2, 3) + u + 1.5 * n, tilted), 1.0, 1e-12);
  EXPECT_NEAR(signedDistance(Vec3(1, 2, 3) + 3 * u + 1.5 * n, tilted), std::sqrt(2.0), 1e-12);
}

TEST(ModelFitDistance, Frustum) {
  // Radius 1 at z = 0 to 0.5 at z = 2: in the (t, ρ) plane the side runs (0,1) → (2,0.5), direction
  // (2,-0.5), length sqrt(4.25).
  const ModelCylinder f = modelPiece({0, 0, 0}, {0, 0, 2}, 1.0, 0.5);
  const double e = std::sqrt(4.25);
  EXPECT_NEAR(signedDistance({2, 0, 1}, f), 2.5 / e, 1e-12);                   // beside: (t,ρ)=(1,2), |w×e|/|e|
  EXPECT_NEAR(signedDistance({0, 0, 1}, f), -1.5 / e, 1e-12);                  // on the axis: to the side, not a cap
  EXPECT_NEAR(signedDistance({0.75, 0, 1}, f), 0.0, 1e-12);                    // on the side: r(1) = 0.75
  EXPECT_NEAR(signedDistance({0.8, 0, 1}, f), 0.05 * 2 / e, 1e-12);            // 0.05 out radially, slant 2/√4.25
  EXPECT_NEAR(signedDistance({0.9, 0, 2.1}, f), std::hypot(0.1, 0.4), 1e-12);  // past the thin rim
  EXPECT_NEAR(signedDistance({0.6, 0, -0.3}, f), 0.3, 1e-12);                  // below the wide cap
  // Volume: π L (r0² + r0 r1 + r1²) / 3.
  EXPECT_NEAR(f.volume(), std::numbers::pi * 2 * (1 + 0.5 + 0.25) / 3, 1e-12);
  EXPECT_NEAR(kCyl.volume(), std::numbers::pi * 0.25 * 2, 1e-12);
  // A zero-length piece has no surface.
  EXPECT_TRUE(std::isinf(signedDistance({0, 0, 0}, modelPiece({1, 1, 1}, {1, 1, 1}, 1, 1))));
}

TEST(ModelFitDistance, UnionAtJoints) {
  // A straight joint: two pieces along z, the second the first's child.
  CylinderModel straight;
  straight.cylinders = {modelPiece({0, 0, 0}, {0, 0, 1}, 0.5, 0.5), modelPiece({0, 0, 1}, {0, 0, 2}, 0.5, 0.5, 0)};
  const CylinderModelIndex si(straight);
  EXPECT_NEAR(si.signedDistance({0.5, 0, 1}), 0.0, 1e-12);
  EXPECT_NEAR(si.signedDistance({0.7, 0, 1}), 0.2, 1e-12);
  // Inside next to the joint: as deep as the side says, not 0.05 from the joined caps.
  EXPECT_NEAR(si.signedDistance({0.1, 0, 0.95}), -0.4, 1e-12);
  EXPECT_NEAR(si.signedDistance({0.2, 0, 1.0}), -0.3, 1e-12);
  // The free caps still count.
  EXPECT_NEAR(si.signedDistance({0, 0, 0.05}), -0.05, 1e-12);
  EXPECT_NEAR(si.signedDistance({0, 0, 1.9}), -0.1, 1e-12);
  EXPECT_NEAR(si.signedDistance({0, 0, 2.3}), 0.3, 1e-12);
  // Without the parent link every cap counts (the documented fallback).
  CylinderModel unlinked = straight;
  unlinked.cylinders[1].parent = -1;
  EXPECT_NEAR(CylinderModelIndex(unlinked).signedDistance({0.1, 0, 0.95}), -0.05, 1e-12);

  // A bend: up, then along x. Outside the corner the union's distance is the nearer piece's
  // (the first piece's rim), not the second's cap.
  CylinderModel bend;
  bend.cylinders = {modelPiece({0, 0, 0}, {0, 0, 1}, 0.2, 0.2), modelPiece({0, 0, 1}, {1, 0, 1}, 0.2, 0.2, 0)};
  const CylinderModelIndex bi(bend);
  std::int64_t which = -2;
  EXPECT_NEAR(bi.signedDistance({-0.3, 0, 1.1}, &which), std::hypot(0.1, 0.1), 1e-12);
  EXPECT_EQ(which, 0);
  // Past the first piece's end cap, on the second piece's upper side: on the union's surface
  // (0.2 from the first piece's cap).
  EXPECT_NEAR(bi.signedDistance({0.1, 0, 1.2}, &which), 0.0, 1e-12);
  EXPECT_EQ(which, 1);
  // Inside the second piece, off the first: depth from the second's side.
  EXPECT_NEAR(bi.signedDistance({0.5, 0, 1.05}, &which), -0.15, 1e-12);
  EXPECT_EQ(which, 1);
}

TEST(ModelFitIndex, MatchesBruteForce) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> pos(-1, 1), rad(0.0, 0.08), len(0.02, 0.3);
  CylinderModel m;
  for (int i = 0; i < 400; ++i) {
    const Vec3 a(pos(rng), pos(rng), pos(rng));
    const Vec3 dir = Vec3(pos(rng), pos(rng), pos(rng)).normalized();
    m.cylinders.push_back(modelPiece(a, a + len(rng) * dir, rad(rng), rad(rng)));
  }
  m.cylinders.push_back(modelPiece({5, 5, 5}, {5, 5, 5}, 1, 1));  // zero length: left out
  const CylinderModelIndex index(m);
  EXPECT_EQ(index.size(), 400u);
  std::uniform_real_distribution<double> q(-3, 3);
  for (int i = 0; i < 3000; ++i) {
    const Vec3 p = i < 1500 ? Vec3(pos(rng), pos(rng), pos(rng)) : Vec3(q(rng), q(rng), q(rng));
    double brute = std::numeric_limits<double>::infinity();
    for (const auto& c : m.cylinders) brute = std::min(brute, signedDistance(p, c));
    std::int64_t idx = -1;
    ASSERT_EQ(index.signedDistance(p, &idx), brute) << i;
    ASSERT_GE(idx, 0);
    EXPECT_EQ(signedDistance(p, m.cylinders[idx]), brute);
  }
  EXPECT_TRUE(std::isinf(CylinderModelIndex(CylinderModel{}).signedDistance({0, 0, 0})));
}

// nearPieces holds the piece nearest to every point within its reach (and signedDistanceAmong
// over them gives that point's signed distance), and every piece it names is within its bound.
TEST(ModelFitIndex, NearPiecesHoldTheNearestPieceOfEveryPointWithinReach) {
  std::mt19937_64 rng(12);
  const CylinderModel m = test::randomJoinedModel(11, 150);
  const CylinderModelIndex index(m);
  const std::vector<std::array<bool, 2>> open = jointCaps(m);
  std::uniform_real_distribution<double> pos(-1.3, 1.3), reachOf(0.0, 0.15), u(-1, 1);
  std::vector<CylinderModelIndex::NearPiece> near;
  int inside = 0, tiedOrMissing = 0;
  for (int i = 0; i < 2000; ++i) {
    // Half the points on a piece's axis or about it, half anywhere.
    const ModelCylinder& c = m.cylinders[rng() % m.size()];
    const Vec3 p = i % 2 ? Vec3(pos(rng), pos(rng), pos(rng))
                         : c.start + (0.5 + 0.6 * u(rng)) * (c.end - c.start) + 0.05 * Vec3(u(rng), u(rng), u(rng));
    const double reach = reachOf(rng);
    const double d = index.nearPieces(p, reach, near);
    ASSERT_EQ(d, index.signedDistance(p)) << i;
    // Exactly the pieces within max(d, 0) + 2 reach.
    std::vector<std::int64_t> expected, got;
    double brute = std::numeric_limits<double>::infinity();  // the pieces' own distances, to the bit
    for (std::size_t k = 0; k < m.size(); ++k) {
      const double own = signedDistance(p, m.cylinders[k], open[k][0], open[k][1]);
      brute = std::min(brute, own);
      if (own <= std::max(d, 0.0) + 2 * reach) expected.push_back(static_cast<std::int64_t>(k));
    }
    ASSERT_EQ(d, brute) << i;
    for (const auto& n : near) got.push_back(n.piece);
    std::sort(got.begin(), got.end());
    ASSERT_EQ(got, expected) << i;
    for (int j = 0; j < 10; ++j) {
      Vec3 step(u(rng), u(rng), u(rng));
      if (step.norm() > 1) step /= step.norm();
      const Vec3 q = p + reach * step;
      std::int64_t piece = -1, among = -1;
      bool tied = false;
      const double e = index.signedDistance(q, &piece);
      inside += e < 0;
      ASSERT_EQ(index.signedDistanceAmong(q, near, &among, &tied), e) << i << " " << j;
      tiedOrMissing += tied || std::find(got.begin(), got.end(), piece) == got.end();
      if (!tied) EXPECT_EQ(among, piece) << i << " " << j;
    }
  }
  EXPECT_GT(inside, 1000);       // the points inside the model were tried too
  EXPECT_EQ(tiedOrMissing, 0);   // ties are exact equalities: none on random points
  EXPECT_TRUE(std::isinf(CylinderModelIndex(CylinderModel{}).nearPieces({0, 0, 0}, 1, near)));
  EXPECT_TRUE(near.empty());
}

// The cells answer as the search does, value and piece, point for point: on random models of
// joined pieces, and on one whose pieces all come twice (every answer a tie, which the search
// decides), for points on, inside and about the pieces and anywhere, asked twice (the first time
// fills the cells), from several threads at once.
TEST(ModelFitIndex, CellsAnswerAsTheSearchDoes) {
  for (std::uint64_t seed = 21; seed <= 24; ++seed) {
    CylinderModel m = test::randomJoinedModel(seed, seed == 24 ? 40 : 200);
    if (seed == 24) {
      const std::size_t n = m.size();
      for (std::size_t k = 0; k < n; ++k) m.cylinders.push_back(m.cylinders[k]);
    }
    const CylinderModelIndex cells(m), plain(m, false);
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> pos(-1.3, 1.3), u(-1, 1);
    std::vector<Vec3> points(20000);
    for (std::size_t i = 0; i < points.size(); ++i) {
      const ModelCylinder& c = m.cylinders[rng() % m.size()];
      points[i] = i % 4 == 0 ? Vec3(pos(rng), pos(rng), pos(rng))
                             : c.start + (0.5 + 0.6 * u(rng)) * (c.end - c.start) +
                                   (i % 4 == 1 ? 0.02 : 0.12) * Vec3(u(rng), u(rng), u(rng));
    }
    std::vector<double> expected(points.size());
    std::vector<std::int64_t> expectedPiece(points.size());
    for (std::size_t i = 0; i < points.size(); ++i) expected[i] = plain.signedDistance(points[i], &expectedPiece[i]);
    for (int pass = 0; pass < 2; ++pass) {
      std::vector<double> got(points.size());
      std::vector<std::int64_t> gotPiece(points.size());
      tbb::parallel_for(std::size_t{0}, points.size(),
                        [&](std::size_t i) { got[i] = cells.signedDistance(points[i], &gotPiece[i]); });
      for (std::size_t i = 0; i < points.size(); ++i) {
        ASSERT_EQ(got[i], expected[i]) << seed << " " << pass << " " << i;
        ASSERT_EQ(gotPiece[i], expectedPiece[i]) << seed << " " << pass << " " << i;
      }
    }
  }
}

TEST(ModelFitIndex, RejectsBadPieces) {
  CylinderModel m;
  m.cylinders = {modelPiece({0, 0, 0}, {0, 0, 1}, -0.1, 0.1)};
  EXPECT_THROW(CylinderModelIndex{m}, OptionsError);
  m.cylinders = {modelPiece({0, 0, std::nan("")}, {0, 0, 1}, 0.1, 0.1)};
  EXPECT_THROW(CylinderModelIndex{m}, OptionsError);
  m.cylinders = {modelPiece({0, 0, 0}, {0, 0, 1}, 0.1, 0.1, 3)};
  EXPECT_THROW(CylinderModelIndex{m}, OptionsError);
}

TEST(ModelFitReport, SharesAndMedianInMetresAndMillimetres) {
  // Ten points at known signed distances from a cylinder of radius 0.1 m along z (0..10 m):
  // -0.03 -0.015 -0.005 0 0.005 0.015 0.03 0.045 0.07 1.0 (m).
  const double d[] = {-0.03, -0.015, -0.005, 0, 0.005, 0.015, 0.03, 0.045, 0.07, 1.0};
  CylinderModel m;
  m.cylinders = {modelPiece({0, 0, 0}, {0, 0, 10}, 0.1, 0.1)};
  for (double scale : {1.0, 1000.0}) {  // metres, then millimetres
    geom::PointCloud cloud;
    for (int i = 0; i < 10; ++i) cloud.positions.emplace_back(scale * (0.1 + d[i]), 0, scale * (1 + 0.5 * i));
    CylinderModel ms = m;
    for (auto& c : ms.cylinders) {
      c.start *= scale;
      c.end *= scale;
      c.startRadius *= scale;
      c.endRadius *= scale;
    }
    ModelFitOptions o;
    o.unitMetres = 1.0 / scale;
    o.keepDistances = true;
    const ModelFitReport r = measureModelFit(cloud, ms, o);
    EXPECT_EQ(r.points, 10u);
    EXPECT_DOUBLE_EQ(r.within1cm, 0.3);          // -0.005 0 0.005
    EXPECT_DOUBLE_EQ(r.within2cm, 0.5);          // and ±0.015
    EXPECT_DOUBLE_EQ(r.within5cm, 0.8);          // and ±0.03, 0.045
    EXPECT_DOUBLE_EQ(r.insideDeeper2cm, 0.1);    // -0.03
    EXPECT_DOUBLE_EQ(r.outsideFarther5cm, 0.2);  // 0.07, 1.0
    EXPECT_NEAR(r.medianSigned, 0.01, 1e-12);    // (0.005 + 0.015) / 2, metres
    ASSERT_EQ(r.distances.size(), 10u);
    EXPECT_NEAR(r.distances[9], scale * 1.0, 1e-9 * scale);
  }
  // An odd count takes the middle value; an empty model misses everything.
  geom::PointCloud three;
  three.positions = {{0.1, 0, 1}, {0.13, 0, 1}, {0.0, 0, 1}};
  EXPECT_NEAR(measureModelFit(three, m).medianSigned, 0.0, 1e-15);
  const ModelFitReport none = measureModelFit(three, CylinderModel{});
  EXPECT_DOUBLE_EQ(none.outsideFarther5cm, 1.0);
  EXPECT_TRUE(std::isinf(none.medianSigned));
  EXPECT_TRUE(toJson(none)["medianSignedDistanceM"].is_null());
  ModelFitOptions bad;
  bad.unitMetres = 0;
  EXPECT_THROW(measureModelFit(three, m, bad), OptionsError);
  const ModelFitReport empty = measureModelFit(geom::PointCloud{}, m);
  EXPECT_EQ(empty.points, 0u);
  EXPECT_TRUE(std::isnan(empty.within2cm));
}

TEST(ModelFitFigures, VolumeLengthTrunkDiameter) {
  // A trunk of two frustums from z = 0.5 (the base) to 2.5 m, a side branch from z = 1.5 that is
  // thicker at 1.8 m than the trunk, and one lower piece that sets the base.
  CylinderModel m;
  m.cylinders = {modelPiece({0, 0, 0.5}, {0, 0, 1.5}, 0.20, 0.16, -1, 0), modelPiece({0, 0, 1.5}, {0, 0, 2.5}, 0.16, 0.10, 0, 0),
                 modelPiece({0, 0, 1.5}, {1, 0, 2.0}, 0.30, 0.30, 0, 1)};
  const ModelFigures f = modelFigures(m, geom::UpAxis::Z);
  EXPECT_EQ(f.cylinders, 3u);
  const double v = m.cylinders[0].volume() + m.cylinders[1].volume() + m.cylinders[2].volume();
  EXPECT_NEAR(f.volume, v, 1e-12);
  EXPECT_NEAR(f.length, 2 + std::sqrt(1.25), 1e-12);
  EXPECT_DOUBLE_EQ(f.baseHeight, 0.5);
  // 1.3 m above the base = z 1.8: the trunk's second piece, 0.3 of the way: r = 0.16 - 0.3·0.06.
  EXPECT_EQ(f.trunkPiece, 1);
  EXPECT_NEAR(f.trunkDiameter, 2 * (0.16 - 0.3 * 0.06), 1e-12);
  // Without branch orders the thickest crossing piece is taken.
  CylinderModel noOrders = m;
  for (auto& c : noOrders.cylinders) c.branchOrder = -1;
  EXPECT_EQ(modelFigures(noOrders, geom::UpAxis::Z).trunkPiece, 2);
  // Millimetres: the same figures in metres.
  CylinderModel mm = m;
  for (auto& c : mm.cylinders) {
    c.start *= 1000;
    c.end *= 1000;
    c.startRadius *= 1000;
    c.endRadius *= 1000;
  }
  const ModelFigures g = modelFigures(mm, geom::UpAxis::Z, 0.001);
  EXPECT_NEAR(g.volume, v, 1e-9);
  EXPECT_NEAR(g.trunkDiameter, f.trunkDiameter, 1e-12);
  // Y up: nothing crosses y = 1.3 above the base (the model lies at y = 0).
  EXPECT_TRUE(std::isnan(modelFigures(m, geom::UpAxis::Y).trunkDiameter));
  EXPECT_THROW(modelFigures(m, geom::UpAxis::Z, -1), OptionsError);
  const nlohmann::json j = toJson(f);
  EXPECT_NEAR(j["trunkDiameterM"].get<double>(), f.trunkDiameter, 1e-15);
  EXPECT_NE(summaryLine(f).find("trunk diameter at 1.3 m 28.4 cm"), std::string::npos) << summaryLine(f);
}

}  // namespace
}  // namespace treesketch::compare
