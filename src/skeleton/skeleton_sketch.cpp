// Skeleton → sketch → fitted, regularised model. The pipe model is Shinozaki et al. 1964 (as used
// by Xu et al. 2007 for branch thickness); the node fit is the thesis's (fit module).
#include "treesketch/skeleton/skeleton_sketch.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <numbers>

#include "skeleton/axis_smoothing.h"
#include "skeleton/completion.h"
#include "skeleton/nearest_tube.h"
#include "skeleton/radius_allometry.h"
#include "skeleton/radius_rules.h"
#include "skeleton/range_noise.h"
#include "skeleton/stem_tracking.h"
#include "skeleton/surface_bound.h"
#include "treesketch/accel/point_index.h"
#include "treesketch/compare/model_fit.h"
#include "treesketch/compare/tree_metrics.h"
#include "treesketch/recon/reconstruction.h"
#include "treesketch/skeleton/skeleton_export.h"
#include "treesketch/util/error.h"
#include "treesketch/util/stopwatch.h"
#include "treesketch/util/union_find.h"

namespace treesketch::skeleton {
namespace {

using geom::Vec3;

/// Below this share of nodes with an accepted circle (and without a tracked stem) the circles do
/// not measure the tree and every radius is inferred from its crown (see fitModel).
constexpr double kMinFittedShare = 0.02;
/// The completion's margin about a tube, in robust spreads of its surface's points (or the scan's
/// noise, the larger): a normal spread leaves 0.3 % of a surface's points beyond three. Of 2, 3 and 4
/// on the tuning clouds (share within ±2 cm): 3 (4 left voxr_t0 under TreeQSM's share; 2 no better
/// than 3 on rtwig). A margin of the scan's noise alone, without the surface's own spread, grafted
/// the synthetic trees' polygon corners (docs/notes/radii_and_volume.md, "Completing the model down
/// to its circles").
constexpr double kMarginSpreads = 3.0;
/// ... and never under half a voxel: the model places an axis to about that (a level set's
/// centroid), so a point that close to the surface may be the surface's own. Without the floor the
/// synthetic trees' dense scans grafted twigs that are not there (tls-step-0.1, tuning half: backward
/// RMS 0.104 → 0.133 % of the diagonal; with it 0.113); a third of a voxel: 0.125.
constexpr double kMarginFloorVoxels = 0.5;

sketch::SamplingParams paramsFor(double radius, double voxel, const SkeletonSketchOptions& o) {
  sketch::SamplingParams p;
  p.sliceHalfThickness = std::max(o.sliceRadii * radius, o.sliceVoxels * voxel);
  p.lineEpsilon = o.lineRadii * radius + o.lineVoxels * voxel;
  p.lineEpsilonStep = o.stepRadii * radius + o.stepVoxels * voxel;
  p.maxGrowthSteps = autoNodeFitOptions().maxGrowthSteps;  // the same cap in the GUI and `reconstruct --sketch`
  return p;
}

}  // namespace

sketch::Sketch skeletonToSketch(const Skeleton& skeleton, const SkeletonSketchOptions& options) {
  sketch::Sketch s;
  s.up = skeleton.up;
  const double voxel = skeleton.graph.voxelSize > 0 ? skeleton.graph.voxelSize : 1.0;
  if (skeleton.nodes.empty()) return s;
  s.defaults = paramsFor(skeleton.nodes.front().radius, voxel, options);
  for (std::size_t i = 0; i < skeleton.nodes.size(); ++i) {
    const auto& n = skeleton.nodes[i];
    const sketch::NodeId parent = n.parent < 0 ? sketch::kNoNode : n.parent;
    const sketch::NodeId id = s.addPointNode(parent, n.position, n.direction, paramsFor(n.radius, voxel, options));
    if (id != static_cast<sketch::NodeId>(i)) throw OptionsError("skeleton: sketch ids out of step with nodes");
  }
  return s;
}

AutoSkeletonOptions autoSkeletonPreset(Foliage foliage, geom::UpAxis up) {
  AutoSkeletonOptions o;
  if (foliage == Foliage::LeafOn) {
    o.skeleton = leafOnSkeletonOptions(o.skeleton);
    o.completion.enabled = false;  // the points off the model leaf-on are leaves
  }
  o.skeleton.up = up;
  return o;
}

namespace {

void checkOptions(const AutoSkeletonOptions& options) {
  detail::checkRadiusRules(options.radii);
  if (!(options.maxFitFlatFraction >= 0 && options.maxFitFlatFraction <= 1))
    throw OptionsError("skeleton: maxFitFlatFraction must be in [0, 1]");
  if (!(options.minInlierBandVoxels >= 0) || !std::isfinite(options.minInlierBandVoxels))
    throw OptionsError("skeleton: minInlierBandVoxels must be a finite number >= 0");
  if (!(options.contractionNoises >= 0) || !std::isfinite(options.contractionNoises))
    throw OptionsError("skeleton: contractionNoises must be a finite number >= 0 (0 = off)");
  if (options.axes.halfWindowNodes < 0 || !(options.axes.unfittedWeight > 0 && options.axes.unfittedWeight <= 1) ||
      !(options.axes.maxShiftRadii >= 0) || !std::isfinite(options.axes.maxShiftRadii))
    throw OptionsError(
        "skeleton axes: halfWindowNodes must be >= 0, unfittedWeight in (0, 1], maxShiftRadii finite and >= 0");
  const CompletionRules& c = options.completion;
  if (!(c.marginVoxels >= 0) || !(c.maxGapVoxels >= 0) || !std::isfinite(c.marginVoxels) ||
      !std::isfinite(c.maxGapVoxels) || c.minPoints < 1 || c.maxParts < 0 || c.maxRounds < 0)
    throw OptionsError(
        "skeleton completion: marginVoxels and maxGapVoxels must be finite and >= 0, minPoints >= 1, maxParts and "
        "maxRounds >= 0");
}

recon::ReconstructionOptions reconstructionOptions(const AutoSkeletonOptions& options, double voxel) {
  recon::ReconstructionOptions ro;
  ro.fit = options.fit;
  ro.fit.circle.inlierThreshold = std::max(ro.fit.circle.inlierThreshold, options.minInlierBandVoxels * voxel);
  ro.sweep.ringVertices = options.ringVertices;
  ro.seed = options.seed;
  return ro;
}

/// Why node `node` is not fitted, or null when it is.
const char* notFitted(const SkeletonNode& node, const AutoSkeletonOptions& options) {
  if (isLeafPiece(node, options)) return "leaf piece (mostly flat voxels): not fitted";
  if (node.grafted) return "grafted twig beside its limb: not fitted";
  return nullptr;
}

/// Step 2: the fit pass. Every node but the leaf pieces and the grafted twigs is fitted from the
/// cloud by recon.
std::vector<fit::NodeResult> fitPass(recon::Reconstruction& rec, const sketch::Sketch& skeletonSketch,
                                     const std::vector<SkeletonNode>& nodes, const AutoSkeletonOptions& options,
                                     const ProgressFn& progress) {
  sketch::Sketch s = skeletonSketch;
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    if (!notFitted(nodes[i], options)) continue;
    const auto id = static_cast<sketch::NodeId>(i);
    sketch::SamplingParams p = s.node(id).params;
    p.enabled = false;
    s.setParams(id, p);
  }
  rec.fit(s, progress);  // the fits only: the tubes are swept once, from the final model
  std::vector<fit::NodeResult> fits(nodes.size());
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    if (const char* why = notFitted(nodes[i], options)) {
      fits[i].status = fit::NodeStatus::Skipped;
      fits[i].reason = why;
    } else {
      fits[i] = *rec.result(static_cast<sketch::NodeId>(i));
    }
  }
  return fits;
}

/// Whether the nodes on the tracked stem are put on the stem's axis (the tracked samples' polyline,
/// at the point nearest the node), whatever their fits and the smoothing say:
/// when the stem was found beside the root region (a conifer's, stem_tracking.h). Its axis is the
/// circles of slabs a radius tall, each whorl's seen as the bark in front of its limbs; a node's
/// slice at a whorl holds the limbs' bases beside the stem, and its circle took them in (on the
/// spruce in leaf 3-16 cm off the stem's axis). For every tracked stem, a broadleaf's fits at its
/// crown base measured better than the stem's slabs (adtree_tree7 -0.4 points within ±2 cm).
bool keepsStemAxis(const Skeleton& s) { return s.levels.stemBesideRoot; }

/// Step 3: which fits to trust (RadiusRules), moving accepted nodes to their fit centres.
std::vector<double> acceptFits(AutoSkeletonResult& res, const RadiusRules& rules, double voxel) {
  const auto& nodes = res.skeleton.nodes;
  const double slack = rules.slackVoxels * voxel;
  std::vector<double> fitted(nodes.size(), 0.0);
  res.fitAccepted.assign(nodes.size(), 0);
  res.model = nodes;
  const bool keepStem = keepsStemAxis(res.skeleton);
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    const auto& f = res.fits[i];
    if (f.status != fit::NodeStatus::Fitted) continue;
    const double est = nodes[i].radius;
    const bool ok = f.radius <= rules.maxRadiusRatio * est + slack &&
                    (f.centre - nodes[i].position).norm() <= rules.maxCentreShiftRadii * est + slack &&
                    f.rms <= rules.maxRelativeRms * f.radius + rules.rmsFloorVoxels * voxel;
    if (!ok) continue;
    res.fitAccepted[i] = 1;
    fitted[i] = f.radius;
    if (!(keepStem && nodes[i].stem)) res.model[i].position = f.centre;
  }
  return fitted;
}

/// Step 5: the model goes into the sketch, every node a kept circle (the model's position and
/// radius). Forks without an accepted fit were once disabled, so the children's tubes joined the
/// fork's parent ring; with the model's axes smoothed and its radii bounded by their points that
/// bridging made the synthetic scans' backward error larger, not smaller
/// (docs/notes/auto_sketch_options.md).
void handOver(AutoSkeletonResult& res) {
  for (std::size_t i = 0; i < res.model.size(); ++i) {
    const auto& node = res.model[i];
    res.sketch.setKeptCircle(static_cast<sketch::NodeId>(i), sketch::KeptCircle{node.position, node.radius});
  }
}

/// Steps 2.-4.: the sketch of `res.skeleton`, the fit pass by `rec`, and the model (accepted fits,
/// regularised radii, smoothed axes). `rec` re-fits only the nodes it has not fitted before.
/// Radii for a cloud where no circle could be fitted and no stem was measured (an airborne scan:
/// scaffold limbs as lines of points): the pipe model from a stem inferred from the crown. An
/// open-grown tree's crown is about 20–25 times as wide as its stem at breast height; the
/// crown's width is the diameter of the circle with the area of the cloud's ground projection.
/// Every radius is inferred (no fit is accepted), and the model says so.
std::vector<double> radiiFromTheCrown(const std::vector<SkeletonNode>& nodes, const geom::PointCloud& cloud,
                                      geom::UpAxis up) {
  constexpr double kCrownPerStemDiameter = 22.0;
  std::vector<geom::Vec2> ground;
  ground.reserve(cloud.size());
  for (const geom::Vec3& p : cloud.positions)
    ground.push_back(up == geom::UpAxis::Y ? geom::Vec2(p.x(), p.z()) : geom::Vec2(p.x(), p.y()));
  double area = 0, spread = 0;
  compare::convexHullFigures(std::move(ground), &area, &spread);
  const double crown = 2 * std::sqrt(area / std::numbers::pi);
  if (!(crown > 0) || !std::isfinite(crown)) return {};  // no crown: points on a line or a plane on edge
  return detail::pipeRadii(nodes, 0.5 * crown / kCrownPerStemDiameter);
}

void fitModel(AutoSkeletonResult& res, recon::Reconstruction& rec, const geom::PointCloud& cloud,
              const AutoSkeletonOptions& options, const ProgressFn& progress) {
  Stopwatch t0;
  res.sketch = skeletonToSketch(res.skeleton, options.sketch);
  const double voxel = res.skeleton.graph.voxelSize;
  res.fits = fitPass(rec, res.sketch, res.skeleton.nodes, options, progress);
  res.fitMs += t0.ms();

  t0.restart();
  std::vector<double> fitted = acceptFits(res, options.radii, voxel);
  // A handful of circles on a tree of hundreds of nodes is no measurement of it: a 4-station scan
  // of a bush at 0.4° steps under 25 mm of noise has 5 circles on 752 nodes (0.7 %), all round
  // the ring of its stems' bases, and the pipe law anchored on them made it 3.2 times its wood
  // (the crown: under 2.5). Every real scan in ../shared/data/real has 11 % or more of its nodes
  // fitted; adtree_tree1 thinned to 30 % of its points has 4.1 % (41 circles of 5-15 cm, residuals
  // of 2-5 mm), and with the share at 5 % lost its stem's circles to the crown's guess, a third of
  // its wood (docs/notes/radii_and_volume.md). Fewer circles than the pipe law needs to take its scale
  // from do not measure it either. A tracked stem is a measurement of its own.
  const bool stemMeasured = std::any_of(res.skeleton.nodes.begin(), res.skeleton.nodes.end(),
                                        [](const SkeletonNode& n) { return n.stem && n.radius > 0; });
  const auto accepted = std::count(res.fitAccepted.begin(), res.fitAccepted.end(), 1);
  const bool measured =
      stemMeasured || (accepted >= static_cast<std::ptrdiff_t>(detail::kMinAllometryAnchors) &&
                       static_cast<double>(accepted) >= kMinFittedShare * static_cast<double>(res.model.size()));
  if (!measured) {
    std::fill(res.fitAccepted.begin(), res.fitAccepted.end(), 0);
    std::fill(fitted.begin(), fitted.end(), 0.0);
    for (std::size_t i = 0; i < res.model.size(); ++i) res.model[i].position = res.skeleton.nodes[i].position;
  }
  std::vector<double> radii;
  if (!measured) radii = radiiFromTheCrown(res.skeleton.nodes, cloud, options.skeleton.up);
  res.radiiFromCrown = !radii.empty();
  res.radiusMeasured.assign(res.model.size(), 0);
  if (radii.empty())
    radii = regularizeRadii(res.skeleton.nodes, fitted, res.fitAccepted, options.radii, &res.radiusMeasured);
  const std::vector<geom::Vec3> axes = detail::smoothAxes(res.model, res.fitAccepted, radii, options.axes);
  const std::vector<detail::StemSample> stem =
      keepsStemAxis(res.skeleton) ? detail::trackedStem(res.skeleton.levels) : std::vector<detail::StemSample>{};
  for (std::size_t i = 0; i < res.model.size(); ++i) {
    res.model[i].radius = radii[i];
    res.model[i].position = axes[i];
    if (!stem.empty() && res.model[i].stem)
      res.model[i].position = detail::stemAt(stem, res.skeleton.nodes[i].position).centre;
  }
  res.sweepMs += t0.ms();
}

/// Step 4b (CompletionRules): the points the model leaves out, cut into connected parts (the
/// voxel graph's components at the model's voxel size); each part's skeleton, largest first, is
/// grafted onto the skeleton. Returns whether any was. `unexplained` holds the indices of the
/// points left out by the previous round (empty before the first): a round only adds to the model
/// (the model's nodes keep their circles), so a point explained once stays explained and later
/// rounds measure only the points left out before.
bool complete(const geom::PointCloud& cloud, const AutoSkeletonOptions& options, AutoSkeletonResult& res,
              std::vector<std::uint32_t>& unexplained, int round) {
  const CompletionRules& c = options.completion;
  if (!c.enabled || res.model.size() < 2 || c.maxParts == 0 || c.maxRounds == 0) return false;
  const Stopwatch t0;
  const double voxel = res.skeleton.graph.voxelSize;
  SkeletonOptions partOptions = options.skeleton;
  partOptions.graph.voxelSize = voxel;  // the same scale as the model's
  partOptions.trackStem = false;        // a part is a branch, not a tree
  // Sparse links no longer than a graft's gap: scattered clusters are parts of their own, each
  // grafted where it is, not one part bridged across the crown (straight tubes through the air).
  partOptions.graph.maxGapVoxels = std::min(partOptions.graph.maxGapVoxels, c.maxGapVoxels);
  const geom::CylinderModel pieces = cylinderModelFromSkeleton(res.model);
  const compare::CylinderModelIndex index(pieces);
  // A point farther outside a tube than its surface's points stray about it (three robust
  // spreads: its circle's points about the circle where it has an accepted fit, else its points'
  // distances to the axis; the scan's noise at least) is not that surface's: a twig the level sets
  // merged into the limb beside it. Between half a voxel and a voxel (the margin before).
  std::vector<double> pieceMargin;
  const std::vector<double> spreads =
      detail::surfaceSpreads(res.model, cloud, res.noise, voxel, options.radii.medianWindow);
  for (std::size_t i = 0; i < res.model.size(); ++i) {
    if (res.model[i].parent < 0) continue;  // the pieces are the non-root nodes, in order
    double spread = spreads[i];
    if (i < res.fitAccepted.size() && res.fitAccepted[i]) spread = detail::fitSpread(res.fits[i], cloud);
    double m = c.marginVoxels * voxel;
    if (res.noiseMeasured && std::isfinite(spread))
      m = std::min(m, std::max(kMarginFloorVoxels * voxel, kMarginSpreads * std::max(res.noise, spread)));
    pieceMargin.push_back(m);
  }
  unexplained = detail::unexplainedPoints(cloud, index, c.marginVoxels * voxel, &res.skeleton.graph,
                                          round == 0 ? nullptr : &unexplained, &pieceMargin);
  if (unexplained.size() < static_cast<std::size_t>(c.minPoints)) {
    res.completionMs += t0.ms();
    return false;
  }
  geom::PointCloud rest;
  rest.up = cloud.up;
  rest.positions.reserve(unexplained.size());
  for (std::uint32_t i : unexplained) rest.positions.push_back(cloud.positions[i]);

  const VoxelGraph graph = buildVoxelGraph(rest, partOptions.graph);
  std::int32_t count = 0;
  const std::vector<std::int32_t> label = util::labelComponents(graph.offsets, graph.targets, &count);
  std::vector<std::vector<std::uint32_t>> members(static_cast<std::size_t>(count));
  for (std::size_t i = 0; i < rest.size(); ++i)
    members[label[graph.pointVoxel[i]]].push_back(static_cast<std::uint32_t>(i));
  std::vector<std::size_t> order(members.size());
  for (std::size_t k = 0; k < order.size(); ++k) order[k] = k;
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return members[a].size() > members[b].size(); });
  bool grafted = false;
  int parts = 0;
  for (std::size_t k : order) {
    if (members[k].size() < static_cast<std::size_t>(c.minPoints) || parts >= c.maxParts) break;
    ++parts;
    geom::PointCloud points;
    points.up = rest.up;
    points.positions.reserve(members[k].size());
    for (std::uint32_t i : members[k]) points.positions.push_back(rest.positions[i]);
    Skeleton part = extractSkeleton(points, partOptions);
    detail::reachStubTip(part.nodes, points, index);
    grafted |= detail::graftPart(res.skeleton.nodes, part.nodes, res.model, pieces, index, c.maxGapVoxels * voxel);
  }
  res.completionMs += t0.ms();
  return grafted;
}

}  // namespace

namespace {

/// The scan's noise (AutoSkeletonResult::noise): the smaller of the tracked stem's points' spread
/// and the circles' (each is the scanner's noise plus the shape's own departure from a circle: a
/// polygonal or rough stem, a leafy crown's circles); half a voxel when neither is measured.
void measureNoise(AutoSkeletonResult& res, const geom::PointCloud& cloud) {
  const double voxel = res.skeleton.graph.voxelSize;
  const double onStem = detail::stemNoise(res.model, cloud, voxel);
  const double onFits = detail::measuredNoise(res.fits, res.fitAccepted, cloud, -1.0);
  res.noise = onStem > 0 && onFits > 0 ? std::min(onStem, onFits) : std::max(onStem, onFits);
  res.noiseMeasured = res.noise > 0;
  if (!res.noiseMeasured) res.noise = 0.5 * voxel;
}

/// A noise's shell is drawn onto its branch's axis in this many rounds of the mean shift (one
/// leaves half of it on a twig under the noise).
constexpr int kContractionRounds = 2;
/// The points are drawn together when the radius reaches this share of a voxel: below it the
/// voxels hold the noise's shell within a branch's own voxels. (At half a voxel the dense
/// benchmark tree, 5 mm of noise on limbs of 5 cm, was drawn together: twice the time for a
/// skeleton its noise did not blur.)
constexpr double kMinContractionVoxels = 0.75;

/// `cloud` with each point moved `kContractionRounds` times to the mean of its neighbours within
/// `radius`, but for the points at most `radius` outside a piece of `model` at least `radius`
/// thick (they keep their place: the first model measured that piece above the noise).
geom::PointCloud drawnTogether(const geom::PointCloud& cloud, const std::vector<SkeletonNode>& model, double radius) {
  std::vector<char> stays(cloud.size(), 0);
  const geom::CylinderModel pieces = cylinderModelFromSkeleton(model);
  if (!pieces.empty()) {
    const compare::CylinderModelIndex index(pieces);
    for (const detail::NearestTube& n : detail::nearestTubes(index, cloud, cloud.size())) {
      const geom::ModelCylinder& c = pieces.cylinders[static_cast<std::size_t>(n.piece)];
      if (std::max(c.startRadius, c.endRadius) >= radius && n.distance <= radius) stays[n.point] = 1;
    }
  }
  geom::PointCloud out = cloud;
  for (int round = 0; round < kContractionRounds; ++round) {
    const accel::PointIndex index(out.positions);
    std::vector<geom::Vec3> next(out.positions.size());
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, next.size(), 1024),
                      [&](const tbb::blocked_range<std::size_t>& range) {
                        std::vector<std::uint32_t> near;
                        for (std::size_t i = range.begin(); i < range.end(); ++i) {
                          next[i] = out.positions[i];
                          if (stays[i]) continue;
                          index.withinRadius(out.positions[i], radius, near);
                          if (near.empty()) continue;
                          geom::Vec3 sum = geom::Vec3::Zero();
                          for (std::uint32_t j : near) sum += out.positions[j];
                          next[i] = sum / static_cast<double>(near.size());
                        }
                      });
    out.positions = std::move(next);
  }
  return out;
}

/// The pipeline on the kept points; the skeleton grown on `skeletonPoints` when given (the same
/// points, drawn together: drawnTogether).
AutoSkeletonResult modelKeptPoints(const geom::PointCloud& cloud, const AutoSkeletonOptions& options,
                                   const ProgressFn& progress, const geom::PointCloud* skeletonPoints = nullptr) {
  AutoSkeletonResult res;
  // 1. The skeleton.
  const Stopwatch t0;
  // `progress` sees the extraction's four steps (d of 4), then the fit pass (d of n); a callback
  // may throw (treesketch::Cancelled) to stop at the next report.
  res.skeleton = extractSkeleton(skeletonPoints ? *skeletonPoints : cloud, options.skeleton, progress);
  res.skeletonMs = t0.ms();
  if (res.skeleton.nodes.empty()) {
    res.sketch = skeletonToSketch(res.skeleton, options.sketch);
    return res;
  }
  // 2.-4. Its sketch, the fit pass (recon builds the slice index and fits every node) and the model.
  const Stopwatch t2;
  recon::Reconstruction rec(cloud, reconstructionOptions(options, res.skeleton.graph.voxelSize));
  res.fitMs += t2.ms();
  fitModel(res, rec, cloud, options, progress);
  // 4b. The parts the model left out, grafted on and fitted (recon fits only the new nodes), round
  // after round while a round grafts any (a part grafted on explains points near it, and the
  // points beyond are the next round's parts). The model's nodes keep their positions and radii: a part carries little
  // length but a fit taken on it, against its host's side, can be thick, and with the carried-length allometry refitted
  // over both, the limbs of a dense crown grew (adtree_tree7: 3.6 → 5.5 % of the points deeper than 2 cm inside). A
  // part is no thicker than the node it grows from.
  measureNoise(res, cloud);  // the completion's margins use it
  std::vector<std::uint32_t> unexplained;
  for (int round = 0; round < options.completion.maxRounds; ++round) {
    const std::size_t modelled = res.model.size();
    if (!complete(cloud, options, res, unexplained, round)) break;
    const std::vector<SkeletonNode> before = res.model;
    const std::vector<char> measuredBefore = res.radiusMeasured;
    fitModel(res, rec, cloud, options, progress);
    for (std::size_t i = 0; i < modelled; ++i) {
      res.model[i].position = before[i].position;
      res.model[i].radius = before[i].radius;
      res.radiusMeasured[i] = measuredBefore[i];
    }
    std::vector<double> grafted(res.model.size() - modelled);
    for (std::size_t i = modelled; i < res.model.size(); ++i) grafted[i - modelled] = res.model[i].radius;
    detail::capByPipeModel(res.model, modelled);
    for (std::size_t i = modelled; i < res.model.size(); ++i)
      if (res.model[i].radius < grafted[i - modelled]) res.radiusMeasured[i] = 0;  // the pipe model's now
  }

  // 4c. No tube thicker than the surface its points show (a scanner sees the bark).
  const Stopwatch t1;
  const double voxel = res.skeleton.graph.voxelSize;
  measureNoise(res, cloud);  // again: the grafted parts' circles count too

  if (options.radii.surfaceBound) {
    std::vector<double> own(res.model.size(), 0.0);
    for (std::size_t i = 0; i < own.size() && i < res.fits.size(); ++i)
      if (res.radiusMeasured[i] && res.fitAccepted[i]) own[i] = res.fits[i].rms;
    // Without circles or a stem to measure the noise, the tubes' own points give it (no more than
    // the half voxel that stands in for it): the allowance of the median and the convex section's
    // quartile is then the scan's, not a guess (docs/notes/radii_and_volume.md).
    double boundNoise = res.noise;
    if (!res.noiseMeasured) {
      const double spread = detail::spreadNoise(res.model, cloud, res.noise, voxel, options.radii.medianWindow);
      if (spread > 0) boundNoise = std::min(boundNoise, spread);
    }
    res.rangeNoise = detail::rangeNoise(res.model, cloud, boundNoise + voxel);
    const detail::SurfaceBoundStats bound =
        detail::boundRadiiBySurface(res.model, cloud, boundNoise, voxel, options.radii.medianWindow, own,
                                    std::max(0.0, res.rangeNoise), options.maxFitFlatFraction);
    res.thinnedBySurface = bound.nodesThinned;
    res.thickenedBySurface = bound.nodesThickened;
  }
  // 5.-6. The model into the sketch, and recon sweeps that sketch (kept circles need no fit).
  handOver(res);
  rec.update(res.sketch);
  res.mesh = rec.mesh();
  res.sweepMs += t1.ms();
  return res;
}

}  // namespace

AutoSkeletonResult autoSkeletonSketch(const geom::PointCloud& cloud, const AutoSkeletonOptions& options,
                                      const ProgressFn& progress) {
  checkOptions(options);
  cloud::StrayPoints strays =
      cloud::findStrayAndGroundPoints(cloud, options.skeleton.up, options.strays, options.ground, options.markedNoise);
  const geom::PointCloud kept = strays.empty() ? geom::PointCloud{} : cloud::keptPoints(cloud, strays);
  const geom::PointCloud& points = strays.empty() ? cloud : kept;
  AutoSkeletonResult res = modelKeptPoints(points, options, progress);
  // A scan whose noise blurs its branches at the voxel's scale: the skeleton again, on the points
  // drawn together (AutoSkeletonOptions::contractionNoises).
  // The radius in whole quarters of a voxel (the graph's own resolution), rounded down: a reading
  // of the noise a percent apart (the same cloud moved 1e9 m) draws the points together the same way.
  const double quarter = 0.25 * res.skeleton.graph.voxelSize;
  const double radius = quarter > 0 && res.rangeNoise > 0
                            ? quarter * std::floor(options.contractionNoises * res.rangeNoise / quarter)
                            : 0.0;
  if (!options.skeleton.leafEntryPositions && options.contractionNoises > 0 && radius > 0 &&
      radius >= kMinContractionVoxels * res.skeleton.graph.voxelSize) {
    const Stopwatch t;
    const double firstMs = res.skeletonMs + res.fitMs + res.sweepMs + res.completionMs;
    const geom::PointCloud drawn = drawnTogether(points, res.model, radius);
    const double drawMs = t.ms();
    res = modelKeptPoints(points, options, progress, &drawn);
    res.contraction = radius;
    res.skeletonMs += firstMs + drawMs;  // the first model and the drawing together are the skeleton's cost
  }
  res.strays = std::move(strays);
  return res;
}

}  // namespace treesketch::skeleton
