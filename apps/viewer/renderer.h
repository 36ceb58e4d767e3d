// OpenGL 3.3 core drawing of a ViewerState: the cloud as points (one VBO, re-uploaded only when
// the cloud or its colours change), the selected node's slice points, 3D lines (circles, sampling
// region) and the tube mesh (solid or wireframe). Node markers are drawn by the panels (ImGui).
// The scene is drawn into an offscreen image that is copied to the window each frame and drawn
// anew only when what it shows changes (SceneKey): a frame drawn for the panel alone (the mouse
// moving over it, a tooltip) does not draw the cloud again.
#pragma once

#include <GL/glew.h>

#include <cstdint>
#include <string>
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
  /// Draws that drew the 3D scene (the cloud, mesh and lines) anew.
  std::uint64_t sceneDraws() const { return sceneDraws_; }
  /// The window's background, behind the scene.
  static constexpr float kBackground[3] = {0.11f, 0.12f, 0.14f};

 private:
  /// Everything the scene's image depends on, as bytes: the camera, the viewport, what was
  /// uploaded (versions), the display options, the points drawn and the 3D lines.
  std::string sceneKey(const viewer::ViewerState& state, const std::vector<viewer::Line3>& lines, int framebufferHeight,
                       double pixelScale, std::size_t points) const;
  void drawScene(const viewer::ViewerState& state, const std::vector<viewer::Line3>& lines, double pixelScale,
                 std::size_t points);
  /// The offscreen image of `width` x `height` framebuffer pixels (made again when the size changes).
  void ensureTarget(int width, int height);
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
  std::uint64_t sceneDraws_ = 0;
  GLuint fbo_ = 0, fboColor_ = 0, fboDepth_ = 0;
  int fboWidth_ = 0, fboHeight_ = 0;
  std::string lastKey_;  ///< the key of the image in fbo_ ("" when there is none)
};

}  // namespace treesketch::gui
