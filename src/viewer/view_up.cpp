#include "treesketch/viewer/view_up.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "treesketch/io/up_axis.h"
#include "treesketch/render/color_map.h"
#include "treesketch/util/error.h"
#include "treesketch/util/text.h"

namespace treesketch::viewer {

const char* toString(UpDirection d) {
  switch (d) {
    case UpDirection::PosX:
      return "+x";
    case UpDirection::NegX:
      return "-x";
    case UpDirection::PosY:
      return "+y";
    case UpDirection::NegY:
      return "-y";
    case UpDirection::PosZ:
      return "+z";
    case UpDirection::NegZ:
      return "-z";
  }
  return "?";
}

UpDirection parseUpDirection(const std::string& s) {
  std::string k = lowercase(s);
  if (k.size() == 1) k = "+" + k;
  for (UpDirection d : {UpDirection::PosX, UpDirection::NegX, UpDirection::PosY, UpDirection::NegY, UpDirection::PosZ,
                        UpDirection::NegZ})
    if (k == toString(d)) return d;
  throw OptionsError("up direction must be +x, -x, +y, -y, +z or -z, got '" + s + "'");
}

geom::Vec3 upDirectionVector(UpDirection d) {
  const int axis = static_cast<int>(d) / 2;
  const double sign = static_cast<int>(d) % 2 == 0 ? 1.0 : -1.0;
  geom::Vec3 v = geom::Vec3::Zero();
  v[axis] = sign;
  return v;
}

std::optional<geom::UpAxis> libraryUpAxis(UpDirection d) {
  if (d == UpDirection::PosY) return geom::UpAxis::Y;
  if (d == UpDirection::PosZ) return geom::UpAxis::Z;
  return std::nullopt;
}

UpDirection toUpDirection(geom::UpAxis up) { return up == geom::UpAxis::Y ? UpDirection::PosY : UpDirection::PosZ; }

ViewUpChoice chooseViewUp(const std::string& option, const geom::PointCloud& cloud, bool demo) {
  ViewUpChoice c;
  std::optional<UpDirection> asked;
  if (!option.empty()) asked = parseUpDirection(option);
  std::optional<geom::UpAxis> axis = asked ? libraryUpAxis(*asked) : std::nullopt;
  if (demo) {
    c.axis = axis.value_or(geom::UpAxis::Y);
    c.reason = axis ? "--up " + option : "the demo tree is y-up";
  } else {
    io::UpAxisChoice rule = io::chooseUpAxis(axis ? geom::toString(*axis) : "", cloud);
    c.axis = rule.up;
    c.reason = asked && !axis ? "the file's axis: " + rule.reason : rule.reason;
  }
  c.view = asked ? *asked : toUpDirection(c.axis);
  if (asked && !axis) c.reason = "--up " + option + " (view only; " + c.reason + ")";
  return c;
}

// Height / widest horizontal extent below which a cloud is said to lie down. Design choice: a
// standing tree is rarely less than 0.7 times as tall as its crown is wide (the demo tree lying on
// its side measures 0.55-0.6); a broad open-grown crown may be warned about, which costs one
// Dismiss, while a missed warning shows the tree from above with no hint.
constexpr double kLyingDownRatio = 0.7;

std::string lyingDownWarning(const geom::BBox& bounds, UpDirection up) {
  if (bounds.empty()) return {};
  const geom::Vec3 ext = bounds.extent();
  const int axis = static_cast<int>(up) / 2;
  double horizontal = 0.0;
  int widest = 0;
  for (int k = 0; k < 3; ++k)
    if (k != axis && ext[k] > horizontal) horizontal = ext[k], widest = k;
  if (!(ext[axis] < kLyingDownRatio * horizontal)) return {};
  char text[320];
  std::snprintf(text, sizeof text,
                "the cloud looks lying down with up %s: %.2f tall but %.2f along %c. If it is a standing tree, "
                "choose its up axis (View > up axis, or start with --up)",
                toString(up), ext[axis], horizontal, "xyz"[widest]);
  return text;
}

std::vector<render::Rgb> heightColorsAlong(const geom::PointCloud& cloud, UpDirection up,
                                           std::pair<double, double>* range) {
  const geom::Vec3 u = upDirectionVector(up);
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (const geom::Vec3& p : cloud.positions) {
    double h = p.dot(u);
    if (std::isfinite(h)) lo = std::min(lo, h), hi = std::max(hi, h);
  }
  if (range) *range = {std::isfinite(lo) ? lo : 0.0, std::isfinite(hi) ? hi : 0.0};
  std::vector<render::Rgb> colors;
  colors.reserve(cloud.size());
  const double span = hi > lo ? hi - lo : 0.0;
  for (const geom::Vec3& p : cloud.positions)
    colors.push_back(render::viridis(span > 0 ? (p.dot(u) - lo) / span : 0.5));
  return colors;
}

}  // namespace treesketch::viewer
