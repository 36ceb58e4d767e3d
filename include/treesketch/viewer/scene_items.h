// What the desktop tool shows of a sketch's reconstruction: each node's fit, the node markers
// over the view, the 3D lines (circles, the sampling region), and the reconstruction interface
// ViewerState runs after every edit (implemented over recon::Reconstruction; tests may plug in
// their own). Plain data, no GL.
#pragma once

#include <cmath>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "treesketch/geom/point_cloud.h"
#include "treesketch/geom/tri_mesh.h"
#include "treesketch/recon/reconstruction.h"
#include "treesketch/sketch/sketch.h"
#include "treesketch/viewer/point_colors.h"

namespace treesketch::viewer {

/// A node's reconstruction outcome, as the viewer shows it.
enum class NodeStatus { Pending, Fitted, Skipped };
const char* toString(NodeStatus status);

/// Everything the viewer knows about one node's fit (from the reconstruction).
struct NodeFitView {
  NodeStatus status = NodeStatus::Pending;
  std::string reason;             ///< why it was skipped ("" when fitted)
  Circle3 circle;                 ///< valid when fitted
  double finalLineEpsilon = 0.0;  ///< the cylinder radius the fit ended with, world units
  std::size_t slicePoints = 0, testPoints = 0, inliers = 0;
  /// Fitted from the node's kept circle (an automatic sketch's model), not from the cloud.
  bool kept = false;
  /// Screen nodes: the circle's depth along the node's view ray (world units from its near
  /// point; NaN when unknown), and what the depth choice says (fit::NodeResult::warning) — a jump
  /// away from where the circle was expected sets depthJump.
  double depth = std::nan("");
  bool depthJump = false;
  std::string warning;
};

/// A node as drawn over the view: screen position (window pixels) under the current camera.
struct NodeMarker {
  sketch::NodeId id = sketch::kNoNode;
  sketch::NodeId parent = sketch::kNoNode;
  geom::Vec2 screen = geom::Vec2::Zero();
  bool visible = true;        ///< false when behind the camera or outside the depth range
  bool inCurrentView = true;  ///< drawn under the current camera (false: projected from 3D)
  bool selected = false;
  bool active = false;
  NodeStatus status = NodeStatus::Pending;
  /// Window depth of the node's circle (or anchor) under the current camera, 0 (near) to 1 (far);
  /// NaN when unknown. A pick among overlapping markers takes the smallest.
  double depth = std::nan("");
  /// A Delete subtree waiting for its confirmation would remove this node (drawn as such).
  bool doomed = false;
};

/// A coloured 3D line segment (world frame).
struct Line3 {
  geom::Vec3 a = geom::Vec3::Zero(), b = geom::Vec3::Zero();
  Rgb color = {255, 255, 255};
};

/// The selected node's sampling region (thesis §4.4): the slab |dist to plane| < ε and the
/// cylinder of radius lineEpsilon around the line L, for drawing.
struct SamplingRegion {
  bool valid = false;
  sketch::NodeGeometry geometry;
  double sliceHalfThickness = 0.0;
  double lineEpsilon = 0.0;  ///< the final (possibly grown) radius when the node was fitted
};

/// The reconstruction the viewer runs after every edit. Implemented over recon::Reconstruction in
/// the library; tests may plug in their own.
class ViewerReconstruction {
 public:
  virtual ~ViewerReconstruction() = default;
  /// Re-fits what changed in `sketch` (nodes added, moved, re-parameterised, removed) and
  /// rebuilds the mesh.
  virtual void update(const sketch::Sketch& sketch) = 0;
  /// The fit of node `id` (Pending when unknown).
  virtual NodeFitView nodeFit(sketch::NodeId id) const = 0;
  /// Indices into the cloud of the node's slice (nearPts) and of its circle's inliers.
  virtual std::vector<std::uint32_t> slicePoints(sketch::NodeId id) const = 0;
  virtual std::vector<std::uint32_t> inlierPoints(sketch::NodeId id) const = 0;
  virtual const geom::TriMesh& mesh() const = 0;
  /// The points a wood/leaf classification calls leaf (1 per point; empty: none): left out of the
  /// fits from the next update, except where a wood lasso holds them
  /// (recon::Reconstruction::setLeafPoints). Default: ignored.
  virtual void setLeafPoints(std::vector<std::uint8_t> leaf) { (void)leaf; }
  /// Every node's fit, the sketch's order and parents, and the mesh (what the model's outputs are
  /// made from: model::fromReconstruction). Default: no fits, the mesh only.
  virtual recon::ReconstructionResult result() const {
    recon::ReconstructionResult r;
    r.mesh = mesh();
    return r;
  }
};

/// The default reconstruction (recon::Reconstruction over `cloud`, which must outlive it).
std::unique_ptr<ViewerReconstruction> makeDefaultReconstruction(const geom::PointCloud& cloud);

}  // namespace treesketch::viewer
