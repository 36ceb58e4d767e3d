// A fitted sketch's radii: fits checked against their limb, the rest inferred along it (see
// radius_inference.h). The pipe model (Shinozaki et al. 1964: a cross-section carries the wood
// above it, so its area grows with the length it carries) gives the shape of a limb's radii
// between and beyond its fits, as the automatic model's allometry does.
#include "treesketch/recon/radius_inference.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "treesketch/util/non_increasing_fit.h"

namespace treesketch::recon {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
/// Weight of a kept circle in a limb's taper fit: the fit goes around it (it is restored after).
constexpr double kKeptWeight = 1e3;
/// Each child's share of its parent's radius at an even fork under the pipe model: 1/√2.
constexpr double kEvenForkShare = 0.70710678118654752;

/// The model's node tree: nodes with a position, each joined to its nearest ancestor with one.
struct Tree {
  std::vector<RadiusSource> source;  ///< per input node: what it starts as (Fitted = a fit to check)
  std::vector<geom::Vec3> position;
  std::vector<int> parent;  ///< nearest ancestor with a position, -1 for none
  std::vector<std::vector<int>> children;
  std::vector<double> segment;  ///< length to `parent`
  std::vector<double> carried;  ///< the sketch's length below the node
  std::vector<std::vector<int>> chains;  ///< limbs, parent-first: a chain's fork is in an earlier one
};

bool usableFit(const fit::NodeResult& f) {
  return f.status == fit::NodeStatus::Fitted && f.radius > 0 && std::isfinite(f.radius) && f.centre.allFinite();
}

Tree buildTree(const std::vector<RadiusInput>& in) {
  const std::size_t n = in.size();
  Tree t;
  t.source.assign(n, RadiusSource::None);
  t.position.assign(n, geom::Vec3::Zero());
  t.parent.assign(n, -1);
  t.children.resize(n);
  t.segment.assign(n, 0.0);
  t.carried.assign(n, 0.0);
  std::map<NodeId, int> index;
  std::vector<int> nearest(n, -1);  // the node itself when it has a position, else its nearest ancestor's
  for (std::size_t i = 0; i < n; ++i) {
    const fit::NodeResult& f = *in[i].fit;
    // Where the node is, for the limbs' shape: a point node where the person put it (a fit may
    // have taken in a neighbour's surface), a screen node at its circle's depth.
    const bool pointNode = !in[i].geometry.hasLine && in[i].geometry.planePoint.allFinite();
    if (usableFit(f)) {
      t.source[i] = f.kept ? RadiusSource::Kept : RadiusSource::Fitted;
      t.position[i] = pointNode ? in[i].geometry.planePoint : f.centre;
    } else if (f.status == fit::NodeStatus::Skipped && pointNode && !f.testIndices.empty()) {
      // Its place is known and there are points there, its radius is not (a node with no point
      // near it is bridged: nothing there to model).
      t.source[i] = RadiusSource::Inferred;
      t.position[i] = in[i].geometry.planePoint;
    }
    const auto p = index.find(in[i].parent);
    const int up = p == index.end() ? -1 : nearest[static_cast<std::size_t>(p->second)];
    index[in[i].id] = static_cast<int>(i);
    if (t.source[i] == RadiusSource::None) {
      nearest[i] = up;
      continue;
    }
    nearest[i] = static_cast<int>(i);
    t.parent[i] = up;
    if (up >= 0) {
      t.children[static_cast<std::size_t>(up)].push_back(static_cast<int>(i));
      t.segment[i] = (t.position[i] - t.position[static_cast<std::size_t>(up)]).norm();
    }
  }
  for (std::size_t i = n; i-- > 0;)
    if (t.parent[i] >= 0) t.carried[static_cast<std::size_t>(t.parent[i])] += t.carried[i] + t.segment[i];
  return t;
}

/// Limbs: from each root and each child that does not continue its parent's limb, along the
/// child that continues it: the straightest one (a person sketches a stem or a limb further than
/// it has been drawn so far, so the length carried says little), at a root the one carrying most.
void buildChains(Tree& t) {
  const std::size_t n = t.source.size();
  auto mainChild = [&](std::size_t i) {
    int best = -1;
    double bestScore = -kInf;
    const int p = t.parent[i];
    const geom::Vec3 in = p >= 0 ? (t.position[i] - t.position[static_cast<std::size_t>(p)]).normalized() : geom::Vec3::Zero();
    for (int c : t.children[i]) {
      const double score = p >= 0 && in.allFinite() && t.segment[c] > 0
                               ? in.dot((t.position[c] - t.position[i]) / t.segment[c])
                               : t.carried[c] + t.segment[c];
      if (best < 0 || score > bestScore) {
        best = c;
        bestScore = score;
      }
    }
    return best;
  };
  std::vector<int> main(n, -1);
  for (std::size_t i = 0; i < n; ++i) main[i] = mainChild(i);
  for (std::size_t i = 0; i < n; ++i) {
    if (t.source[i] == RadiusSource::None) continue;
    const int p = t.parent[i];
    if (p >= 0 && main[static_cast<std::size_t>(p)] == static_cast<int>(i)) continue;
    std::vector<int> chain;
    for (int k = static_cast<int>(i); k >= 0; k = main[static_cast<std::size_t>(k)]) chain.push_back(k);
    t.chains.push_back(std::move(chain));
  }
}

double median(std::vector<double> v) {
  if (v.empty()) return std::numeric_limits<double>::quiet_NaN();
  std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
  return v[v.size() / 2];
}

/// The scan's noise as the sketch measures it: the median RMS residual of its fits (NaN with
/// fewer than three).
double sketchNoise(const std::vector<RadiusInput>& in, const Tree& t) {
  std::vector<double> rms;
  for (std::size_t i = 0; i < in.size(); ++i)
    if (t.source[i] == RadiusSource::Fitted) rms.push_back(in[i].fit->rms);
  return rms.size() >= 3 ? median(std::move(rms)) : std::numeric_limits<double>::quiet_NaN();
}

std::string figure(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g", v);
  return buf;
}

/// What makes fit `f` implausible against the radius `cap` of the node its limb grows from and
/// the scan's `noise`; "" when nothing does.
std::string implausibleAlone(const RadiusInput& n, double cap, bool side, double noise,
                             const RadiusInferenceOptions& o) {
  const fit::NodeResult& f = *n.fit;
  if (side && f.radius > o.maxSideOfParent * cap)
    return "the fit (radius " + figure(f.radius) + ") is wider than the node its limb grows from (" + figure(cap) + ")";
  if (!n.geometry.hasLine) {
    const double off = (f.centre - n.geometry.planePoint).norm() - f.radius;
    if (off > o.maxOffCircleRadii * f.radius + n.sliceHalfThickness)
      return "the fit's circle (radius " + figure(f.radius) + ") passes " + figure(off) + " from the node's point";
  }
  if (std::isfinite(noise) && f.rms > o.maxRmsOfNoise * noise && f.rms > o.maxRelativeRms * f.radius)
    return "the fit's residual (" + figure(f.rms) + ") is large against the scan's noise (" + figure(noise) + ")";
  return {};
}

/// Step 1 on a limb: which of its fits to use. Sets `why` for the fits set aside.
std::vector<char> acceptFits(const std::vector<RadiusInput>& in, const Tree& t, const std::vector<int>& chain, double cap,
                             bool side, double noise, const RadiusInferenceOptions& o, std::map<NodeId, NodeRadius>& out) {
  std::vector<char> ok(chain.size(), 0);
  for (std::size_t k = 0; k < chain.size(); ++k) {
    const std::size_t i = static_cast<std::size_t>(chain[k]);
    if (t.source[i] != RadiusSource::Fitted) continue;
    std::string why = implausibleAlone(in[i], cap, side, noise, o);
    ok[k] = why.empty();
    if (!ok[k]) out[in[i].id].why = std::move(why);
  }
  // Against the limb's other fits near it: a slice that took in a neighbouring limb or noise.
  std::vector<char> keep = ok;
  for (std::size_t k = 0; k < chain.size(); ++k) {
    if (!ok[k]) continue;
    std::vector<double> near;
    const std::size_t w = static_cast<std::size_t>(std::max(0, o.neighbourNodes));
    for (std::size_t j = k > w ? k - w : 0; j < chain.size() && j <= k + w; ++j)
      if (j != k && ok[j]) near.push_back(in[static_cast<std::size_t>(chain[j])].fit->radius);
    const double r = in[static_cast<std::size_t>(chain[k])].fit->radius;
    if (near.empty() || !(r > o.maxOfNeighbours * median(near))) continue;
    keep[k] = 0;
    out[in[static_cast<std::size_t>(chain[k])].id].why =
        "the fit (radius " + figure(r) + ") is much wider than the fits beside it on its limb (median " +
        figure(median(near)) + ")";
  }
  return keep;
}

/// Step 2 on a limb: radii where there is no accepted fit. Between and beyond the fits the ratio
/// of radius to the pipe model's shape (√ of the length carried) is interpolated by arc length,
/// so a limb tapers past its last fit; a limb with no fit takes the pipe model's share of `cap`.
/// Returns false when nothing gives a radius (no fit and no cap).
bool inferAlongLimb(const std::vector<RadiusInput>& in, const Tree& t, const std::vector<int>& chain,
                    const std::vector<char>& ok, int fork, double cap, std::vector<double>& r) {
  const std::size_t m = chain.size();
  std::vector<double> arc(m, 0.0), shape(m, 1.0);
  bool shaped = true;
  for (std::size_t k = 0; k < m; ++k) {
    const std::size_t i = static_cast<std::size_t>(chain[k]);
    if (k > 0) arc[k] = arc[k - 1] + t.segment[i];
    shape[k] = std::sqrt(t.carried[i] + t.segment[i]);
    shaped = shaped && shape[k] > 0;
  }
  if (!shaped) shape.assign(m, 1.0);
  std::vector<std::size_t> good;
  for (std::size_t k = 0; k < m; ++k)
    if (ok[k]) good.push_back(k);
  if (good.empty()) {
    if (fork < 0 || !std::isfinite(cap) || !(t.carried[static_cast<std::size_t>(fork)] > 0)) return false;
    // The fork's cross-section carries both limbs (r² = r_main² + r_side²) and the limb that goes
    // on is the thicker, so a side limb is at most 1/√2 of the fork even where the sketch has
    // drawn more of it than of the limb that goes on.
    const double forkShape = std::sqrt(t.carried[static_cast<std::size_t>(fork)]);
    const double share = std::min(shaped ? shape.front() / forkShape : 1.0, kEvenForkShare);
    for (std::size_t k = 0; k < m; ++k) r[static_cast<std::size_t>(chain[k])] = cap * share * shape[k] / shape.front();
    return true;
  }
  auto ratio = [&](std::size_t k) { return in[static_cast<std::size_t>(chain[k])].fit->radius / shape[k]; };
  for (std::size_t k = 0; k < m; ++k) {
    const std::size_t i = static_cast<std::size_t>(chain[k]);
    if (ok[k]) {
      r[i] = in[i].fit->radius;
      continue;
    }
    const auto after = std::lower_bound(good.begin(), good.end(), k);
    double v;
    if (after == good.begin() || after == good.end()) {
      v = ratio(after == good.end() ? good.back() : *after);
    } else {
      const std::size_t b = *after, a = *(after - 1);
      const double s = arc[b] > arc[a] ? (arc[k] - arc[a]) / (arc[b] - arc[a]) : 0.5;
      v = (1 - s) * ratio(a) + s * ratio(b);
    }
    r[i] = v * shape[k];
  }
  return true;
}

/// Step 3 on a limb: the least-absolute-deviations non-increasing radii towards the tip (kept circles as they
/// are), none above the node it grows from.
void taperLimb(const Tree& t, const std::vector<int>& chain, const std::vector<char>& ok, double cap,
               const RadiusInferenceOptions& o, std::vector<double>& r) {
  std::vector<double> values(chain.size()), weights(chain.size());
  for (std::size_t k = 0; k < chain.size(); ++k) {
    const std::size_t i = static_cast<std::size_t>(chain[k]);
    values[k] = r[i];
    weights[k] = t.source[i] == RadiusSource::Kept ? kKeptWeight : ok[k] ? 1.0 : o.inferredWeight;
  }
  util::nonIncreasingFit(values, weights);
  for (std::size_t k = 0; k < chain.size(); ++k) {
    const std::size_t i = static_cast<std::size_t>(chain[k]);
    if (t.source[i] != RadiusSource::Kept) r[i] = std::min(values[k], cap);
  }
}

NodeRadius circleOf(const RadiusInput& in, const Tree& t, std::size_t i, bool accepted, double radius) {
  NodeRadius c;
  c.normal = in.fit->normal;
  c.radius = radius;
  const bool pointNode = !in.geometry.hasLine;
  if (t.source[i] == RadiusSource::Kept) {
    c.source = RadiusSource::Kept;
    c.centre = in.fit->centre;
  } else if (accepted) {
    c.source = RadiusSource::Fitted;
    c.centre = in.fit->centre;
  } else {
    c.source = RadiusSource::Inferred;
    // A fit set aside may have taken in something else: a point node keeps the person's point.
    c.centre = pointNode ? in.geometry.planePoint : in.fit->centre;
    if (t.source[i] == RadiusSource::Inferred && in.fit->status == fit::NodeStatus::Skipped) c.why = in.fit->reason;
  }
  return c;
}

/// Without inference: fits and kept circles as they are, every other node bridged.
std::map<NodeId, NodeRadius> fitsAsTheyAre(const std::vector<RadiusInput>& in) {
  std::map<NodeId, NodeRadius> out;
  for (const RadiusInput& n : in) {
    NodeRadius c;
    if (usableFit(*n.fit)) {
      c.source = n.fit->kept ? RadiusSource::Kept : RadiusSource::Fitted;
      c.centre = n.fit->centre;
      c.normal = n.fit->normal;
      c.radius = n.fit->radius;
    }
    out[n.id] = c;
  }
  return out;
}

}  // namespace

const char* toString(RadiusSource source) {
  switch (source) {
    case RadiusSource::Fitted: return "fitted";
    case RadiusSource::Kept: return "kept";
    case RadiusSource::Inferred: return "inferred";
    case RadiusSource::None: return "none";
  }
  return "?";
}

std::map<NodeId, NodeRadius> inferRadii(const std::vector<RadiusInput>& in, const RadiusInferenceOptions& o) {
  if (!o.enabled) return fitsAsTheyAre(in);
  Tree t = buildTree(in);
  buildChains(t);
  const double noise = sketchNoise(in, t);
  std::vector<double> r(in.size(), 0.0);
  std::vector<char> hasRadius(in.size(), 0), accepted(in.size(), 0);
  std::map<NodeId, NodeRadius> out;
  for (const std::vector<int>& chain : t.chains) {
    const int fork = t.parent[static_cast<std::size_t>(chain.front())];
    const bool forkKnown = fork >= 0 && hasRadius[static_cast<std::size_t>(fork)];
    const double cap = forkKnown ? r[static_cast<std::size_t>(fork)] : kInf;
    std::vector<char> ok = acceptFits(in, t, chain, cap, fork >= 0, noise, o, out);
    for (std::size_t k = 0; k < chain.size(); ++k)
      if (t.source[static_cast<std::size_t>(chain[k])] == RadiusSource::Kept) ok[k] = 1;
    if (!inferAlongLimb(in, t, chain, ok, forkKnown ? fork : -1, cap, r)) continue;
    for (std::size_t k = 0; k < chain.size(); ++k) {
      const std::size_t i = static_cast<std::size_t>(chain[k]);
      if (t.source[i] == RadiusSource::Kept) r[i] = in[i].fit->radius;
    }
    taperLimb(t, chain, ok, cap, o, r);
    for (std::size_t k = 0; k < chain.size(); ++k) {
      const std::size_t i = static_cast<std::size_t>(chain[k]);
      hasRadius[i] = r[i] > 0 && std::isfinite(r[i]);
      accepted[i] = ok[k];
    }
  }
  for (std::size_t i = 0; i < in.size(); ++i) {
    std::string why = out[in[i].id].why;  // an implausible fit's, set by acceptFits
    NodeRadius c = hasRadius[i] ? circleOf(in[i], t, i, accepted[i], r[i]) : NodeRadius{};
    if (c.source == RadiusSource::Inferred && c.why.empty()) c.why = std::move(why);
    if (!hasRadius[i]) c.normal = in[i].fit->normal;
    out[in[i].id] = std::move(c);
  }
  return out;
}

std::string reasonKind(const std::string& reason) {
  static const std::pair<const char*, const char*> kKinds[] = {
      {"disabled", "disabled"},
      {"no points within", "no points in the slice"},
      {"too few points for the minimum support", "too few points for a circle"},
      {"fewer than 3 points", "too few points for a circle"},
      {"too few inliers", "too few points on the best circle"},
      {"degrees of the circle", "the points cover too little of a circle"},
      {"no admissible 3-point circle", "no circle through the points (in a line, or outside the radius bounds)"},
      {"centre lies outside", "the circle's centre lies outside the test region"},
      {"along the view ray from the parent", "circles refused at another depth or wider than the parent"},
      {"wider than the node its limb grows from", "fit wider than the node its limb grows from"},
      {"much wider than the fits beside it", "fit much wider than the fits beside it"},
      {"large against the scan's noise", "fit residual large against the scan's noise"},
      {"from the node's point", "fit circle away from the node"},
  };
  for (const auto& [key, kind] : kKinds)
    if (reason.find(key) != std::string::npos) return kind;
  return reason.empty() ? "no reason given" : reason;
}

FitSummary summarizeFits(const std::map<NodeId, fit::NodeResult>& results, const std::map<NodeId, NodeRadius>& radii,
                         const std::vector<NodeId>& ids) {
  std::vector<NodeId> all = ids;
  if (all.empty())
    for (const auto& [id, c] : radii) all.push_back(id);
  FitSummary s;
  for (NodeId id : all) {
    const auto f = results.find(id);
    const auto c = radii.find(id);
    if (f == results.end() || c == radii.end()) continue;
    ++s.nodes;
    const RadiusSource src = c->second.source;
    if (src == RadiusSource::Kept) {
      ++s.kept;
    } else if (src == RadiusSource::Fitted) {
      ++s.fitted;
    } else if (f->second.status == fit::NodeStatus::Disabled) {
      ++s.disabled;
    } else {
      s.inferred += src == RadiusSource::Inferred;
      ++s.notFitted[reasonKind(c->second.why.empty() ? f->second.reason : c->second.why)];
    }
  }
  return s;
}

std::string FitSummary::text() const {
  std::string t = std::to_string(fitted) + " of " + std::to_string(nodes) + " fitted";
  if (kept) t += ", " + std::to_string(kept) + " kept circles";
  if (disabled) t += ", " + std::to_string(disabled) + " disabled";
  for (const auto& [reason, n] : notFitted) t += "; " + std::to_string(n) + " not: " + reason;
  if (inferred) t += "; " + std::to_string(inferred) + " radii inferred from their limb";
  return t;
}

}  // namespace treesketch::recon
