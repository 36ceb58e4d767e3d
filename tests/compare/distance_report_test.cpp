#include "treesketch/compare/distance_report.h"

#include <gtest/gtest.h>

#include <cmath>

#include "treesketch/util/error.h"

namespace treesketch::compare {
namespace {

const double kInf = std::numeric_limits<double>::infinity();

TEST(DistanceReport, StatisticsOfKnownValues) {
  DistanceReport r = summarizeDistances({1, 2, 3, kInf, 4}, 200.0, 3);
  EXPECT_EQ(r.samplesUsed, 4u);
  EXPECT_EQ(r.samplesDropped, 1u);
  EXPECT_DOUBLE_EQ(r.min, 1);
  EXPECT_DOUBLE_EQ(r.max, 4);
  EXPECT_DOUBLE_EQ(r.mean, 2.5);
  EXPECT_DOUBLE_EQ(r.rms, std::sqrt(30.0 / 4));
  EXPECT_DOUBLE_EQ(r.diagonal, 200);
  EXPECT_DOUBLE_EQ(r.percent(r.max), 2.0);
  // Bins of width 1 over [1, 4]: {1}, {2}, {3, 4} (the last bin includes the maximum).
  EXPECT_DOUBLE_EQ(r.histogram.min, 1);
  EXPECT_DOUBLE_EQ(r.histogram.max, 4);
  EXPECT_EQ(r.histogram.counts, (std::vector<std::uint64_t>{1, 1, 2}));
}

TEST(DistanceReport, AllEqualAndAllDropped) {
  DistanceReport same = summarizeDistances({0.5, 0.5, 0.5}, 1.0, 4);
  EXPECT_EQ(same.histogram.counts, (std::vector<std::uint64_t>{3, 0, 0, 0}));
  EXPECT_DOUBLE_EQ(same.rms, 0.5);

  DistanceReport none = summarizeDistances({kInf, std::nan("")}, 1.0, 4);
  EXPECT_EQ(none.samplesUsed, 0u);
  EXPECT_EQ(none.samplesDropped, 2u);
  EXPECT_TRUE(std::isnan(none.max));
  EXPECT_TRUE(none.histogram.counts.empty());
  nlohmann::json j = toJson(none);
  EXPECT_TRUE(j["max"].is_null());
  EXPECT_TRUE(j["rmsPercent"].is_null());

  DistanceReport zeroDiag = summarizeDistances({1.0}, 0.0, 1);
  EXPECT_TRUE(std::isnan(zeroDiag.percent(1.0)));
}

TEST(DistanceReport, BadBinsThrow) { EXPECT_THROW(summarizeDistances({1.0}, 1.0, 0), OptionsError); }

TEST(DistanceReport, JsonHasCountsStatisticsPercentagesAndHistogram) {
  DistanceReport r = summarizeDistances({1, 3}, 50.0, 2);
  r.vertexSamples = 1;
  r.faceSamples = 1;
  nlohmann::json j = toJson(r);
  EXPECT_EQ(j["samples"]["used"], 2);
  EXPECT_EQ(j["samples"]["dropped"], 0);
  EXPECT_EQ(j["samples"]["vertex"], 1);
  EXPECT_EQ(j["samples"]["edge"], 0);
  EXPECT_DOUBLE_EQ(j["mean"].get<double>(), 2.0);
  EXPECT_DOUBLE_EQ(j["maxPercent"].get<double>(), 6.0);
  EXPECT_TRUE(j["maxDistance"].is_null());  // +inf: no search limit
  EXPECT_EQ(j["histogram"]["counts"], nlohmann::json::array({1, 1}));
  EXPECT_FALSE(j.contains("perSample"));
  r.distances = {1, kInf};
  r.sampleKinds = {SampleKind::Vertex, SampleKind::Face};
  r.sampleVertex = {7, -1};
  j = toJson(r);
  EXPECT_EQ(j["perSample"]["distance"][0], 1.0);
  EXPECT_TRUE(j["perSample"]["distance"][1].is_null());
  EXPECT_EQ(j["perSample"]["kind"][1], "face");
  EXPECT_EQ(j["perSample"]["vertex"][0], 7);
  // Round trip through text.
  EXPECT_EQ(nlohmann::json::parse(j.dump()), j);
}

}  // namespace
}  // namespace treesketch::compare
