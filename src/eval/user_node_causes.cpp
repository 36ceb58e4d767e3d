// Why a simulated careful user's node found no circle (see the header).
#include "treesketch/eval/user_node_causes.h"

#include <sstream>

#include "treesketch/fit/cloud_index.h"
#include "treesketch/util/error.h"

namespace treesketch::eval {

const char* toString(NodeCause cause) {
  switch (cause) {
    case NodeCause::Fitted:
      return "fitted";
    case NodeCause::OffLimb:
      return "off-limb";
    case NodeCause::Hidden:
      return "hidden";
    case NodeCause::ClassedLeaf:
      return "classed-leaf";
    case NodeCause::Rejected:
      return "rejected";
  }
  return "?";
}

std::string rejectionTest(const std::string& reason) {
  auto has = [&](const char* s) { return reason.find(s) != std::string::npos; };
  if (has("no points within")) return "empty slice";
  if (has("fewer than 3 points") || has("too few points for the minimum support")) return "too few points";
  if (has("no admissible 3-point circle")) return "no admissible circle";
  if (has("too few inliers")) return "support";
  if (has("centre lies outside")) return "centre off the line";
  if (has("cover only")) return "arc";
  if (has("along the view ray") || has("wider than the parent")) return "depth choice";
  return "other";
}

namespace {

void checkInput(const NodeCauseInput& in) {
  if (in.truth.size() != in.sketch.size())
    throw OptionsError("node causes: " + std::to_string(in.truth.size()) + " true nodes for a sketch of " +
                       std::to_string(in.sketch.size()) + " nodes");
  if (in.kept.size() != in.cloud.size() || in.cloud.meshId.size() != in.cloud.size())
    throw OptionsError("node causes: the kept flags and the scanner's labels must have one entry per point");
}

// The points of `cloud` that the flags keep (the fit's cloud).
geom::PointCloud keptCloud(const geom::PointCloud& cloud, const std::vector<std::uint8_t>& kept) {
  geom::PointCloud out;
  out.up = cloud.up;
  for (std::size_t i = 0; i < cloud.size(); ++i)
    if (kept[i]) out.positions.push_back(cloud.positions[i]);
  return out;
}

// The node's slab around the limb's true point.
fit::SliceRegion limbRegion(const sketch::NodeGeometry& g, const sketch::SamplingParams& p, const TrueNode& t,
                            double nearRadii) {
  fit::SliceRegion r = fit::slabRegion(g, p);
  r.kind = fit::SliceRegion::Kind::Ball;
  r.linePoint = t.point;
  r.radius = nearRadii * t.radius + p.sliceHalfThickness;
  return r;
}

double distanceToLine(const geom::Vec3& p, const sketch::NodeGeometry& g) {
  if (!g.hasLine) return (p - g.planePoint).norm();
  const geom::Vec3 d = g.lineDir.normalized();
  const geom::Vec3 r = p - g.linePoint;
  return (r - d * d.dot(r)).norm();
}

}  // namespace

std::vector<NodeCauseRecord> userNodeCauses(const NodeCauseInput& in, const NodeCauseOptions& options) {
  checkInput(in);
  const geom::PointCloud fitCloud = keptCloud(in.cloud, in.kept);
  const fit::CloudIndex fitIndex(fitCloud);
  std::vector<NodeCauseRecord> out;
  std::size_t k = 0;
  for (const auto& [id, node] : in.sketch.nodes()) {
    const TrueNode& t = in.truth[k++];
    const sketch::NodeGeometry g = in.sketch.geometry(id);
    NodeCauseRecord rec;
    rec.id = id;
    rec.radius = t.radius;
    rec.offAxis = distanceToLine(t.point, g);
    for (std::uint32_t i : fit::sliceBruteForce(in.cloud, limbRegion(g, node.params, t, options.nearRadii))) {
      if (in.cloud.meshId[i] != 0) continue;
      ++rec.woodPoints;
      rec.classedWood += in.kept[i] != 0;
    }
    auto res = in.results.find(id);
    if (res != in.results.end() && res->second.status == fit::NodeStatus::Fitted) {
      rec.cause = NodeCause::Fitted;
      rec.onLimb =
          (res->second.centre - t.point).norm() <= options.nearRadii * t.radius + node.params.sliceHalfThickness;
    } else if (rec.offAxis > node.params.lineEpsilon) {
      rec.cause = NodeCause::OffLimb;
    } else if (rec.woodPoints < options.fewPoints) {
      rec.cause = NodeCause::Hidden;
    } else if (rec.classedWood < options.fewPoints) {
      rec.cause = NodeCause::ClassedLeaf;
    } else {
      rec.cause = NodeCause::Rejected;
      sketch::SamplingParams first = node.params;
      first.maxGrowthSteps = 0;
      fit::NodeFitOptions fo = in.fit;
      fo.circle.seed = in.fit.circle.seed + std::uint64_t(std::int64_t(id));  // as recon seeds each node
      const fit::NodeResult once = fitNode(fitIndex, g, first, fo);
      // Fitted alone, the first region holds a circle the node's own fit refused: its parent's prior.
      rec.test = once.status == fit::NodeStatus::Fitted ? "depth choice" : rejectionTest(once.reason);
    }
    out.push_back(rec);
  }
  return out;
}

NodeCauseCounts countCauses(const std::vector<NodeCauseRecord>& records) {
  NodeCauseCounts c;
  for (const auto& r : records) {
    ++c.causes[r.cause];
    c.onLimb += r.onLimb;
    if (r.cause == NodeCause::Rejected) ++c.tests[r.test];
  }
  return c;
}

std::string NodeCauseCounts::text() const {
  std::ostringstream s;
  auto fitted = causes.find(NodeCause::Fitted);
  s << "fitted " << (fitted == causes.end() ? 0 : fitted->second) << " (on its limb " << onLimb << "); skipped: ";
  bool first = true;
  for (NodeCause cause : {NodeCause::OffLimb, NodeCause::Hidden, NodeCause::ClassedLeaf, NodeCause::Rejected}) {
    auto it = causes.find(cause);
    s << (first ? "" : ", ") << toString(cause) << " " << (it == causes.end() ? 0 : it->second);
    first = false;
  }
  if (!tests.empty()) {
    s << " (";
    bool firstTest = true;
    for (const auto& [test, n] : tests) {
      s << (firstTest ? "" : ", ") << test << " " << n;
      firstTest = false;
    }
    s << ")";
  }
  return s.str();
}

}  // namespace treesketch::eval
