// The fit report of a cloud against a cylinder model (through CylinderModelIndex, model_index.cpp)
// and the QSM figures (volume, length, trunk diameter at 1.3 m).
#include "treesketch/compare/model_fit.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "treesketch/util/error.h"

namespace treesketch::compare {

// ---- the report -------------------------------------------------------------------------------

namespace {

void checkUnit(double unitMetres) {
  if (!std::isfinite(unitMetres) || unitMetres <= 0)
    throw OptionsError("model fit: metres per cloud unit must be > 0, got " + std::to_string(unitMetres));
}

}  // namespace

ModelFitReport measureModelFit(const geom::PointCloud& cloud, const CylinderModelIndex& index,
                               const ModelFitOptions& options) {
  checkUnit(options.unitMetres);
  for (std::size_t i = 0; i < cloud.size(); ++i)
    if (!cloud.positions[i].allFinite())
      throw OptionsError("model fit: the cloud's point " + std::to_string(i) + " is NaN or infinite");
  const std::size_t n = cloud.size();
  std::vector<double> d(n);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 1024), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t i = r.begin(); i != r.end(); ++i) d[i] = index.signedDistance(cloud.positions[i]);
  });

  ModelFitReport rep;
  rep.points = n;
  rep.unitMetres = options.unitMetres;
  if (n > 0) {
    // Thresholds in cloud units; a point exactly at a threshold counts as within it.
    const double u = options.unitMetres;
    const double c1 = 0.01 / u, c2 = 0.02 / u, c5 = 0.05 / u;
    std::size_t w1 = 0, w2 = 0, w5 = 0, deep = 0, missed = 0;
    for (double v : d) {
      const double a = std::abs(v);
      w1 += a <= c1;
      w2 += a <= c2;
      w5 += a <= c5;
      deep += v < -c2;
      missed += v > c5;
    }
    const double dn = static_cast<double>(n);
    rep.within1cm = static_cast<double>(w1) / dn;
    rep.within2cm = static_cast<double>(w2) / dn;
    rep.within5cm = static_cast<double>(w5) / dn;
    rep.insideDeeper2cm = static_cast<double>(deep) / dn;
    rep.outsideFarther5cm = static_cast<double>(missed) / dn;
    std::vector<double> s = d;
    const std::size_t mid = n / 2;
    std::nth_element(s.begin(), s.begin() + mid, s.end());
    double median = s[mid];
    if (n % 2 == 0) median = 0.5 * (median + *std::max_element(s.begin(), s.begin() + mid));
    rep.medianSigned = median * u;  // +inf (every point missed by an empty model) stays +inf
  }
  if (options.keepDistances) rep.distances = std::move(d);
  return rep;
}

ModelFitReport measureModelFit(const geom::PointCloud& cloud, const geom::CylinderModel& model,
                               const ModelFitOptions& options) {
  checkUnit(options.unitMetres);
  return measureModelFit(cloud, CylinderModelIndex(model), options);
}

// ---- figures ----------------------------------------------------------------------------------

ModelFigures modelFigures(const geom::CylinderModel& model, geom::UpAxis up, double unitMetres,
                          double breastHeightMetres) {
  checkUnit(unitMetres);
  if (!std::isfinite(breastHeightMetres) || breastHeightMetres < 0)
    throw OptionsError("model figures: breast height must be >= 0 metres, got " + std::to_string(breastHeightMetres));
  ModelFigures f;
  f.cylinders = model.size();
  f.breastHeight = breastHeightMetres;
  double volume = 0, length = 0;
  bool hasOrders = false;
  for (const auto& c : model.cylinders) {
    volume += c.volume();
    length += c.length();
    hasOrders = hasOrders || c.branchOrder >= 0;
    const double lo = std::min(geom::height(c.start, up), geom::height(c.end, up));
    if (!(lo >= f.baseHeight)) f.baseHeight = lo;  // also replaces the initial NaN
  }
  f.volume = volume * unitMetres * unitMetres * unitMetres;
  f.length = length * unitMetres;
  if (model.empty()) return f;

  // The trunk at breast height: the pieces whose axis spans that height (a piece lying flat at
  // exactly that height has no single crossing point and is left out).
  const double h = f.baseHeight + breastHeightMetres / unitMetres;
  double bestRadius = -1;
  for (int pass = 0; pass < 2 && f.trunkPiece < 0; ++pass) {
    // First the trunk's pieces (branch order 0) when the model gives orders, then any piece.
    if (pass == 0 && !hasOrders) continue;
    for (std::size_t i = 0; i < model.size(); ++i) {
      const auto& c = model.cylinders[i];
      if (pass == 0 && c.branchOrder != 0) continue;
      const double h0 = geom::height(c.start, up), h1 = geom::height(c.end, up);
      if (h0 == h1 || h < std::min(h0, h1) || h > std::max(h0, h1)) continue;
      const double s = (h - h0) / (h1 - h0);
      const double r = c.startRadius + s * (c.endRadius - c.startRadius);
      if (r > bestRadius) {
        bestRadius = r;
        f.trunkPiece = static_cast<std::int64_t>(i);
      }
    }
  }
  if (f.trunkPiece >= 0) f.trunkDiameter = 2 * bestRadius * unitMetres;
  return f;
}

// ---- output -----------------------------------------------------------------------------------

namespace {

nlohmann::json number(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); }

std::string percent(double share) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.1f %%", 100.0 * share);
  return buf;
}

}  // namespace

nlohmann::json toJson(const ModelFitReport& r) {
  nlohmann::json j;
  j["points"] = r.points;
  j["unitMetres"] = r.unitMetres;
  j["within1cm"] = number(r.within1cm);
  j["within2cm"] = number(r.within2cm);
  j["within5cm"] = number(r.within5cm);
  j["insideDeeper2cm"] = number(r.insideDeeper2cm);
  j["outsideFarther5cm"] = number(r.outsideFarther5cm);
  j["medianSignedDistanceM"] = number(r.medianSigned);
  return j;
}

nlohmann::json toJson(const ModelFigures& f) {
  nlohmann::json j;
  j["cylinders"] = f.cylinders;
  j["volumeM3"] = f.volume;
  j["lengthM"] = f.length;
  j["baseHeight"] = number(f.baseHeight);
  j["breastHeightM"] = f.breastHeight;
  j["trunkDiameterM"] = number(f.trunkDiameter);
  j["trunkPiece"] = f.trunkPiece;
  return j;
}

std::string summaryLine(const ModelFitReport& r) {
  if (r.points == 0) return "no points measured";
  char median[48];
  if (std::isfinite(r.medianSigned))
    std::snprintf(median, sizeof median, "%+.2f cm", 100.0 * r.medianSigned);
  else
    std::snprintf(median, sizeof median, "none (no model)");
  return percent(r.within2cm) + " within ±2 cm (±1: " + percent(r.within1cm) + ", ±5: " + percent(r.within5cm) + "), " +
         percent(r.outsideFarther5cm) + " missed (> 5 cm outside), " + percent(r.insideDeeper2cm) +
         " > 2 cm inside, median signed distance " + median;
}

std::string summaryLine(const ModelFigures& f) {
  char buf[256];
  char dbh[64];
  if (std::isfinite(f.trunkDiameter))
    std::snprintf(dbh, sizeof dbh, "%.1f cm", 100.0 * f.trunkDiameter);
  else
    std::snprintf(dbh, sizeof dbh, "none (no piece crosses it)");
  std::snprintf(buf, sizeof buf, "volume %.4f m³ (%.1f L), length %.2f m, trunk diameter at %.2g m %s (%zu pieces)",
                f.volume, 1000.0 * f.volume, f.length, f.breastHeight, dbh, f.cylinders);
  return buf;
}

}  // namespace treesketch::compare
