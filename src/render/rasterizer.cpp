// Software rasterizer: half-space (edge function) triangle filling at pixel centres (Pineda,
// "A parallel algorithm for polygon rasterization", SIGGRAPH 1988), window depth interpolated
// linearly in screen space (exact for projective maps), DDA lines, near-plane clipping in clip space.
#include "treesketch/render/rasterizer.h"

#include <algorithm>
#include <cmath>

#include "treesketch/util/error.h"

namespace treesketch::render {

using geom::Vec3;

namespace {

constexpr double kMaxViewportSide = 16384;

/// Signed distance of a clip-space point in front of the near plane (>= 0: in front).
double nearDistance(const Eigen::Vector4d& c) { return c.z() + c.w(); }

Rgb scale(Rgb c, double f) {
  auto s = [f](std::uint8_t v) { return static_cast<std::uint8_t>(std::clamp(std::lround(v * f), 0L, 255L)); };
  return {s(c.r), s(c.g), s(c.b)};
}

}  // namespace

Rasterizer::Rasterizer(const geom::Camera& camera, Rgb background) : camera_(camera) {
  camera.validate("render camera");
  if (camera.viewport.width > kMaxViewportSide || camera.viewport.height > kMaxViewportSide)
    throw OptionsError("render camera: viewport larger than 16384 pixels a side");
  int w = std::max(1, static_cast<int>(std::lround(camera.viewport.width)));
  int h = std::max(1, static_cast<int>(std::lround(camera.viewport.height)));
  image_ = Image(w, h, background, 3);
  depth_.assign(static_cast<std::size_t>(w) * h, 1.0f);
  viewProj_ = camera.projection * camera.view;
  ortho_ = camera.isOrthographic();
  eye_ = camera.eye();
  forward_ = camera.forward();
}

Eigen::Vector4d Rasterizer::toClip(const Vec3& p) const {
  return viewProj_ * Eigen::Vector4d(p.x(), p.y(), p.z(), 1.0);
}

Rasterizer::Projected Rasterizer::toScreen(const Eigen::Vector4d& c) const {
  // Same mapping as Camera::project, minus the viewport's offset (the image starts at the viewport).
  const auto& vp = camera_.viewport;
  Vec3 ndc = c.head<3>() / c.w();
  return {(ndc.x() + 1.0) * 0.5 * vp.width, (1.0 - ndc.y()) * 0.5 * vp.height, 0.5 * (ndc.z() + 1.0)};
}

void Rasterizer::stamp(double x, double y, double depth, int size, Rgb color, PointDepth mode) {
  if (!(depth <= 1.0)) return;  // beyond the far plane (or NaN)
  const double half = 0.5 * size;
  const int x0 = static_cast<int>(std::floor(x - half + 0.5)), y0 = static_cast<int>(std::floor(y - half + 0.5));
  const float d = static_cast<float>(std::max(depth, 0.0));
  for (int py = std::max(y0, 0); py < std::min(y0 + size, image_.height); ++py) {
    for (int px = std::max(x0, 0); px < std::min(x0 + size, image_.width); ++px) {
      float& zb = depth_[static_cast<std::size_t>(py) * image_.width + px];
      if (mode == PointDepth::Test && !(d < zb)) continue;
      if (mode == PointDepth::EmptyOnly && zb < 1.0f) continue;
      zb = std::min(zb, d);
      image_.set(px, py, color);
    }
  }
}

bool Rasterizer::drawPoint(const Vec3& p, Rgb color, int sizePx, PointDepth depth) {
  if (!p.allFinite()) return false;
  Eigen::Vector4d c = toClip(p);
  if (nearDistance(c) < 0 || c.w() <= 0) return false;
  Projected s = toScreen(c);
  if (s.depth > 1.0) return false;
  const int size = std::clamp(sizePx, 1, 32);
  if (s.x + size < 0 || s.y + size < 0 || s.x - size > image_.width || s.y - size > image_.height) return false;
  stamp(s.x, s.y, s.depth, size, color, depth);
  return true;
}

bool Rasterizer::drawLine(const Vec3& a, const Vec3& b, Rgb color, const LineStyle& style) {
  if (!a.allFinite() || !b.allFinite()) return false;
  Eigen::Vector4d ca = toClip(a), cb = toClip(b);
  double da = nearDistance(ca), db = nearDistance(cb);
  if (da < 0 && db < 0) return false;
  if (da < 0)
    ca = ca + (cb - ca) * (da / (da - db));  // clip at the near plane
  else if (db < 0)
    cb = cb + (ca - cb) * (db / (db - da));
  if (ca.w() <= 0 || cb.w() <= 0) return false;
  Projected sa = toScreen(ca), sb = toScreen(cb);
  const int width = std::clamp(style.widthPx, 1, 8);
  // Clip the screen segment to the image (grown by the line width), Liang-Barsky style, so a
  // segment reaching far off screen is walked only where it can be seen.
  double t0 = 0.0, t1 = 1.0;
  const double dx = sb.x - sa.x, dy = sb.y - sa.y;
  auto clipAgainst = [&](double p, double q) {  // keeps the part where p * t <= q
    if (p == 0) return q >= 0;
    double t = q / p;
    if (p < 0)
      t0 = std::max(t0, t);
    else
      t1 = std::min(t1, t);
    return t0 <= t1;
  };
  const double lo = -width - 1.0, hiX = image_.width + width + 1.0, hiY = image_.height + width + 1.0;
  if (!clipAgainst(-dx, sa.x - lo) || !clipAgainst(dx, hiX - sa.x) || !clipAgainst(-dy, sa.y - lo) ||
      !clipAgainst(dy, hiY - sa.y))
    return true;  // in front of the camera but off screen
  const double len = (t1 - t0) * std::max(std::abs(dx), std::abs(dy));
  if (!std::isfinite(len)) return false;
  const int steps = std::max(1, static_cast<int>(std::ceil(len)));
  // Walk between the clipped ends (not from the far-away original ends: rounding there would
  // make the steps uneven and leave gaps).
  const double xs = sa.x + t0 * dx, ys = sa.y + t0 * dy, xe = sa.x + t1 * dx, ye = sa.y + t1 * dy;
  const double ds = sa.depth + t0 * (sb.depth - sa.depth), de = sa.depth + t1 * (sb.depth - sa.depth);
  for (int i = 0; i <= steps; ++i) {
    const double f = static_cast<double>(i) / steps;
    stamp(xs + f * (xe - xs), ys + f * (ye - ys), ds + f * (de - ds) - style.depthBias, width, color,
          style.depthTest ? PointDepth::Test : PointDepth::Ignore);
  }
  return true;
}

bool Rasterizer::drawTriangle(const std::array<Vec3, 3>& v, const std::array<Rgb, 3>& colors,
                              const TriangleStyle& style) {
  std::array<Projected, 3> s;
  for (int k = 0; k < 3; ++k) {
    if (!v[k].allFinite()) return false;
    Eigen::Vector4d c = toClip(v[k]);
    if (nearDistance(c) < 0 || c.w() <= 0) return false;
    s[k] = toScreen(c);
  }
  const double area = (s[1].x - s[0].x) * (s[2].y - s[0].y) - (s[2].x - s[0].x) * (s[1].y - s[0].y);
  if (!(std::abs(area) > 1e-12)) return false;

  double shade = 1.0;
  if (style.lambert) {
    Vec3 n = (v[1] - v[0]).cross(v[2] - v[0]);
    Vec3 toLight = ortho_ ? Vec3(-forward_) : Vec3(eye_ - (v[0] + v[1] + v[2]) / 3.0);
    double cosine = n.norm() > 0 && toLight.norm() > 0 ? std::abs(n.normalized().dot(toLight.normalized())) : 1.0;
    shade = style.ambient + style.diffuse * cosine;
  }
  const bool uniform = colors[0] == colors[1] && colors[1] == colors[2];
  const Rgb flat = scale(colors[0], shade);

  // Pixel bounds, clamped in floating point first (a vertex near the eye can project very far).
  auto toPixel = [](double v, int size) { return static_cast<int>(std::floor(std::clamp(v, -1.0, double(size)))); };
  const int x0 = std::max(0, toPixel(std::min({s[0].x, s[1].x, s[2].x}), image_.width));
  const int x1 = std::min(image_.width - 1, toPixel(std::max({s[0].x, s[1].x, s[2].x}), image_.width));
  const int y0 = std::max(0, toPixel(std::min({s[0].y, s[1].y, s[2].y}), image_.height));
  const int y1 = std::min(image_.height - 1, toPixel(std::max({s[0].y, s[1].y, s[2].y}), image_.height));
  const double inv = 1.0 / area;
  for (int py = y0; py <= y1; ++py) {
    const double y = py + 0.5;
    for (int px = x0; px <= x1; ++px) {
      const double x = px + 0.5;
      // Barycentric weights from the edge functions, normalised by the signed area (either winding).
      double b0 = ((s[1].x - x) * (s[2].y - y) - (s[2].x - x) * (s[1].y - y)) * inv;
      double b1 = ((s[2].x - x) * (s[0].y - y) - (s[0].x - x) * (s[2].y - y)) * inv;
      double b2 = 1.0 - b0 - b1;
      if (b0 < 0 || b1 < 0 || b2 < 0) continue;
      double d = b0 * s[0].depth + b1 * s[1].depth + b2 * s[2].depth;
      float& zb = depth_[static_cast<std::size_t>(py) * image_.width + px];
      if (!(d < zb) || d < 0.0) continue;
      zb = static_cast<float>(d);
      if (uniform) {
        image_.set(px, py, flat);
      } else {
        auto mix = [&](std::uint8_t Rgb::*ch) {
          return b0 * (colors[0].*ch) + b1 * (colors[1].*ch) + b2 * (colors[2].*ch);
        };
        Rgb c{static_cast<std::uint8_t>(std::clamp(std::lround(mix(&Rgb::r)), 0L, 255L)),
              static_cast<std::uint8_t>(std::clamp(std::lround(mix(&Rgb::g)), 0L, 255L)),
              static_cast<std::uint8_t>(std::clamp(std::lround(mix(&Rgb::b)), 0L, 255L))};
        image_.set(px, py, scale(c, shade));
      }
    }
  }
  if (style.wireframe) {
    LineStyle edge;
    for (int k = 0; k < 3; ++k) drawLine(v[k], v[(k + 1) % 3], style.wireColor, edge);
  }
  return true;
}

std::size_t Rasterizer::drawMesh(const geom::TriMesh& mesh, Rgb color, const TriangleStyle& style) {
  mesh.checkConsistent();
  const bool perVertex = style.useVertexColors && mesh.colors.size() == mesh.vertices.size();
  std::size_t drawn = 0;
  for (const auto& t : mesh.triangles) {
    std::array<Vec3, 3> v = {mesh.vertices[t[0]], mesh.vertices[t[1]], mesh.vertices[t[2]]};
    std::array<Rgb, 3> c = {color, color, color};
    if (perVertex) {
      for (int k = 0; k < 3; ++k) c[k] = {mesh.colors[t[k]][0], mesh.colors[t[k]][1], mesh.colors[t[k]][2]};
    }
    if (drawTriangle(v, c, style)) ++drawn;
  }
  return drawn;
}

}  // namespace treesketch::render
