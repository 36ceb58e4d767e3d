// OpenGL 3.3 core drawing of a ViewerState: the cloud as points (one VBO, re-uploaded only when
// the cloud or its colours change), the selected node's slice points, 3D lines (circles, sampling
// region) and the tube mesh (solid or wireframe). Node markers are drawn by the panels (ImGui).
#pragma once

#include <GL/glew.h>

#include <cstdint>
#include <vector>

#include "treesketch/viewer/point_lod.h"
#include "treesketch/viewer/viewer_state.h"

namespace treesketch::gui {

class Renderer {
 public:
  /// Compiles the shaders (needs a current GL context). Throws std::runtime_error on failure.
  Renderer();
  ~Renderer();
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  /// Draws the scene into the state's viewport (window pixels); `framebufferHeight` flips the
  /// viewport's top-left origin into OpenGL's bottom-left one and `pixelScale` converts window
  /// pixels to framebuffer pixels (1 except on high-DPI screens).
  /// `maxPoints` limits the cloud's points drawn (the first ones of a fixed shuffle: a uniform
  /// subsample; the level of detail while the view moves).
  void draw(viewer::ViewerState& state, int framebufferHeight, double pixelScale = 1.0,
            std::size_t maxPoints = SIZE_MAX);
  std::size_t cloudPoints() const { return static_cast<std::size_t>(cloudCount_); }

 private:
  void drawSceneLines(const std::vector<viewer::Line3>& lines, GLint tint);
  void uploadCloud(viewer::ViewerState& state);
  void uploadMesh(const viewer::ViewerState& state);
  void uploadHighlights(const viewer::ViewerState& state);

  GLuint pointProgram_ = 0, meshProgram_ = 0;
  GLuint cloudVao_ = 0, cloudPos_ = 0, cloudCol_ = 0;
  GLuint hlVao_ = 0, hlPos_ = 0;
  GLuint lineVao_ = 0, linePos_ = 0, lineCol_ = 0;
  GLuint meshVao_ = 0, meshVbo_ = 0, meshEbo_ = 0;
  std::uint64_t cloudVersion_ = 0, colorsVersion_ = 0, meshVersion_ = 0, hlVersion_ = 0;
  sketch::NodeId hlNode_ = sketch::kNoNode;
  GLsizei cloudCount_ = 0, meshIndexCount_ = 0, sliceCount_ = 0, inlierCount_ = 0;
  geom::Vec3 origin_ = geom::Vec3::Zero();  ///< subtracted from positions (float precision)
  viewer::PointLod lod_;                    ///< the upload order
  std::vector<float> posScratch_;
};

}  // namespace treesketch::gui
