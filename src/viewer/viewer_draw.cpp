// Scene, what the window draws of a ViewerState (viewer/scene.h): display option names, point
// colours, node markers (and picking them), 3D lines for circles and the selected node's sampling
// region, highlighted points, the mesh and counts. See viewer_state.h for the map of the files.
#include <algorithm>
#include <cmath>
#include <exception>
#include <limits>

#include "treesketch/classify/classify.h"
#include "treesketch/model/tree_model.h"
#include "treesketch/render/color_map.h"
#include "treesketch/util/error.h"
#include "treesketch/util/text.h"
#include "treesketch/viewer/color_legend.h"
#include "treesketch/viewer/scene.h"
#include "treesketch/viewer/viewer_state.h"

namespace treesketch::viewer {

using geom::Vec2;
using geom::Vec3;

namespace {

constexpr Rgb kCircleColor = {255, 150, 30};
constexpr Rgb kSelectedCircleColor = {255, 50, 50};
constexpr Rgb kSlabColor = {40, 200, 255};
constexpr Rgb kCylinderColor = {255, 60, 255};

/// Appends a polyline ring (circle of `radius` around `centre` in the plane of unit `normal`).
void addRing(std::vector<Line3>& out, const Vec3& centre, const Vec3& normal, double radius, int segments,
             const Rgb& color) {
  Vec3 u = geom::anyPerpendicular(normal);
  Vec3 v = normal.normalized().cross(u);
  segments = std::max(segments, 3);
  Vec3 prev = centre + radius * u;
  for (int i = 1; i <= segments; ++i) {
    double a = 2.0 * M_PI * i / segments;
    Vec3 p = centre + radius * (std::cos(a) * u + std::sin(a) * v);
    out.push_back(Line3{prev, p, color});
    prev = p;
  }
}

/// The parameter range [t0, t1] where the line p + t d passes through `box` grown by `margin`;
/// false when it misses.
bool clipLineToBox(const Vec3& p, const Vec3& d, const geom::BBox& box, double margin, double* t0, double* t1) {
  double lo = -std::numeric_limits<double>::infinity(), hi = std::numeric_limits<double>::infinity();
  for (int k = 0; k < 3; ++k) {
    double mn = box.min[k] - margin, mx = box.max[k] + margin;
    if (std::abs(d[k]) < 1e-15) {
      if (p[k] < mn || p[k] > mx) return false;
      continue;
    }
    double a = (mn - p[k]) / d[k], b = (mx - p[k]) / d[k];
    lo = std::max(lo, std::min(a, b));
    hi = std::min(hi, std::max(a, b));
  }
  if (!(lo <= hi)) return false;
  *t0 = lo;
  *t1 = hi;
  return true;
}

}  // namespace

ColorMode parseColorMode(const std::string& s) {
  std::string k = lowercase(s);
  if (k == "height") return ColorMode::Height;
  if (k == "distance" || k == "circle-distance") return ColorMode::CircleDistance;
  if (k == "plain") return ColorMode::Plain;
  if (k == "intensity") return ColorMode::Intensity;
  if (k == "rgb" || k == "color" || k == "colour") return ColorMode::FileColor;
  if (k == "classification" || k == "class") return ColorMode::Classification;
  if (k == "wood-probability") return ColorMode::WoodProbability;
  if (k == "wood-class" || k == "wood") return ColorMode::WoodClass;
  throw OptionsError("colour mode must be 'height', 'distance', 'plain', 'intensity', 'rgb', 'classification', "
                     "'wood-probability' or 'wood-class', got '" + s + "'");
}

MeshStyle parseMeshStyle(const std::string& s) {
  std::string k = lowercase(s);
  if (k == "solid") return MeshStyle::Solid;
  if (k == "wireframe") return MeshStyle::Wireframe;
  if (k == "hidden") return MeshStyle::Hidden;
  throw OptionsError("mesh style must be 'solid', 'wireframe' or 'hidden', got '" + s + "'");
}

const char* toString(ColorMode mode) {
  switch (mode) {
    case ColorMode::Height:
      return "height";
    case ColorMode::CircleDistance:
      return "distance";
    case ColorMode::Plain:
      return "plain";
    case ColorMode::Intensity:
      return "intensity";
    case ColorMode::FileColor:
      return "rgb";
    case ColorMode::Classification:
      return "classification";
    case ColorMode::WoodProbability:
      return "wood-probability";
    case ColorMode::WoodClass:
      return "wood-class";
  }
  return "?";
}

const char* toString(MeshStyle style) {
  switch (style) {
    case MeshStyle::Solid:
      return "solid";
    case MeshStyle::Wireframe:
      return "wireframe";
    case MeshStyle::Hidden:
      return "hidden";
  }
  return "?";
}

const char* toString(NodeStatus status) {
  switch (status) {
    case NodeStatus::Pending:
      return "pending";
    case NodeStatus::Fitted:
      return "fitted";
    case NodeStatus::Skipped:
      return "skipped";
  }
  return "?";
}

// ---- display and status --------------------------------------------------------------------------

LabelMode parseLabelMode(const std::string& s) {
  std::string k = lowercase(s);
  if (k == "auto") return LabelMode::Auto;
  if (k == "on" || k == "true") return LabelMode::On;
  if (k == "off" || k == "false") return LabelMode::Off;
  throw OptionsError("labels must be 'auto', 'on' or 'off', got '" + s + "'");
}

const char* toString(LabelMode mode) {
  switch (mode) {
    case LabelMode::Auto:
      return "auto";
    case LabelMode::On:
      return "on";
    case LabelMode::Off:
      return "off";
  }
  return "?";
}

bool Scene::labelsShown() const {
  switch (s_.view_.display().labels) {
    case LabelMode::On:
      return true;
    case LabelMode::Off:
      return false;
    case LabelMode::Auto:
      break;
  }
  return s_.sketch_.size() <= s_.options_.autoLabelMaxNodes;
}

// ---- what to draw --------------------------------------------------------------------------------

const std::vector<Rgb>& Scene::pointColors() {
  if (colorsStale_ || colorsMode_ != s_.view_.display().colorMode || colors_.size() != s_.cloud_.size() ||
      colorsNotWood_ != s_.sketch_.notWood() || colorsClasses_ != s_.classesVersion_) {
    colorsClasses_ = s_.classesVersion_;
    colorsMode_ = s_.view_.display().colorMode;
    colorsNotWood_ = s_.sketch_.notWood();
    switch (colorsMode_) {
      case ColorMode::Height:
        colors_ = heightColorsAlong(s_.cloud_, s_.view_.upDirection());
        break;
      case ColorMode::Plain:
        colors_ = plainColors(s_.cloud_, s_.options_.plainColor);
        break;
      case ColorMode::CircleDistance: {
        const double scale = s_.options_.distanceColorScale * std::max(s_.bounds_.diagonal(), 1e-12);
        if (distanceGridVersion_ != s_.cloudVersion_ || !distanceGrid_.builtFor(s_.cloud_, scale)) {
          distanceGrid_.build(s_.cloud_, scale);  // once per cloud
          distanceGridVersion_ = s_.cloudVersion_;
        }
        // The distance to the model's surface (its frustums, what fit-report measures): zero on
        // the tubes, also between two circles. A sketch with no two linked fitted nodes has no
        // surface yet: the distance to its fitted circles stands in.
        const model::TreeModel tree = treeModel();
        if (!tree.cylinders.empty()) {
          distanceGrid_.surfaceColors(tree.cylinders, colors_);
          break;
        }
        std::vector<Circle3> circles;
        for (NodeId id : s_.sketch_.ids()) {
          NodeFitView f = s_.recon_->nodeFit(id);
          if (f.status == NodeStatus::Fitted) circles.push_back(f.circle);
        }
        distanceGrid_.colors(circles, colors_);
        break;
      }
      case ColorMode::Intensity:
      case ColorMode::FileColor:
      case ColorMode::Classification:
        colors_ = attributeColors(s_.cloud_, colorsMode_);
        if (colors_.size() != s_.cloud_.size()) colors_ = plainColors(s_.cloud_, s_.options_.plainColor);
        break;
      case ColorMode::WoodProbability:
      case ColorMode::WoodClass:
        colors_ = s_.classes_ ? woodColors(colorsMode_ == ColorMode::WoodProbability ? s_.classes_->woodProbability
                                                                                     : std::vector<float>{},
                                           s_.woodAfterLassos())
                              : plainColors(s_.cloud_, s_.options_.plainColor);
        break;
    }
    // Not-wood points (the sketch's lassos) are drawn dark, whatever the colour mode (the wood
    // class shows them as leaf already).
    if (!s_.sketch_.notWood().empty() && colorsMode_ != ColorMode::WoodClass)
      for (std::size_t i = 0; i < s_.cloud_.size(); ++i)
        if (s_.sketch_.isNotWood(s_.cloud_.positions[i])) colors_[i] = Rgb{60, 50, 70};
    colorsStale_ = false;
    ++colorsVersion_;
  }
  return colors_;
}

model::TreeModel Scene::treeModel() const {
  if (!s_.recon_) return {};
  return model::fromReconstruction(s_.recon_->result(), s_.sketch_.up);
}

NodeFitView Scene::nodeFit(NodeId id) const { return s_.recon_->nodeFit(id); }

std::vector<NodeMarker> Scene::nodeMarkers() const {
  std::vector<NodeMarker> markers;
  geom::Camera cur = s_.view_.camera();
  markers.reserve(s_.sketch_.size());
  const bool currentView = !s_.sketch_.cameras().empty();
  std::vector<bool> sameCamera(s_.sketch_.cameras().size());
  for (std::size_t c = 0; currentView && c < sameCamera.size(); ++c)
    sameCamera[c] = s_.sameAsCurrent(s_.sketch_.cameras()[c]);
  for (const auto& [id, node] : s_.sketch_.nodes()) {
    NodeMarker m;
    m.id = id;
    m.parent = node.parent;
    m.selected = id == s_.tools_.selected();
    m.active = id == s_.tools_.active();
    m.status = s_.recon_->nodeFit(id).status;
    // A node goes with a pending Delete subtree when the path to the root meets its root.
    m.doomed = s_.pendingDelete_ != kNoNode && s_.sketch_.contains(s_.pendingDelete_);
    for (NodeId a = id; m.doomed && a != s_.pendingDelete_; a = s_.sketch_.node(a).parent)
      if (a == kNoNode || s_.sketch_.node(a).parent == kNoNode) m.doomed = false;
    try {
      const Vec3 s = cur.project(s_.anchor(id));
      if (s.allFinite()) m.depth = s.z();
    } catch (const std::exception&) {
    }
    if (node.isScreenNode() && sameCamera[node.camera]) {
      m.screen = node.screen;
      m.inCurrentView = true;
      m.visible = true;
    } else {
      m.inCurrentView = false;
      try {
        Vec3 s = cur.project(s_.anchor(id));
        m.screen = s.head<2>();
        m.visible = s.allFinite() && s.z() >= 0.0 && s.z() <= 1.0;
      } catch (const std::exception&) {
        m.visible = false;
      }
    }
    markers.push_back(m);
  }
  return markers;
}

NodeId Scene::nodeAt(const Vec2& screen) const {
  // Of the markers under the click (within the pick radius), the nearest to the eye: the node the
  // person sees in front, not one hidden behind it; ties in depth go to the nearer marker.
  NodeId best = kNoNode;
  double bestDepth = std::numeric_limits<double>::infinity(), bestD = s_.options_.pickRadiusPx;
  for (const NodeMarker& m : nodeMarkers()) {
    if (!m.visible) continue;
    const double d = (m.screen - screen).norm();
    if (d > s_.options_.pickRadiusPx) continue;
    const double depth = std::isfinite(m.depth) ? m.depth : 2.0;
    if (depth < bestDepth || (depth == bestDepth && d < bestD)) {
      bestDepth = depth;
      bestD = d;
      best = m.id;
    }
  }
  return best;
}

std::size_t Scene::markersAt(const Vec2& screen) const {
  std::size_t n = 0;
  for (const NodeMarker& m : nodeMarkers()) n += m.visible && (m.screen - screen).norm() <= s_.options_.pickRadiusPx;
  return n;
}

NodeId Scene::nearestMarker(const Vec2& screen) const {
  NodeId best = kNoNode;
  double bestD = std::numeric_limits<double>::infinity();
  for (const NodeMarker& m : nodeMarkers()) {
    if (!m.visible || !m.screen.allFinite()) continue;
    double d = (m.screen - screen).norm();
    if (d < bestD) {
      bestD = d;
      best = m.id;
    }
  }
  return best;
}

SamplingRegion Scene::samplingRegion() const {
  SamplingRegion r;
  if (s_.tools_.selected() == kNoNode || !s_.sketch_.contains(s_.tools_.selected())) return r;
  try {
    const sketch::Node& node = s_.sketch_.node(s_.tools_.selected());
    r.geometry = s_.sketch_.geometry(s_.tools_.selected());
    r.sliceHalfThickness = node.params.sliceHalfThickness;
    NodeFitView f = s_.recon_->nodeFit(s_.tools_.selected());
    r.lineEpsilon = f.finalLineEpsilon > 0 ? f.finalLineEpsilon : node.params.lineEpsilon;
    r.valid = true;
  } catch (const std::exception&) {
    r.valid = false;
  }
  return r;
}

std::vector<Line3> Scene::sceneLines() const {
  std::vector<Line3> lines;
  if (s_.view_.display().showCircles) {
    for (NodeId id : s_.sketch_.ids()) {
      NodeFitView f = s_.recon_->nodeFit(id);
      if (f.status != NodeStatus::Fitted) continue;
      addRing(lines, f.circle.centre, f.circle.normal, f.circle.radius, s_.options_.circleSegments,
              id == s_.tools_.selected() ? kSelectedCircleColor : kCircleColor);
    }
  }
  SamplingRegion r = samplingRegion();
  if (!s_.view_.display().showSamplingRegion || !r.valid) return lines;
  const sketch::NodeGeometry& g = r.geometry;
  Vec3 n = g.planeNormal.normalized();
  Vec3 centre = s_.anchor(s_.tools_.selected());
  // The slab: two squares at ±ε around the node's region, joined at the corners.
  Vec3 u = g.hasLine ? g.lineDir.normalized() : geom::anyPerpendicular(n);
  Vec3 v = n.cross(u).normalized();
  const geom::BBox& box = s_.bounds_;
  double half = std::max(1.5 * r.lineEpsilon, 0.05 * box.diagonal());
  Vec3 corners[4] = {centre + half * (u + v), centre + half * (-u + v), centre + half * (-u - v),
                     centre + half * (u - v)};
  for (int side = -1; side <= 1; side += 2) {
    Vec3 off = side * r.sliceHalfThickness * n;
    for (int i = 0; i < 4; ++i) lines.push_back(Line3{corners[i] + off, corners[(i + 1) % 4] + off, kSlabColor});
  }
  for (int i = 0; i < 4; ++i)
    lines.push_back(Line3{corners[i] - r.sliceHalfThickness * n, corners[i] + r.sliceHalfThickness * n, kSlabColor});
  // The test region: the cylinder of radius lineEpsilon around L within the cloud's box, or the
  // disc around a point node's point.
  if (g.hasLine) {
    Vec3 d = g.lineDir.normalized();
    double t0, t1;
    if (clipLineToBox(g.linePoint, d, box, r.lineEpsilon, &t0, &t1)) {
      Vec3 a = g.linePoint + t0 * d, b = g.linePoint + t1 * d;
      addRing(lines, a, d, r.lineEpsilon, s_.options_.circleSegments, kCylinderColor);
      addRing(lines, b, d, r.lineEpsilon, s_.options_.circleSegments, kCylinderColor);
      Vec3 p = geom::anyPerpendicular(d), q = d.cross(p);
      for (int i = 0; i < 8; ++i) {
        double ang = 2.0 * M_PI * i / 8;
        Vec3 off = r.lineEpsilon * (std::cos(ang) * p + std::sin(ang) * q);
        lines.push_back(Line3{a + off, b + off, kCylinderColor});
      }
    }
  } else {
    addRing(lines, g.planePoint, n, r.lineEpsilon, s_.options_.circleSegments, kCylinderColor);
  }
  return lines;
}

std::vector<std::uint32_t> Scene::highlightedSlicePoints() const {
  if (!s_.view_.display().showSamplingRegion || s_.tools_.selected() == kNoNode) return {};
  return s_.recon_->slicePoints(s_.tools_.selected());
}

std::vector<std::uint32_t> Scene::highlightedInliers() const {
  if (!s_.view_.display().showSamplingRegion || s_.tools_.selected() == kNoNode) return {};
  return s_.recon_->inlierPoints(s_.tools_.selected());
}

const geom::TriMesh& Scene::mesh() const { return s_.recon_ ? s_.recon_->mesh() : emptyMesh_; }

std::size_t Scene::fittedCount() const {
  std::size_t n = 0;
  for (NodeId id : s_.sketch_.ids()) n += s_.recon_->nodeFit(id).status == NodeStatus::Fitted;
  return n;
}

std::size_t Scene::skippedCount() const {
  std::size_t n = 0;
  for (NodeId id : s_.sketch_.ids()) n += s_.recon_->nodeFit(id).status == NodeStatus::Skipped;
  return n;
}

}  // namespace treesketch::viewer
