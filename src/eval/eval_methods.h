// The evaluation's sketch methods shared between evaluation.cpp and careful_user.cpp (internal).
#pragma once

#include <map>
#include <vector>

#include "treesketch/eval/evaluation.h"
#include "treesketch/recon/reconstruction.h"
#include "treesketch/sketch/polyline_sketch.h"
#include "treesketch/util/stopwatch.h"

namespace treesketch::eval::detail {

using NodeResults = std::map<sketch::NodeId, fit::NodeResult>;

/// Fewer points called wood than this: the classification found no tree's wood (every point is used).
constexpr std::size_t kMinWoodPoints = 100;

/// Reconstructs `sk` on `cloud` with `options`; the fits go to *results when given.
MethodOutput reconstructSketch(const sketch::Sketch& sk, const geom::PointCloud& cloud,
                               const recon::ReconstructionOptions& options, const Stopwatch& timer,
                               NodeResults* results = nullptr);
/// The points of `cloud` whose flag is non-zero (one flag per point).
geom::PointCloud pointsWhere(const geom::PointCloud& cloud, const std::vector<std::uint8_t>& flags);
/// The camera of the view the sketches are drawn in.
geom::Camera viewCamera(const MethodInput& in);
/// The simulated user's branches (into `axes`) and polyline options for in.nodeCount nodes.
sketch::PolylineSketchOptions userOptions(const MethodInput& in, std::vector<sketch::BranchPolyline>& axes);
/// The same from `source` instead of the tree's true branches (a part of them).
sketch::PolylineSketchOptions userOptions(const MethodInput& in, const std::vector<sketch::BranchPolyline>& source,
                                          std::vector<sketch::BranchPolyline>& axes);
/// The points the simulated careful user fits on and sees (a flag per point of in.cloud): on a
/// leaf-on scan with EvalOptions::userFitsOnWood the classified wood, else every point.
std::vector<std::uint8_t> carefulUserPoints(const MethodInput& in);
/// `cloud` when every flag of `kept` is set, else its kept points copied into `storage`.
const geom::PointCloud& pointsKept(const geom::PointCloud& cloud, const std::vector<std::uint8_t>& kept,
                                  geom::PointCloud& storage);
/// The careful user's branches (into `axes`) and polyline options: those `seen` shows
/// (seenBranches, with `minPoints`) unless EvalOptions::userDrawsWhatItSees is off.
sketch::PolylineSketchOptions carefulUserPlan(const MethodInput& in, const geom::PointCloud& seen, int minPoints,
                                              std::vector<sketch::BranchPolyline>& axes);
/// The part of each true branch (`axes`, radii per vertex in `radii`) that the points `seen`
/// show: a branch from its base as far as every sample along it (a radius apart, at least a slab's
/// thickness) has `minPoints` points within two radii plus `halfThickness` of it in the slab
/// across the branch there; a branch whose base is not seen, or whose parent's drawn part does
/// not reach its base, is left out with its branches. Parents are renumbered.
std::vector<sketch::BranchPolyline> seenBranches(const std::vector<sketch::BranchPolyline>& axes,
                                                 const std::vector<std::vector<double>>& radii,
                                                 const geom::PointCloud& seen, double halfThickness, int minPoints);

/// The row's skipped-node counts from the user's causes.
void setCauses(EvalRow& row, const NodeCauseCounts& causes);

/// The "user" method (careful_user.cpp).
MethodOutput methodUser(const MethodInput& in);

}  // namespace treesketch::eval::detail
