// One-call pictures of a scene: a point cloud, meshes, polylines and dots drawn with the software
// rasterizer, plus a camera that frames a bounding box from a named view (front, side, top, iso).
// For README and docs pictures without a display.
#pragma once

#include <string>
#include <vector>

#include "treesketch/geom/camera.h"
#include "treesketch/geom/point_cloud.h"
#include "treesketch/geom/tri_mesh.h"
#include "treesketch/render/image.h"
#include "treesketch/render/rasterizer.h"
#include "treesketch/sketch/sketch.h"

namespace treesketch::render {

/// A connected line strip in world coordinates.
struct Polyline {
  std::vector<geom::Vec3> points;
  Rgb color = {220, 30, 30};
};

/// A dot (square splat) in world coordinates.
struct Dot {
  geom::Vec3 position = geom::Vec3::Zero();
  Rgb color = {220, 30, 30};
};

/// What renderScene draws, in this order: cloud points, meshes (or meshes, then the cloud as a
/// backdrop when cloudBehindMeshes), then polylines and dots (over everything when linesOnTop).
struct RenderScene {
  std::vector<geom::Vec3> cloud;  ///< world points
  std::vector<Rgb> cloudColors;   ///< one per point, or empty for cloudColor
  Rgb cloudColor = {120, 120, 120};
  int pointSize = 2;               ///< pixels
  bool cloudBehindMeshes = false;  ///< true: meshes first, points only on pixels no mesh covers
  std::vector<geom::TriMesh> meshes;
  std::vector<Rgb> meshColors;  ///< one per mesh, or fewer: the rest get distinctColor(i)
  TriangleStyle meshStyle;
  std::vector<Polyline> polylines;
  std::vector<Dot> dots;
  int lineWidth = 2;       ///< pixels
  int dotSize = 7;         ///< pixels
  bool linesOnTop = true;  ///< polylines and dots ignore the depth of points and meshes
  Rgb background = {255, 255, 255};

  /// Bounding box of everything in the scene (empty when the scene is).
  geom::BBox bounds() const;
};

/// Draws `scene` through `camera` into a width x height image (the camera's viewport is set to
/// 0, 0, width, height). Throws OptionsError for sizes outside [1, 16384], a degenerate camera, a
/// colour array whose size does not match the cloud, or a mesh with bad indices. An empty scene
/// gives a background-only image.
Image renderScene(const RenderScene& scene, const geom::Camera& camera, int width, int height);

enum class RenderView { Front, Side, Top, Iso };
/// Parses "front", "side", "top" or "iso" (case-insensitive); throws OptionsError otherwise.
RenderView parseRenderView(const std::string& name);

/// A camera framing `box` in a width x height picture. Front, side and top are orthographic
/// geom::presetCamera views (see there for the directions). Iso is a perspective camera
/// (30° vertical field of view) looking at the box centre from 45° azimuth, between the front
/// and side cameras' positions, and 30° elevation above the horizon; it is moved back until all
/// eight box corners fall inside the picture with a 5 % margin. Throws OptionsError for an empty
/// box or a non-positive size; a zero-size box (one point) is padded to a small cube.
geom::Camera fitCamera(const geom::BBox& box, RenderView view, geom::UpAxis up, int width, int height);

/// `camera` zoomed and shifted in the picture plane (a uniform scale and shift of normalized
/// device coordinates, so view direction, eye and aspect ratio are unchanged) so that the screen
/// bounding box of `points` (world) fills the picture less a `margin` fraction (clamped to
/// [0, 0.45]) on each side, centred. Points behind the near plane are ignored; with fewer than two
/// usable points or a zero-size screen box the camera is returned unchanged.
geom::Camera tightenCamera(const geom::Camera& camera, const std::vector<geom::Vec3>& points, double margin = 0.04);

/// Adds a sketch to `scene`: one dot per node and one line per parent link. A point node sits at
/// its point; a screen node at the point of its view ray closest to `focus` (e.g. the cloud's
/// bounding-box centre, world). Nodes with no usable geometry (a degenerate ray) are skipped;
/// returns how many nodes were placed.
std::size_t addSketch(RenderScene& scene, const sketch::Sketch& sketch, const geom::Vec3& focus,
                      Rgb color = {220, 30, 30});

}  // namespace treesketch::render
