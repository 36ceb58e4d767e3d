#include <memory>

#include "treesketch/viewer/viewer_state.h"

namespace treesketch::viewer {

namespace {
class PendingReconstruction : public ViewerReconstruction {
 public:
  void update(const sketch::Sketch&) override {}
  NodeFitView nodeFit(sketch::NodeId) const override { return {}; }
  std::vector<std::uint32_t> slicePoints(sketch::NodeId) const override { return {}; }
  std::vector<std::uint32_t> inlierPoints(sketch::NodeId) const override { return {}; }
  const geom::TriMesh& mesh() const override { return mesh_; }

 private:
  geom::TriMesh mesh_;
};
}  // namespace

std::unique_ptr<ViewerReconstruction> makeDefaultReconstruction(const geom::PointCloud& cloud) {
  (void)cloud;
  return std::make_unique<PendingReconstruction>();
}

}  // namespace treesketch::viewer
