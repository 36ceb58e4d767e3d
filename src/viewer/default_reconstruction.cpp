// The viewer's default reconstruction: recon::Reconstruction behind the ViewerReconstruction
// interface, plus a cache of the selected node's slice (computed on demand, only for display).
#include <memory>
#include <optional>

#include "treesketch/fit/node_fit.h"
#include "treesketch/recon/reconstruction.h"
#include "treesketch/viewer/viewer_state.h"

namespace treesketch::viewer {

namespace {

class DefaultReconstruction : public ViewerReconstruction {
 public:
  /// A person's screen nodes choose their depth along the view ray, as `reconstruct --sketch` does.
  explicit DefaultReconstruction(const geom::PointCloud& cloud)
      : recon_(cloud, recon::sketchReconstructionOptions()) {}

  recon::ReconstructionResult result() const override { return recon_.result(sketch_); }

  void update(const sketch::Sketch& sketch) override {
    sketch_ = sketch;
    recon_.update(sketch_);
  }

  NodeFitView nodeFit(sketch::NodeId id) const override {
    NodeFitView v;
    const fit::NodeResult* r = recon_.result(id);
    if (!r) return v;
    v.status = r->status == fit::NodeStatus::Fitted ? NodeStatus::Fitted : NodeStatus::Skipped;
    v.reason = r->status == fit::NodeStatus::Disabled && r->reason.empty() ? "disabled" : r->reason;
    v.circle = Circle3{r->centre, r->normal, r->radius};
    v.finalLineEpsilon = r->lineEpsilon;
    v.slicePoints = r->sliceComputed ? r->sliceIndices.size() : 0;
    v.testPoints = r->testIndices.size();
    v.inliers = r->inlierIndices.size();
    v.kept = r->kept;
    v.depth = r->depth;
    v.depthJump = r->depthJump;
    v.warning = r->warning;
    return v;
  }

  std::vector<std::uint32_t> slicePoints(sketch::NodeId id) const override {
    const fit::NodeResult* r = recon_.result(id);
    if (!r || !sketch_.contains(id)) return {};
    if (r->sliceComputed) return r->sliceIndices;
    sketch::NodeGeometry g = sketch_.geometry(id);
    const sketch::SamplingParams& p = sketch_.node(id).params;
    if (cache_ && cache_->id == id && cache_->geometry == g && cache_->params == p) return cache_->indices;
    cache_ = Cached{id, g, p, fit::nodeSlice(recon_.index(), g, p)};
    return cache_->indices;
  }

  std::vector<std::uint32_t> inlierPoints(sketch::NodeId id) const override {
    const fit::NodeResult* r = recon_.result(id);
    return r ? r->inlierIndices : std::vector<std::uint32_t>{};
  }

  const geom::TriMesh& mesh() const override { return recon_.mesh(); }

  void setLeafPoints(std::vector<std::uint8_t> leaf) override {
    recon_.setLeafPoints(std::move(leaf));
    cache_.reset();  // the selected node's slice leaves the leaf points out too
  }

 private:
  struct Cached {
    sketch::NodeId id;
    sketch::NodeGeometry geometry;
    sketch::SamplingParams params;
    std::vector<std::uint32_t> indices;
  };
  recon::Reconstruction recon_;
  sketch::Sketch sketch_;
  mutable std::optional<Cached> cache_;
};

}  // namespace

std::unique_ptr<ViewerReconstruction> makeDefaultReconstruction(const geom::PointCloud& cloud) {
  return std::make_unique<DefaultReconstruction>(cloud);
}

}  // namespace treesketch::viewer
