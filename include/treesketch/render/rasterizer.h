// A small z-buffered software rasterizer for pictures without a display or OpenGL: square point
// splats, 3D line segments and flat/Lambert-shaded triangles seen through a geom::Camera, into an
// RGB image (top-left origin, like Camera::project) with a depth buffer of window depths in [0, 1].
#pragma once

#include <array>

#include "treesketch/geom/camera.h"
#include "treesketch/geom/tri_mesh.h"
#include "treesketch/geom/types.h"
#include "treesketch/render/image.h"

namespace treesketch::render {

/// How a point splat meets what is already drawn.
enum class PointDepth {
  Test,       ///< z-tested like everything else
  Ignore,     ///< drawn over everything
  EmptyOnly,  ///< only on pixels nothing was drawn on yet (a backdrop behind earlier meshes)
};

struct LineStyle {
  int widthPx = 1;          ///< line width in pixels, clamped to [1, 8]
  bool depthTest = true;    ///< false: drawn over everything already in the image
  double depthBias = 2e-4;  ///< window-depth units pulled towards the viewer so lines on a surface show
};

struct TriangleStyle {
  bool lambert = true;          ///< true: Lambert shading from a headlight at the eye; false: flat colour
  double ambient = 0.35;        ///< fraction of the colour kept where the surface faces away from the light
  double diffuse = 0.65;        ///< fraction added by the cosine term (ambient + diffuse = 1: full colour head-on)
  bool useVertexColors = true;  ///< drawMesh: take TriMesh::colors when the mesh has them
  bool wireframe = false;       ///< overlay the triangle edges
  Rgb wireColor = {40, 40, 40};
};

/// Draws into an image the size of the camera's viewport (rounded to whole pixels). Pixel (x, y)
/// covers screen [x, x+1) x [y, y+1) (screen as Camera::project, less the viewport's offset) and is
/// sampled at its centre. Every primitive is depth-tested against the nearest drawn so far.
/// Near plane: a point or triangle with any vertex in front of the near plane (behind or too close
/// to the eye) is skipped; a line is clipped at the near plane. Beyond the far plane nothing draws.
class Rasterizer {
 public:
  /// Throws OptionsError if the camera is degenerate (Camera::validate) or its viewport is larger
  /// than 16384 pixels a side.
  explicit Rasterizer(const geom::Camera& camera, Rgb background = {255, 255, 255});

  const Image& image() const { return image_; }
  Image takeImage() { return std::move(image_); }
  /// Window depth stored at pixel (x, y): 1 where nothing was drawn. The caller keeps x, y inside.
  float depthAt(int x, int y) const { return depth_[static_cast<std::size_t>(y) * image_.width + x]; }

  /// A square splat of `sizePx` pixels (clamped to [1, 32]) centred on the world point `p`.
  /// Returns false when the point is culled (behind the near plane, beyond the far plane, off screen).
  bool drawPoint(const geom::Vec3& p, Rgb color, int sizePx = 1, PointDepth depth = PointDepth::Test);
  /// The world segment a-b. Returns false when nothing of it lies in front of the near plane.
  bool drawLine(const geom::Vec3& a, const geom::Vec3& b, Rgb color, const LineStyle& style = {});
  /// The world triangle v with a colour per vertex (interpolated), shaded as `style` says.
  /// Returns false when skipped (a vertex behind the near plane, zero screen area, NaN).
  bool drawTriangle(const std::array<geom::Vec3, 3>& v, const std::array<Rgb, 3>& colors,
                    const TriangleStyle& style = {});
  /// Every triangle of `mesh` in `color` (or its vertex colours, see TriangleStyle). Throws
  /// OptionsError (TriMesh::checkConsistent) for out-of-range indices. Returns the number drawn.
  std::size_t drawMesh(const geom::TriMesh& mesh, Rgb color, const TriangleStyle& style = {});

 private:
  struct Projected {
    double x = 0, y = 0, depth = 0;  ///< pixels (image frame) and window depth
  };
  Eigen::Vector4d toClip(const geom::Vec3& p) const;
  Projected toScreen(const Eigen::Vector4d& clip) const;
  void stamp(double x, double y, double depth, int size, Rgb color, PointDepth mode);

  geom::Camera camera_;
  Eigen::Matrix4d viewProj_;
  geom::Vec3 eye_;
  geom::Vec3 forward_;
  bool ortho_ = false;
  Image image_;
  std::vector<float> depth_;
};

}  // namespace treesketch::render
