// Reconstruction: a sketch + a cloud → per-node circle fits → a swept tube mesh (thesis §3.1.3–
// 3.1.4, §4.4). The Reconstruction class keeps the cloud's slice index and the last fit of every
// node, so an edit re-fits only the nodes whose inputs changed and re-sweeps only the bands
// touching them: what the viewer calls on every edit. reconstruct() is the one-shot form.
#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <optional>

#include "treesketch/fit/cloud_index.h"
#include "treesketch/fit/node_fit.h"
#include "treesketch/geom/point_cloud.h"
#include "treesketch/geom/tri_mesh.h"
#include "treesketch/recon/radius_inference.h"
#include "treesketch/sketch/sketch.h"
#include "treesketch/sweep/tube_mesh.h"
#include "treesketch/util/progress.h"

namespace treesketch::recon {

using sketch::NodeId;

struct ReconstructionOptions {
  fit::NodeFitOptions fit;
  sweep::SweepOptions sweep;
  fit::CloudIndexOptions index;
  /// Base seed: node `id` is fitted with seed `seed + id` (results do not depend on fit order).
  std::uint64_t seed = 1;
  /// Fit changed nodes in parallel (TBB) when more than one changed.
  bool parallel = true;
  /// Which fits the model uses and the radii inferred for the rest (recon/radius_inference.h):
  /// what the sweep and every model made from the result take.
  RadiusInferenceOptions radii;
};

struct Timings {
  double indexMs = 0.0;  ///< building the slice index (constructor)
  double fitMs = 0.0;    ///< fitting the changed nodes (last update)
  double sweepMs = 0.0;  ///< re-sweeping (last update)
  double totalMs = 0.0;  ///< the last update, fit + sweep + diff
};

struct ReconstructionResult;

class Reconstruction {
 public:
  /// Builds the slice index of `cloud` (the cloud is not referenced afterwards). Throws
  /// OptionsError for invalid options.
  explicit Reconstruction(const geom::PointCloud& cloud, const ReconstructionOptions& options = {});

  /// Brings the fits and the mesh up to date with `sketch`: a node is re-fitted when its geometry
  /// (line, plane — which moves when its parent moves), its sampling params or its kept circle
  /// changed or it is new (with options.fit.chooseDepth also a screen node whose parent is
  /// re-fitted: its fit starts from the parent's circle); removed nodes are dropped; re-parenting alone only re-sweeps. A node
  /// with a kept circle is not fitted: it takes that circle (fit::resolveNode). Returns the ids
  /// re-fitted (or re-resolved).
  /// The sketch's not-wood lassos (Sketch::notWood) leave their points out of every fit, and its
  /// wood lassos bring back points setLeafPoints left out: when they change, the index's
  /// exclusions are recomputed and every node that is not a kept circle is re-fitted.
  /// `progress` (optional) is told (nodes fitted, nodes to fit) as the fits finish.
  /// Throws OptionsError for an invalid sketch (see Sketch::validate).
  std::vector<NodeId> update(const sketch::Sketch& sketch, const ProgressFn& progress = {});

  /// The fitting half of update: the fits are brought up to date with `sketch`, the mesh is left
  /// as the last update swept it (the next update sweeps whatever changed since). For passes that
  /// read the fits and discard the tubes (the automatic model's fit pass).
  std::vector<NodeId> fit(const sketch::Sketch& sketch, const ProgressFn& progress = {});

  /// Forgets every fit and the mesh (keeps the index): the next update fits every node.
  void reset();

  /// The points a wood/leaf classification calls leaf (one flag per point of the cloud the
  /// index was built from, 1 = leaf; empty: no classification). From the next update they are
  /// left out of every fit, except where a wood lasso holds them (a not-wood lasso leaves its
  /// points out either way; the last lasso drawn over a point decides), and every node that is not
  /// a kept circle is re-fitted. Throws OptionsError when the size is not the cloud's.
  void setLeafPoints(std::vector<std::uint8_t> leaf);
  const std::vector<std::uint8_t>& leafPoints() const { return leaf_; }

  const geom::TriMesh& mesh() const { return sweeper_.mesh(); }
  /// The last fit of node `id`; nullptr if the node is unknown.
  const fit::NodeResult* result(NodeId id) const;
  /// Node `id`'s circle in the model (its fit, kept circle or inferred radius; inferRadii over the
  /// last fits); nullptr if the node is unknown.
  const NodeRadius* radius(NodeId id) const;
  /// All current results by id.
  std::map<NodeId, const fit::NodeResult*> results() const;
  /// Total node fits performed since construction.
  std::size_t fitCount() const { return fitCount_; }
  double lastUpdateMs() const { return timings_.totalMs; }
  const Timings& timings() const { return timings_; }
  const fit::CloudIndex& index() const { return *index_; }
  const sweep::TubeSweeper& sweeper() const { return sweeper_; }
  const ReconstructionOptions& options() const { return options_; }
  /// The current fits, the sketch's order and parents, and the mesh, as one result (what
  /// reconstruct returns); `sketch` is the one last given to update.
  ReconstructionResult result(const sketch::Sketch& sketch) const;

 private:
  struct Entry {
    sketch::NodeGeometry geometry;
    sketch::SamplingParams params;
    std::optional<sketch::KeptCircle> kept;
    NodeId parent = sketch::kNoNode;
    fit::NodeResult result;
  };
  /// One update's work: the nodes to fit, their new entries, and the waves they are fitted in.
  struct Pending {
    std::vector<NodeId> changed;
    std::vector<Entry> fresh;
    std::map<NodeId, std::size_t> slot;  ///< changed id -> index in `changed`
    std::vector<int> wave;               ///< per changed node: its wave (parents first)
    int waves = 1;
  };
  bool refreshExclusions(const sketch::Sketch& sketch);
  Pending diff(const sketch::Sketch& sketch, bool lassosChanged);
  void addPriorDependents(const sketch::Sketch& sketch, Pending& p) const;
  void fitPending(const sketch::Sketch& sketch, Pending& p, const ProgressFn& progress);
  void sweepEntries();
  void refreshRadii();

  ReconstructionOptions options_;
  std::unique_ptr<fit::CloudIndex> index_;
  std::map<NodeId, Entry> entries_;
  sweep::TubeSweeper sweeper_;
  std::size_t fitCount_ = 0;
  Timings timings_;
  std::vector<NodeId> order_;  ///< the last sketch's parent-before-child order
  std::map<NodeId, NodeRadius> radii_;
  /// The lassos (each with its camera) the index's exclusions were computed from.
  std::vector<std::pair<sketch::NotWoodLasso, geom::Camera>> notWood_;
  std::vector<std::uint8_t> leaf_;  ///< setLeafPoints
  std::size_t cloudSize_ = 0;
  bool leafChanged_ = false;  ///< setLeafPoints was called since the exclusions were computed
};

struct ReconstructionResult {
  std::map<NodeId, fit::NodeResult> results;
  /// Every node's circle in the model: its fit, its kept circle or a radius inferred from its
  /// limb (Reconstruction::radius); what the mesh was swept through.
  std::map<NodeId, NodeRadius> radii;
  std::vector<NodeId> order;  ///< the sketch's parent-before-child order
  std::map<NodeId, NodeId> parents;
  geom::TriMesh mesh;
  Timings timings;
};

/// The options a person's sketch is fitted with, in the desktop tool and by `reconstruct --sketch`
/// alike (so one sketch gives one model): the defaults, with screen nodes choosing their depth along
/// the view ray (fit::NodeFitOptions::chooseDepth) and radii inferred along each limb where the fits
/// fail or are implausible (RadiusInferenceOptions::enabled).
ReconstructionOptions sketchReconstructionOptions();

/// One-shot reconstruction (index, fit every node, sweep). Empty sketch → empty mesh.
ReconstructionResult reconstruct(const geom::PointCloud& cloud, const sketch::Sketch& sketch,
                                 const ReconstructionOptions& options = {});

}  // namespace treesketch::recon
