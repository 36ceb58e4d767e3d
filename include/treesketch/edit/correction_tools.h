// The correction tools — what a person does to fix an automatic model, as library
// calls on a sketch and its cloud, shared by the viewer (each one an undoable edit, a key and a
// `--script` verb) and the evaluation's simulated correcting user (eval/correcting_user.h), so
// that the evaluation measures the operations the GUI offers:
//  - delete a subtree, re-attach a node to another parent (sketch/sketch_edits.h, re-exported
//    here for one place to look);
//  - draw a limb as one stroke (drawLimb): a screen polyline; the depth of each stroke sample is
//    chosen among the cloud's candidates along its view ray, by continuity from the node the
//    stroke starts on; point nodes are placed along the 3D path at a spacing from the local
//    branch radius, each fitted from the cloud;
//  - a not-wood lasso (lassoNotWood): a screen polygon whose points the fits and the automatic
//    skeleton leave out, saved with the sketch;
//  - automatic from here (automaticBelow, automaticInRegion): the automatic skeleton run on the
//    points below a node or inside a screen polygon, merged into the sketch.
// Module `edit`: may use skeleton, recon, fit, sweep, sketch, accel, geom, util (see
// docs/ARCHITECTURE.md); eval and viewer use it.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "treesketch/geom/camera.h"
#include "treesketch/geom/point_cloud.h"
#include "treesketch/recon/reconstruction.h"
#include "treesketch/skeleton/skeleton_sketch.h"
#include "treesketch/sketch/sketch.h"
#include "treesketch/sketch/sketch_edits.h"

namespace treesketch::edit {

using sketch::kNoNode;
using sketch::NodeId;

/// Where a node is in 3D and how thick its branch is there.
struct NodeAnchor {
  geom::Vec3 centre = geom::Vec3::Zero();  ///< world
  double radius = 0.0;                     ///< world units; 0 = unknown (no circle)
};

/// Every node's anchor: its circle (fitted or kept) when `recon` has one, else a point node's
/// point; screen nodes without a circle have no depth and are left out. `recon` may be null.
std::map<NodeId, NodeAnchor> nodeAnchors(const sketch::Sketch& sketch, const recon::Reconstruction* recon);

/// Cloud points that project near a screen position under one camera (a grid over the view,
/// built once): the view ray's candidates in depth.
class ViewPicker {
 public:
  /// `skip` (optional): points for which it is true, given their index in `cloud` and position,
  /// are left out (not-wood points, the points a classification calls leaf).
  ViewPicker(const geom::PointCloud& cloud, const geom::Camera& camera, double cellPx = 4.0,
             const std::function<bool(std::size_t, const geom::Vec3&)>& skip = {});
  struct Candidate {
    std::uint32_t index;  ///< into the cloud
    double depth;         ///< distance along the view ray from the near plane, world units
  };
  /// The points within `radiusPx` of `screen` (projected), in increasing depth.
  std::vector<Candidate> near(const geom::Vec2& screen, double radiusPx) const;
  /// The view ray through `screen`: near-plane point and unit direction.
  void ray(const geom::Vec2& screen, geom::Vec3* origin, geom::Vec3* dir) const;
  /// Depth of a world point along the ray through its own projection.
  double depthOf(const geom::Vec3& p) const;
  const geom::Camera& camera() const { return camera_; }

 private:
  geom::Camera camera_;
  double cell_;
  int cols_ = 0, rows_ = 0;
  std::vector<std::uint32_t> start_, ids_;
  std::vector<geom::Vec2> screen_;  ///< per cloud point (NaN: not on screen or skipped)
  std::vector<double> depth_;
};

struct StrokeOptions {
  /// The stroke is resampled every this many pixels before its depth is picked (design choice:
  /// 2 px, finer than a hand's jitter).
  double sampleStepPx = 2.0;
  /// Points within this distance (pixels) of a stroke sample are its depth candidates (design
  /// choice: 4 px, a thin branch's width on screen).
  double pickRadiusPx = 4.0;
  /// Depth candidates further apart than this along the ray are different surfaces, as a
  /// fraction of the sketch's default lineEpsilon (design choice: 0.5 — half the default search
  /// radius, about 1 % of the cloud's diagonal, wider than any twig).
  double depthGapFraction = 0.5;
  /// A surface needs at least this many candidates (design choice: 3; fewer is noise).
  int minSurfacePoints = 3;
  /// Node spacing along the limb: this many local radii (the radius of the node the stroke
  /// starts on), bounded below by 2.5 slice half-thicknesses (slices must not overlap) and
  /// above by the default lineEpsilon. Design choice: 4.
  double spacingRadii = 4.0;
  /// The stroke must start within this distance (pixels) of a node to attach to it; further
  /// away it is attached to the nearest node anyway, with a warning (design choice: 40 px).
  double attachWarnPx = 40.0;
};

struct StrokeResult {
  std::vector<NodeId> added;  ///< the new nodes, base to tip
  NodeId attachedTo = kNoNode;
  std::vector<geom::Vec3> path;  ///< the picked 3D path, base to tip
  /// Samples whose chosen surface was not the front-most one (the stroke followed a branch
  /// behind another, by continuity) and samples where the chosen depth jumped by more than the
  /// surface gap from the previous sample.
  int behindFront = 0;
  int depthJumps = 0;
  int samplesWithoutPoints = 0;
  std::string warning;  ///< "" or what the person should know (depth jumps, far attach)
};

/// Adds a limb drawn as one stroke under `camera` (window pixels, base first). Throws
/// OptionsError for fewer than 2 stroke points, a non-finite point, or a stroke along which no
/// sample has a cloud point (nothing to follow). Nodes are point nodes (sketch defaults, with
/// lineEpsilon = min(default, 4 local radii) and at most 3 growth steps, as the automatic
/// skeleton's) whose normal is the path's tangent; they are fitted by the next reconstruction.
StrokeResult drawLimb(sketch::Sketch& sketch, const ViewPicker& picker, const geom::PointCloud& cloud,
                      const std::vector<geom::Vec2>& stroke, const std::map<NodeId, NodeAnchor>& anchors,
                      const StrokeOptions& options = {});

/// Adds a not-wood lasso under `camera`; returns the number of cloud points it marks.
std::size_t lassoNotWood(sketch::Sketch& sketch, const geom::PointCloud& cloud, const geom::Camera& camera,
                         const std::vector<geom::Vec2>& polygon);

/// Adds a wood lasso under `camera` (its points are wood whatever the classification says; see
/// sketch::NotWoodLasso); returns the number of cloud points it marks.
std::size_t lassoWood(sketch::Sketch& sketch, const geom::PointCloud& cloud, const geom::Camera& camera,
                      const std::vector<geom::Vec2>& polygon);

/// The cloud without its not-wood points (what the automatic skeleton is given).
geom::PointCloud woodOnly(const geom::PointCloud& cloud, const sketch::Sketch& sketch);
/// The same with a wood/leaf classification: `leaf` (one flag per point, 1 = the classification
/// calls it leaf; empty = none) leaves out the leaf points too, except where a lasso says
/// otherwise (the last lasso drawn over a point decides). Throws OptionsError when `leaf` is not
/// empty and not one flag per point.
geom::PointCloud woodOnly(const geom::PointCloud& cloud, const sketch::Sketch& sketch,
                          const std::vector<std::uint8_t>& leaf);
/// Point `i` (at `p`) is wood by the lassos, else by `leaf` (empty: wood).
bool isWoodPoint(const sketch::Sketch& sketch, const std::vector<std::uint8_t>& leaf, std::size_t i,
                 const geom::Vec3& p);

/// Adds `from`'s not-wood lassos (with their cameras) to `to`: a sketch that replaces another
/// (an automatic one) keeps the person's lassos.
void copyNotWood(const sketch::Sketch& from, sketch::Sketch& to);

/// Drops the kept circle of every node whose circle centre is not-wood (a model circle inside a
/// lasso was fitted to what the person says is not wood): those nodes are fitted from the
/// remaining points by the next reconstruction. Returns how many were dropped.
std::size_t refitNotWoodCircles(sketch::Sketch& sketch);

struct AutoHereOptions {
  skeleton::AutoSkeletonOptions skeleton;
  /// automaticBelow: the region is the half-space beyond the node's plane (in its growth
  /// direction) within this distance of its centre; 0 = a quarter of the cloud's diagonal.
  double regionRadius = 0.0;
  /// A new node within this many radii (its own or the existing node's, the larger; at least one
  /// default slice half-thickness) of an existing node's centre repeats that node and is dropped.
  double duplicateRadii = 2.0;
};

struct AutoHereResult {
  std::vector<NodeId> added;
  std::size_t regionPoints = 0;
  std::size_t duplicates = 0;  ///< nodes of the region's skeleton dropped as repeats
  NodeId attachedTo = kNoNode;
};

/// Automatic skeleton on the points below `node` (see AutoHereOptions::regionRadius; not-wood
/// points left out), merged under `node`. Throws OptionsError for an unknown node, a node with
/// no anchor, or a region with too few points for a skeleton.
AutoHereResult automaticBelow(sketch::Sketch& sketch, const geom::PointCloud& cloud, NodeId node,
                              const std::map<NodeId, NodeAnchor>& anchors, const AutoHereOptions& options);
/// Automatic skeleton on the points inside a screen polygon under `camera`, merged under the
/// existing node nearest (3D) to the region skeleton's root (or as the whole sketch when it is
/// empty).
AutoHereResult automaticInRegion(sketch::Sketch& sketch, const geom::PointCloud& cloud, const geom::Camera& camera,
                                 const std::vector<geom::Vec2>& polygon, const std::map<NodeId, NodeAnchor>& anchors,
                                 const AutoHereOptions& options);

}  // namespace treesketch::edit
