#include "renderer.h"

#include <algorithm>
#include <stdexcept>
#include <string>
#include <vector>

namespace treesketch::gui {

using geom::Vec3;

namespace {

const char* kPointVs = R"(#version 330 core
layout(location = 0) in vec3 aPos;
layout(location = 1) in vec3 aColor;
uniform mat4 uMvp;
uniform float uPointSize;
uniform vec4 uTint;  // a > 0: draw everything in this colour
out vec3 vColor;
void main() {
  gl_Position = uMvp * vec4(aPos, 1.0);
  gl_PointSize = uPointSize;
  vColor = uTint.a > 0.0 ? uTint.rgb : aColor;
}
)";
const char* kPointFs = R"(#version 330 core
in vec3 vColor;
out vec4 fragColor;
void main() { fragColor = vec4(vColor, 1.0); }
)";
const char* kMeshVs = R"(#version 330 core
layout(location = 0) in vec3 aPos;
layout(location = 1) in vec3 aNormal;
uniform mat4 uMvp;
uniform mat3 uNormalMatrix;
out vec3 vNormal;
void main() {
  gl_Position = uMvp * vec4(aPos, 1.0);
  vNormal = uNormalMatrix * aNormal;
}
)";
const char* kMeshFs = R"(#version 330 core
in vec3 vNormal;
uniform vec3 uColor;
uniform float uLit;
out vec4 fragColor;
void main() {
  float k = 1.0;
  if (uLit > 0.5) {
    vec3 n = normalize(vNormal);
    k = 0.35 + 0.65 * abs(n.z);  // headlight
  }
  fragColor = vec4(uColor * k, 1.0);
}
)";

GLuint compile(GLenum type, const char* src) {
  GLuint s = glCreateShader(type);
  glShaderSource(s, 1, &src, nullptr);
  glCompileShader(s);
  GLint ok = 0;
  glGetShaderiv(s, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    char log[2048];
    glGetShaderInfoLog(s, sizeof log, nullptr, log);
    throw std::runtime_error(std::string("shader compile failed: ") + log);
  }
  return s;
}

GLuint link(const char* vs, const char* fs) {
  GLuint p = glCreateProgram();
  GLuint v = compile(GL_VERTEX_SHADER, vs), f = compile(GL_FRAGMENT_SHADER, fs);
  glAttachShader(p, v);
  glAttachShader(p, f);
  glLinkProgram(p);
  glDeleteShader(v);
  glDeleteShader(f);
  GLint ok = 0;
  glGetProgramiv(p, GL_LINK_STATUS, &ok);
  if (!ok) {
    char log[2048];
    glGetProgramInfoLog(p, sizeof log, nullptr, log);
    throw std::runtime_error(std::string("shader link failed: ") + log);
  }
  return p;
}

void setVec3Attrib(GLuint vao, GLuint vbo, GLuint location, GLenum type, GLboolean normalized) {
  glBindVertexArray(vao);
  glBindBuffer(GL_ARRAY_BUFFER, vbo);
  glEnableVertexAttribArray(location);
  glVertexAttribPointer(location, 3, type, normalized, 0, nullptr);
}

Eigen::Matrix4f toFloat(const geom::Mat4& m) { return m.cast<float>(); }

}  // namespace

Renderer::Renderer() {
  pointProgram_ = link(kPointVs, kPointFs);
  meshProgram_ = link(kMeshVs, kMeshFs);
  GLuint vaos[4];
  glGenVertexArrays(4, vaos);
  cloudVao_ = vaos[0];
  hlVao_ = vaos[1];
  lineVao_ = vaos[2];
  meshVao_ = vaos[3];
  GLuint bufs[7];
  glGenBuffers(7, bufs);
  cloudPos_ = bufs[0];
  cloudCol_ = bufs[1];
  hlPos_ = bufs[2];
  linePos_ = bufs[3];
  lineCol_ = bufs[4];
  meshVbo_ = bufs[5];
  meshEbo_ = bufs[6];
  setVec3Attrib(cloudVao_, cloudPos_, 0, GL_FLOAT, GL_FALSE);
  setVec3Attrib(cloudVao_, cloudCol_, 1, GL_UNSIGNED_BYTE, GL_TRUE);
  setVec3Attrib(hlVao_, hlPos_, 0, GL_FLOAT, GL_FALSE);
  glVertexAttrib3f(1, 1, 1, 1);
  setVec3Attrib(lineVao_, linePos_, 0, GL_FLOAT, GL_FALSE);
  setVec3Attrib(lineVao_, lineCol_, 1, GL_UNSIGNED_BYTE, GL_TRUE);
  glBindVertexArray(meshVao_);
  glBindBuffer(GL_ARRAY_BUFFER, meshVbo_);
  glEnableVertexAttribArray(0);
  glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 6 * sizeof(float), nullptr);
  glEnableVertexAttribArray(1);
  glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, 6 * sizeof(float), reinterpret_cast<void*>(3 * sizeof(float)));
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, meshEbo_);
  glBindVertexArray(0);
}

Renderer::~Renderer() {
  GLuint vaos[4] = {cloudVao_, hlVao_, lineVao_, meshVao_};
  glDeleteVertexArrays(4, vaos);
  GLuint bufs[7] = {cloudPos_, cloudCol_, hlPos_, linePos_, lineCol_, meshVbo_, meshEbo_};
  glDeleteBuffers(7, bufs);
  glDeleteProgram(pointProgram_);
  glDeleteProgram(meshProgram_);
  if (fbo_) {
    glDeleteFramebuffers(1, &fbo_);
    glDeleteTextures(1, &fboColor_);
    glDeleteRenderbuffers(1, &fboDepth_);
  }
}

void Renderer::uploadCloud(viewer::ViewerState& state) {
  const geom::PointCloud& cloud = state.cloud();
  if (cloudVersion_ != state.cloudVersion()) {
    cloudVersion_ = state.cloudVersion();
    origin_ = cloud.empty() ? Vec3::Zero() : state.bounds().centre();
    lod_.build(cloud.size());
    lod_.positions(cloud, origin_, posScratch_);
    glBindBuffer(GL_ARRAY_BUFFER, cloudPos_);
    glBufferData(GL_ARRAY_BUFFER, posScratch_.size() * sizeof(float), posScratch_.data(), GL_STATIC_DRAW);
    cloudCount_ = static_cast<GLsizei>(cloud.size());
    colorsVersion_ = 0;
    hlVersion_ = 0;
    meshVersion_ = 0;
  }
  const std::vector<viewer::Rgb>& colors = state.scene().pointColors();
  if (colorsVersion_ != state.scene().colorsVersion()) {
    colorsVersion_ = state.scene().colorsVersion();
    const std::vector<std::uint8_t>& ordered = lod_.keptColors(colors);  // the positions' upload order
    glBindBuffer(GL_ARRAY_BUFFER, cloudCol_);
    glBufferData(GL_ARRAY_BUFFER, ordered.size(), ordered.data(), GL_DYNAMIC_DRAW);
  }
}

void Renderer::uploadMesh(const viewer::ViewerState& state) {
  if (meshVersion_ == state.sceneVersion()) return;
  meshVersion_ = state.sceneVersion();
  const geom::TriMesh& mesh = state.scene().mesh();
  // Per-vertex normals: area-weighted sums of the face normals.
  std::vector<Vec3> normals(mesh.vertices.size(), Vec3::Zero());
  for (const auto& t : mesh.triangles) {
    if (t[0] >= mesh.vertices.size() || t[1] >= mesh.vertices.size() || t[2] >= mesh.vertices.size()) continue;
    Vec3 n = (mesh.vertices[t[1]] - mesh.vertices[t[0]]).cross(mesh.vertices[t[2]] - mesh.vertices[t[0]]);
    for (int k = 0; k < 3; ++k) normals[t[k]] += n;
  }
  std::vector<float> data(6 * mesh.vertices.size());
  for (std::size_t i = 0; i < mesh.vertices.size(); ++i) {
    Vec3 n = normals[i].norm() > 0 ? Vec3(normals[i].normalized()) : Vec3::UnitY();
    for (int k = 0; k < 3; ++k) {
      data[6 * i + k] = static_cast<float>(mesh.vertices[i][k] - origin_[k]);
      data[6 * i + 3 + k] = static_cast<float>(n[k]);
    }
  }
  glBindVertexArray(meshVao_);
  glBindBuffer(GL_ARRAY_BUFFER, meshVbo_);
  glBufferData(GL_ARRAY_BUFFER, data.size() * sizeof(float), data.data(), GL_DYNAMIC_DRAW);
  glBufferData(GL_ELEMENT_ARRAY_BUFFER, mesh.triangles.size() * 3 * sizeof(std::uint32_t), mesh.triangles.data(),
               GL_DYNAMIC_DRAW);
  glBindVertexArray(0);
  meshIndexCount_ = static_cast<GLsizei>(mesh.triangles.size() * 3);
}

void Renderer::uploadHighlights(const viewer::ViewerState& state) {
  if (hlVersion_ == state.sceneVersion() && hlNode_ == state.tools().selected()) return;
  hlVersion_ = state.sceneVersion();
  hlNode_ = state.tools().selected();
  std::vector<std::uint32_t> slice = state.scene().highlightedSlicePoints();
  std::vector<std::uint32_t> inliers = state.scene().highlightedInliers();
  const geom::PointCloud& cloud = state.cloud();
  std::vector<float> pos;
  pos.reserve(3 * (slice.size() + inliers.size()));
  for (const auto* list : {&slice, &inliers})
    for (std::uint32_t i : *list)
      if (i < cloud.size())
        for (int k = 0; k < 3; ++k) pos.push_back(static_cast<float>(cloud.positions[i][k] - origin_[k]));
  sliceCount_ = static_cast<GLsizei>(slice.size());
  inlierCount_ = static_cast<GLsizei>(pos.size() / 3) - sliceCount_;
  glBindBuffer(GL_ARRAY_BUFFER, hlPos_);
  glBufferData(GL_ARRAY_BUFFER, pos.size() * sizeof(float), pos.data(), GL_DYNAMIC_DRAW);
}

// Circles, regions and links as coloured lines, drawn over everything.
void Renderer::drawSceneLines(const std::vector<viewer::Line3>& lines, GLint tint) {
  if (lines.empty()) return;
  std::vector<float> pos;
  std::vector<std::uint8_t> col;
  pos.reserve(6 * lines.size());
  col.reserve(6 * lines.size());
  for (const viewer::Line3& l : lines) {
    for (const Vec3* p : {&l.a, &l.b}) {
      for (int k = 0; k < 3; ++k) pos.push_back(static_cast<float>((*p)[k] - origin_[k]));
      col.insert(col.end(), {l.color.r, l.color.g, l.color.b});
    }
  }
  glUseProgram(pointProgram_);
  glUniform4f(tint, 0, 0, 0, 0);
  glBindVertexArray(lineVao_);
  glBindBuffer(GL_ARRAY_BUFFER, linePos_);
  glBufferData(GL_ARRAY_BUFFER, pos.size() * sizeof(float), pos.data(), GL_STREAM_DRAW);
  glBindBuffer(GL_ARRAY_BUFFER, lineCol_);
  glBufferData(GL_ARRAY_BUFFER, col.size(), col.data(), GL_STREAM_DRAW);
  glDisable(GL_DEPTH_TEST);  // circles and regions stay visible through the mesh
  glDrawArrays(GL_LINES, 0, static_cast<GLsizei>(pos.size() / 3));
  glEnable(GL_DEPTH_TEST);
}

namespace {

template <class T>
void append(std::string& key, const T& value) {
  key.append(reinterpret_cast<const char*>(&value), sizeof value);
}

}  // namespace

std::string Renderer::sceneKey(const viewer::ViewerState& state, const std::vector<viewer::Line3>& lines,
                               int framebufferHeight, double pixelScale, std::size_t points) const {
  const geom::Camera cam = state.view().camera();
  const viewer::DisplayOptions& d = state.view().display();
  std::string key;
  key.reserve(512 + lines.size() * sizeof(viewer::Line3));
  key.append(reinterpret_cast<const char*>(cam.view.data()), sizeof(double) * 16);
  key.append(reinterpret_cast<const char*>(cam.projection.data()), sizeof(double) * 16);
  for (double v : {cam.viewport.x, cam.viewport.y, cam.viewport.width, cam.viewport.height, pixelScale}) append(key, v);
  for (std::uint64_t v : {cloudVersion_, colorsVersion_, meshVersion_, hlVersion_, std::uint64_t(points)})
    append(key, v);
  for (int v : {framebufferHeight, int(hlNode_), int(cloudCount_), int(meshIndexCount_), int(sliceCount_),
                int(inlierCount_), int(d.meshStyle), int(d.showCloud)})
    append(key, v);
  append(key, d.pointSize);
  for (const viewer::Line3& l : lines) {
    append(key, l.a);
    append(key, l.b);
    for (std::uint8_t c : {l.color.r, l.color.g, l.color.b}) append(key, c);
  }
  return key;
}

void Renderer::ensureTarget(int width, int height) {
  if (fbo_ && width == fboWidth_ && height == fboHeight_) return;
  if (!fbo_) {
    glGenFramebuffers(1, &fbo_);
    glGenTextures(1, &fboColor_);
    glGenRenderbuffers(1, &fboDepth_);
  }
  glBindTexture(GL_TEXTURE_2D, fboColor_);
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, width, height, 0, GL_RGBA, GL_UNSIGNED_BYTE, nullptr);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  glBindTexture(GL_TEXTURE_2D, 0);
  glBindRenderbuffer(GL_RENDERBUFFER, fboDepth_);
  glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT24, width, height);
  glBindRenderbuffer(GL_RENDERBUFFER, 0);
  glBindFramebuffer(GL_FRAMEBUFFER, fbo_);
  glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, fboColor_, 0);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, fboDepth_);
  const GLenum status = glCheckFramebufferStatus(GL_FRAMEBUFFER);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  if (status != GL_FRAMEBUFFER_COMPLETE) throw std::runtime_error("the scene's offscreen framebuffer is incomplete");
  fboWidth_ = width;
  fboHeight_ = height;
  lastKey_.clear();
}

void Renderer::draw(viewer::ViewerState& state, int framebufferHeight, double pixelScale, std::size_t maxPoints) {
  const geom::Viewport vp = state.view().camera().viewport;
  const double k = pixelScale > 0 ? pixelScale : 1.0;
  const GLint x = static_cast<GLint>(vp.x * k), y = static_cast<GLint>(framebufferHeight - (vp.y + vp.height) * k);
  const GLsizei w = static_cast<GLsizei>(vp.width * k), h = static_cast<GLsizei>(vp.height * k);
  if (state.cloud().empty() || w <= 0 || h <= 0) return;
  uploadCloud(state);
  uploadMesh(state);
  uploadHighlights(state);
  const std::vector<viewer::Line3> lines = state.scene().sceneLines();
  const std::size_t points = std::min<std::size_t>(cloudCount_, maxPoints);
  ensureTarget(w, h);
  std::string key = sceneKey(state, lines, framebufferHeight, k, points);
  if (key != lastKey_) {
    glBindFramebuffer(GL_FRAMEBUFFER, fbo_);
    glViewport(0, 0, w, h);
    glClearColor(kBackground[0], kBackground[1], kBackground[2], 1.0f);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    drawScene(state, lines, k, points);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    lastKey_ = std::move(key);
    ++sceneDraws_;
  }
  glBindFramebuffer(GL_READ_FRAMEBUFFER, fbo_);
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
  glBlitFramebuffer(0, 0, w, h, x, y, x + w, y + h, GL_COLOR_BUFFER_BIT, GL_NEAREST);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

void Renderer::drawScene(const viewer::ViewerState& state, const std::vector<viewer::Line3>& lines, double k,
                         std::size_t points) {
  const geom::Camera cam = state.view().camera();
  glEnable(GL_DEPTH_TEST);
  glEnable(GL_PROGRAM_POINT_SIZE);
  geom::Mat4 model = geom::Mat4::Identity();
  model.block<3, 1>(0, 3) = origin_;
  Eigen::Matrix4f mvp = toFloat(cam.projection * cam.view * model);
  Eigen::Matrix3f normalMatrix = cam.view.block<3, 3>(0, 0).cast<float>();
  const viewer::DisplayOptions& d = state.view().display();

  glUseProgram(pointProgram_);
  glUniformMatrix4fv(glGetUniformLocation(pointProgram_, "uMvp"), 1, GL_FALSE, mvp.data());
  GLint tint = glGetUniformLocation(pointProgram_, "uTint");
  GLint size = glGetUniformLocation(pointProgram_, "uPointSize");
  if (d.showCloud) {
    glUniform4f(tint, 0, 0, 0, 0);
    glUniform1f(size, static_cast<float>(d.pointSize * k));
    glBindVertexArray(cloudVao_);
    glDrawArrays(GL_POINTS, 0, static_cast<GLsizei>(points));
  }
  if (sliceCount_ + inlierCount_ > 0) {
    glBindVertexArray(hlVao_);
    glDepthFunc(GL_LEQUAL);
    glUniform1f(size, static_cast<float>((d.pointSize + 2.0) * k));
    glUniform4f(tint, 0.2f, 0.85f, 1.0f, 1.0f);  // slice points: cyan
    glDrawArrays(GL_POINTS, 0, sliceCount_);
    glUniform1f(size, static_cast<float>((d.pointSize + 3.0) * k));
    glUniform4f(tint, 1.0f, 0.15f, 0.15f, 1.0f);  // circle inliers: red
    glDrawArrays(GL_POINTS, sliceCount_, inlierCount_);
    glDepthFunc(GL_LESS);
  }

  if (d.meshStyle != viewer::MeshStyle::Hidden && meshIndexCount_ > 0) {
    glUseProgram(meshProgram_);
    glUniformMatrix4fv(glGetUniformLocation(meshProgram_, "uMvp"), 1, GL_FALSE, mvp.data());
    glUniformMatrix3fv(glGetUniformLocation(meshProgram_, "uNormalMatrix"), 1, GL_FALSE, normalMatrix.data());
    bool wire = d.meshStyle == viewer::MeshStyle::Wireframe;
    glUniform3f(glGetUniformLocation(meshProgram_, "uColor"), wire ? 0.95f : 0.72f, wire ? 0.95f : 0.55f,
                wire ? 0.95f : 0.38f);
    glUniform1f(glGetUniformLocation(meshProgram_, "uLit"), wire ? 0.0f : 1.0f);
    if (wire) glPolygonMode(GL_FRONT_AND_BACK, GL_LINE);
    glBindVertexArray(meshVao_);
    glDrawElements(GL_TRIANGLES, meshIndexCount_, GL_UNSIGNED_INT, nullptr);
    if (wire) glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);
  }

  drawSceneLines(lines, tint);
  glBindVertexArray(0);
  glUseProgram(0);
}

}  // namespace treesketch::gui
