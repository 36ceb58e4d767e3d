// Tree metrics of a cylinder model and its cloud (see the header for every figure's definition).
#include "treesketch/compare/tree_metrics.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <numbers>

#include "treesketch/util/error.h"

namespace treesketch::compare {

namespace {

/// Ground-plane coordinates of `p` (the two axes other than up).
geom::Vec2 ground(const geom::Vec3& p, geom::UpAxis up) {
  return up == geom::UpAxis::Y ? geom::Vec2(p.x(), p.z()) : geom::Vec2(p.x(), p.y());
}

nlohmann::json number(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); }

double cross(const geom::Vec2& o, const geom::Vec2& a, const geom::Vec2& b) {
  return (a.x() - o.x()) * (b.y() - o.y()) - (a.y() - o.y()) * (b.x() - o.x());
}

/// The stem's radius at height h (model units) and the axis point there: the thickest order-0
/// piece whose axis spans h.
bool stemAt(const geom::CylinderModel& model, const geom::BranchStructure& b, geom::UpAxis up, double h, double* radius,
            geom::Vec3* axisPoint) {
  double best = -1;
  for (std::size_t i = 0; i < model.size(); ++i) {
    if (b.order[i] != 0) continue;
    const auto& c = model.cylinders[i];
    const double h0 = geom::height(c.start, up), h1 = geom::height(c.end, up);
    if (h0 == h1 || h < std::min(h0, h1) || h > std::max(h0, h1)) continue;
    const double s = (h - h0) / (h1 - h0);
    const double r = c.startRadius + s * (c.endRadius - c.startRadius);
    if (r > best) {
      best = r;
      *axisPoint = c.start + s * (c.end - c.start);
    }
  }
  *radius = best;
  return best >= 0;
}

void checkOptions(const TreeMetricsOptions& o) {
  auto bad = [](double v) { return !std::isfinite(v) || v < 0; };
  if (!(o.unitMetres > 0) || !std::isfinite(o.unitMetres))
    throw OptionsError("tree metrics: unitMetres must be > 0, got " + std::to_string(o.unitMetres));
  if (bad(o.breastHeight) || bad(o.sliceHalfWidth) || bad(o.stemRegionRadii) || !(o.taperStep > 0))
    throw OptionsError(
        "tree metrics: breast height, slice half-width and stem region must be >= 0 and the taper "
        "step > 0 metres");
}

void modelMetrics(const geom::CylinderModel& model, geom::UpAxis up, const TreeMetricsOptions& o, TreeMetrics* m) {
  const double u = o.unitMetres, u3 = u * u * u;
  const geom::BranchStructure b = geom::branchStructure(model, up);
  std::map<std::int32_t, OrderMetrics> orders;
  double top = -std::numeric_limits<double>::infinity();
  std::vector<geom::Vec2> hull;
  for (std::size_t i = 0; i < model.size(); ++i) {
    const auto& c = model.cylinders[i];
    OrderMetrics& om = orders[b.order[i]];
    om.order = b.order[i];
    ++om.pieces;
    om.length += c.length() * u;
    om.volume += c.volume() * u3;
    if (b.position[i] == 0) ++om.branches;
    top = std::max({top, geom::height(c.start, up), geom::height(c.end, up)});
    // The end discs' extents on the ground (four points each: enough for a crown of many pieces).
    for (const auto& [p, r] : {std::pair{c.start, c.startRadius}, std::pair{c.end, c.endRadius}}) {
      const geom::Vec2 g = ground(p, up);
      hull.insert(hull.end(), {g + geom::Vec2(r, 0), g - geom::Vec2(r, 0), g + geom::Vec2(0, r), g - geom::Vec2(0, r)});
    }
  }
  for (auto& [order, om] : orders) {
    m->orders.push_back(om);
    (order == 0 ? m->stemVolume : m->branchVolume) += om.volume;
    if (order == 0)
      m->stemLength = om.length;
    else
      m->branches += om.branches;
  }
  if (model.empty()) return;
  m->height = (top - m->figures.baseHeight) * u;
  convexHullFigures(std::move(hull), &m->crownArea, &m->crownSpread);
  m->crownArea *= u * u;
  m->crownSpread *= u;
  m->crownDiameter = 2 * std::sqrt(m->crownArea / std::numbers::pi);
  // The taper table of a tree: at most kMaxTaperSamples heights (a taller "tree" is a cloud in the
  // wrong units or with far outliers; its table would fill the memory, one row per metre).
  constexpr int kMaxTaperSamples = 2000;
  if (!(m->height / o.taperStep < kMaxTaperSamples)) return;
  for (int k = 0; k * o.taperStep <= m->height * (1 + 1e-12); ++k) {
    const double h = k * o.taperStep;
    double r = 0;
    geom::Vec3 axis;
    const bool ok = stemAt(model, b, up, m->figures.baseHeight + h / u, &r, &axis);
    m->taper.push_back({h, ok ? 2 * r * u : std::numeric_limits<double>::quiet_NaN()});
  }
  while (!m->taper.empty() && std::isnan(m->taper.back().diameter)) m->taper.pop_back();
}

CloudDbh cloudDbh(const geom::PointCloud& cloud, double base, const geom::CylinderModel& model, double modelBase,
                  geom::UpAxis up, const TreeMetricsOptions& o) {
  const double u = o.unitMetres;
  CloudDbh d;
  d.sliceHeight = o.breastHeight;
  const double h = base + o.breastHeight / u, half = o.sliceHalfWidth / u;
  // The stem region: around the model's stem axis at breast height, when there is one.
  double stemRadius = -1;
  geom::Vec3 axis;
  if (o.stemRegionRadii > 0 && !model.empty()) {
    const geom::BranchStructure b = geom::branchStructure(model, up);
    stemAt(model, b, up, modelBase + o.breastHeight / u, &stemRadius, &axis);
  }
  const double region = stemRadius >= 0 ? o.stemRegionRadii * stemRadius + 0.05 / u : 0;
  std::vector<geom::Vec2> slice;
  for (const geom::Vec3& p : cloud.positions) {
    if (std::abs(geom::height(p, up) - h) > half) continue;
    const geom::Vec2 g = ground(p, up);
    if (stemRadius >= 0 && (g - ground(axis, up)).norm() > region) continue;
    slice.push_back(g);
  }
  d.slicePoints = slice.size();
  fit::CircleFitOptions c = o.circle;
  c.inlierThreshold /= u;
  c.minRadius /= u;
  c.maxRadius /= u;
  const fit::CircleFitResult r = fit::fitCircleRansac(slice, c);
  d.ok = r.ok;
  d.reason = r.ok ? "" : (slice.empty() ? "no points in the slice" : r.reason);
  if (!r.ok) return d;
  d.inliers = r.inliers.size();
  d.diameter = 2 * r.radius * u;
  d.rms = r.rms * u;
  d.centre =
      up == geom::UpAxis::Y ? geom::Vec3(r.centre.x(), h, r.centre.y()) : geom::Vec3(r.centre.x(), r.centre.y(), h);
  return d;
}

void cloudMetrics(const geom::PointCloud& cloud, const geom::CylinderModel& model, geom::UpAxis up,
                  const TreeMetricsOptions& o, TreeMetrics* m) {
  const double u = o.unitMetres;
  m->hasCloud = true;
  m->cloudPoints = cloud.size();
  if (cloud.empty()) {
    m->cloudDbh.reason = "the cloud has no points";
    return;
  }
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  std::vector<geom::Vec2> g;
  g.reserve(cloud.size());
  for (const geom::Vec3& p : cloud.positions) {
    lo = std::min(lo, geom::height(p, up));
    hi = std::max(hi, geom::height(p, up));
    g.push_back(ground(p, up));
  }
  m->cloudHeight = (hi - lo) * u;
  convexHullFigures(std::move(g), &m->cloudCrownArea, &m->cloudCrownSpread);
  m->cloudCrownArea *= u * u;
  m->cloudCrownSpread *= u;
  m->cloudCrownDiameter = 2 * std::sqrt(m->cloudCrownArea / std::numbers::pi);
  m->cloudDbh = cloudDbh(cloud, lo, model, m->figures.baseHeight, up, o);
}

}  // namespace

void convexHullFigures(std::vector<geom::Vec2> p, double* area, double* spread) {
  *area = 0;
  *spread = 0;
  std::sort(p.begin(), p.end(), [](const geom::Vec2& a, const geom::Vec2& b) {
    return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y());
  });
  p.erase(std::unique(p.begin(), p.end()), p.end());
  if (p.size() < 2) return;
  // Relative to the first point: the area's cross products of coordinates 1e9 from the origin
  // are 1e18, whose rounding (128) swamped a crown of a few square metres; of differences (exact
  // for points this close) they are the crown's own size.
  const geom::Vec2 origin = p[0];
  for (geom::Vec2& q : p) q -= origin;
  // Andrew's monotone chain.
  std::vector<geom::Vec2> h(2 * p.size());
  std::size_t k = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    while (k >= 2 && cross(h[k - 2], h[k - 1], p[i]) <= 0) --k;
    h[k++] = p[i];
  }
  for (std::size_t i = p.size() - 1, t = k + 1; i > 0; --i) {
    while (k >= t && cross(h[k - 2], h[k - 1], p[i - 1]) <= 0) --k;
    h[k++] = p[i - 1];
  }
  h.resize(k - 1);
  double a = 0;
  for (std::size_t i = 0; i < h.size(); ++i) {
    const geom::Vec2& q = h[i];
    const geom::Vec2& r = h[(i + 1) % h.size()];
    a += q.x() * r.y() - r.x() * q.y();
    for (std::size_t j = i + 1; j < h.size(); ++j) *spread = std::max(*spread, (h[j] - q).norm());
  }
  *area = h.size() >= 3 ? std::abs(a) / 2 : 0;
}

TreeMetrics treeMetrics(const geom::CylinderModel& model, geom::UpAxis up, const TreeMetricsOptions& options,
                        const geom::PointCloud* cloud) {
  checkOptions(options);
  TreeMetrics m;
  m.unitMetres = options.unitMetres;
  m.figures = modelFigures(model, up, options.unitMetres, options.breastHeight);
  modelMetrics(model, up, options, &m);
  if (cloud) cloudMetrics(*cloud, model, up, options, &m);
  return m;
}

nlohmann::json toJson(const TreeMetrics& m) {
  nlohmann::json j;
  j["unitMetres"] = m.unitMetres;
  j["pieces"] = m.figures.cylinders;
  j["heightM"] = number(m.height);
  j["dbhModelM"] = number(m.figures.trunkDiameter);
  j["breastHeightM"] = m.figures.breastHeight;
  j["volumeM3"] = m.figures.volume;
  j["stemVolumeM3"] = m.stemVolume;
  j["branchVolumeM3"] = m.branchVolume;
  j["lengthM"] = m.figures.length;
  j["stemLengthM"] = m.stemLength;
  j["branches"] = m.branches;
  j["crownAreaM2"] = m.crownArea;
  j["crownDiameterM"] = m.crownDiameter;
  j["crownSpreadM"] = m.crownSpread;
  nlohmann::json orders = nlohmann::json::array();
  for (const auto& o : m.orders)
    orders.push_back({{"order", o.order},
                      {"branches", o.branches},
                      {"pieces", o.pieces},
                      {"lengthM", o.length},
                      {"volumeM3", o.volume}});
  j["orders"] = orders;
  nlohmann::json taper = nlohmann::json::array();
  for (const auto& t : m.taper) taper.push_back({{"heightM", t.height}, {"diameterM", number(t.diameter)}});
  j["taper"] = taper;
  if (m.hasCloud) {
    const CloudDbh& d = m.cloudDbh;
    j["cloud"] = {{"points", m.cloudPoints},
                  {"heightM", number(m.cloudHeight)},
                  {"crownAreaM2", number(m.cloudCrownArea)},
                  {"crownDiameterM", number(m.cloudCrownDiameter)},
                  {"crownSpreadM", number(m.cloudCrownSpread)},
                  {"dbh",
                   {{"ok", d.ok},
                    {"reason", d.reason},
                    {"sliceHeightM", d.sliceHeight},
                    {"slicePoints", d.slicePoints},
                    {"inliers", d.inliers},
                    {"diameterM", number(d.diameter)},
                    {"rmsM", number(d.rms)}}}};
  }
  return j;
}

namespace {

std::string fmt(const char* f, double v) {
  if (!std::isfinite(v)) return "-";
  char buf[64];
  std::snprintf(buf, sizeof buf, f, v);
  return buf;
}

}  // namespace

std::string metricsTable(const TreeMetrics& m) {
  std::string s;
  auto row = [&](const std::string& name, const std::string& value) {
    char buf[160];
    std::snprintf(buf, sizeof buf, "  %-34s %s\n", name.c_str(), value.c_str());
    s += buf;
  };
  row("height (model)", fmt("%.2f m", m.height));
  row("DBH at " + fmt("%.2g", m.figures.breastHeight) + " m (model)", fmt("%.1f cm", 100 * m.figures.trunkDiameter));
  if (m.hasCloud) {
    const CloudDbh& d = m.cloudDbh;
    row("height (cloud)", fmt("%.2f m", m.cloudHeight));
    if (d.ok)
      row("DBH (cloud slice)", fmt("%.1f cm", 100 * d.diameter) + " (" + std::to_string(d.inliers) + " of " +
                                   std::to_string(d.slicePoints) + " points within the band, rms " +
                                   fmt("%.1f mm", 1000 * d.rms) + ")");
    else
      row("DBH (cloud slice)", "none: " + d.reason);
  }
  row("wood volume", fmt("%.4f m³", m.figures.volume) + fmt(" (%.1f L)", 1000 * m.figures.volume));
  row("  stem / branches", fmt("%.4f", m.stemVolume) + fmt(" / %.4f m³", m.branchVolume));
  row("total length", fmt("%.2f m", m.figures.length) + fmt(" (stem %.2f m)", m.stemLength));
  row("branches (order >= 1)", std::to_string(m.branches));
  for (const auto& o : m.orders)
    row("  order " + std::to_string(o.order), std::to_string(o.branches) + " branches, " + fmt("%.2f m, ", o.length) +
                                                  fmt("%.4f m³", o.volume) + " (" + std::to_string(o.pieces) +
                                                  " pieces)");
  row("crown projection (model)",
      fmt("%.2f m², ", m.crownArea) + fmt("diameter %.2f m, ", m.crownDiameter) + fmt("spread %.2f m", m.crownSpread));
  if (m.hasCloud)
    row("crown projection (cloud)", fmt("%.2f m², ", m.cloudCrownArea) +
                                        fmt("diameter %.2f m, ", m.cloudCrownDiameter) +
                                        fmt("spread %.2f m", m.cloudCrownSpread));
  std::string taper;
  for (const auto& t : m.taper)
    taper += (taper.empty() ? "" : ", ") + fmt("%.0f m: ", t.height) + fmt("%.1f cm", 100 * t.diameter);
  row("stem taper (diameter)", taper.empty() ? "-" : taper);
  return s;
}

}  // namespace treesketch::compare
