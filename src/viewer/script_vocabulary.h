// The action script's vocabularies (see action_script.h), each in one table that both the
// parser (which names exist) and the runner (what a name does) read, so that the two cannot
// disagree. Private to src/viewer/.
#pragma once

#include <cstddef>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "treesketch/util/error.h"
#include "treesketch/viewer/color_legend.h"
#include "treesketch/viewer/viewer_state.h"

namespace treesketch::viewer::script {

/// {"button": NAME} and the bare "NAME" verbs.
struct Button {
  const char* name;
  void (*press)(ViewerState&);
};
inline const Button kButtons[] = {
    {"undo", [](ViewerState& s) { s.undo(); }},
    {"redo", [](ViewerState& s) { s.redo(); }},
    {"fit", [](ViewerState& s) { s.view().fitView(); }},
    {"clear", [](ViewerState& s) { s.clearSketch(); }},
    {"autoSketch", [](ViewerState& s) { s.requestAutoSketchUniform(); }},
    {"autoSkeleton", [](ViewerState& s) { s.requestAutoSketchSkeleton(); }},
    {"autoSkeletonWood", [](ViewerState& s) { s.requestAutoSketchSkeletonWood(); }},
    {"classify", [](ViewerState& s) { s.startClassifyJob(); }},
    {"delete", [](ViewerState& s) { s.deleteSelected(false); }},
    {"deleteSubtree", [](ViewerState& s) { s.deleteSelected(true); }},
    {"refit", [](ViewerState& s) { s.refitSelected(); }},
    {"refitAll", [](ViewerState& s) { s.refitAll(); }},
    {"clearNotWood", [](ViewerState& s) { s.clearNotWood(); }},
    {"cancel", [](ViewerState& s) { s.jobs().cancel(); }},
};

/// {"tool": NAME}.
struct ToolName {
  const char* name;
  ViewerState::Tool tool;
};
inline const ToolName kTools[] = {
    {"select", ViewerState::Tool::Select},     {"sketch", ViewerState::Tool::Select},
    {"add", ViewerState::Tool::AddNodes},      {"stroke", ViewerState::Tool::Stroke},
    {"lasso", ViewerState::Tool::Lasso},       {"region", ViewerState::Tool::Region},
    {"reattach", ViewerState::Tool::Reattach}, {"lassoWood", ViewerState::Tool::LassoWood},
};

/// {"slider": NAME, "value": number}.
struct Slider {
  const char* name;
  void (*set)(ViewerState&, double);
};
inline const Slider kSliders[] = {
    {"sliceHalfThickness", [](ViewerState& s, double v) { s.setSliceHalfThickness(v); }},
    {"lineEpsilon", [](ViewerState& s, double v) { s.setLineEpsilon(v); }},
    {"pointSize",
     [](ViewerState& s, double v) {
       if (!(v > 0)) throw OptionsError("pointSize must be positive");
       s.view().display().pointSize = static_cast<float>(v);
     }},
};

inline bool parseBool(const std::string& s) {
  if (s == "true" || s == "on" || s == "1") return true;
  if (s == "false" || s == "off" || s == "0") return false;
  throw OptionsError("expected true or false, got '" + s + "'");
}

/// {"option": NAME, "value": ...}; the value arrives as text ("true"/"false" for booleans).
struct Option {
  const char* name;
  void (*apply)(ViewerState&, const std::string&);
};
inline const Option kOptions[] = {
    {"colorMode", [](ViewerState& s, const std::string& v) { s.view().display().colorMode = parseColorMode(v); }},
    {"meshStyle", [](ViewerState& s, const std::string& v) { s.view().display().meshStyle = parseMeshStyle(v); }},
    {"projection",
     [](ViewerState& s, const std::string& v) {
       if (v != "ortho" && v != "orthographic" && v != "perspective")
         throw OptionsError("projection must be 'ortho' or 'perspective', got '" + v + "'");
       s.view().setOrthographic(v != "perspective");
     }},
    {"showCloud", [](ViewerState& s, const std::string& v) { s.view().display().showCloud = parseBool(v); }},
    {"showNodes", [](ViewerState& s, const std::string& v) { s.view().display().showNodes = parseBool(v); }},
    {"showCircles", [](ViewerState& s, const std::string& v) { s.view().display().showCircles = parseBool(v); }},
    {"showRegion", [](ViewerState& s, const std::string& v) { s.view().display().showSamplingRegion = parseBool(v); }},
    {"labels", [](ViewerState& s, const std::string& v) { s.view().display().labels = parseLabelMode(v); }},
    {"upAxis", [](ViewerState& s, const std::string& v) { s.setUpDirection(parseUpDirection(v)); }},
    {"holdJobs", [](ViewerState& s, const std::string& v) { s.jobs().hold(parseBool(v)); }},
};

/// {"expect": {NAME: n, ...}}: what each name reads from the state; `atLeast` keys pass with any
/// value >= n (the mesh's triangle count depends on the fits' details), the others need n exactly.
struct Expectation {
  const char* name;
  double (*read)(const ViewerState&);
  bool atLeast;
};
inline const Expectation kExpectations[] = {
    {"nodes", [](const ViewerState& s) { return double(s.sketch().size()); }, false},
    {"fitted", [](const ViewerState& s) { return double(s.scene().fittedCount()); }, false},
    {"skipped", [](const ViewerState& s) { return double(s.scene().skippedCount()); }, false},
    {"selected", [](const ViewerState& s) { return double(s.tools().selected()); }, false},
    {"active", [](const ViewerState& s) { return double(s.tools().active()); }, false},
    {"errors", [](const ViewerState& s) { return double(s.status().errorCount()); }, false},
    {"meshTriangles", [](const ViewerState& s) { return double(s.scene().mesh().triangles.size()); }, true},
    {"kept", [](const ViewerState& s) { return double(s.sketch().keptCircleCount()); }, false},
    {"notWood", [](const ViewerState& s) { return double(s.sketch().notWood().size()); }, false},
    {"recoveryOffered", [](const ViewerState& s) { return double(s.document().recoveryPending()); }, false},
    {"confirmPending", [](const ViewerState& s) { return double(s.confirmationPending()); }, false},
    {"handEdits", [](const ViewerState& s) { return double(s.hasHandEdits()); }, false},
    {"labelsShown", [](const ViewerState& s) { return double(s.scene().labelsShown()); }, false},
    {"statusShown", [](const ViewerState& s) { return double(s.status().statusLine().has_value()); }, false},
    {"lyingDown", [](const ViewerState& s) { return double(s.upWarningShown()); }, false},
    {"legend", [](const ViewerState& s) { return double(colorLegend(s).kind != Legend::Kind::None); }, false},
    {"busy", [](const ViewerState& s) { return double(s.jobs().busy()); }, false},
    {"points", [](const ViewerState& s) { return double(s.cloud().size()); }, false},
    {"woodLassos", [](const ViewerState& s) { return double(s.sketch().woodLassoCount()); }, false},
    {"classified", [](const ViewerState& s) { return double(s.woodClasses() != nullptr); }, false},
    {"woodPoints", [](const ViewerState& s) { return double(s.woodPointCount()); }, true},
};

/// The model file an export verb writes: "export" the mesh, "export-cylinders", "export-qsm",
/// "export-metrics", "export-report" the others; nothing for any other word.
inline std::optional<ViewerState::ModelFile> exportedFile(const std::string& verb) {
  using F = ViewerState::ModelFile;
  static const std::pair<const char*, F> kVerbs[] = {{"export", F::Mesh},
                                                     {"export-cylinders", F::Cylinders},
                                                     {"export-qsm", F::Qsm},
                                                     {"export-metrics", F::Metrics},
                                                     {"export-report", F::Report}};
  for (const auto& [name, file] : kVerbs)
    if (verb == name) return file;
  return std::nullopt;
}

/// The verb of a JSON action that takes a path ("save", "load", an export verb, "screenshot"), or "".
inline std::string pathVerb(const nlohmann::json& j) {
  for (const char* verb :
       {"save", "load", "export", "export-cylinders", "export-qsm", "export-metrics", "export-report", "screenshot"})
    if (j.contains(verb)) return verb;
  return {};
}

/// Window verbs and the values each takes (checked here so a typo fails at parse time; what they do
/// is apps/viewer's, through ScriptHooks::window).
struct WindowVerb {
  const char* name;
  std::vector<std::string> values;  ///< allowed string values; empty: not a string verb
};
inline const WindowVerb kWindowVerbs[] = {
    {"menu",
     {"open-cloud", "open-sketch", "save", "save-as", "export", "export-cylinders", "export-qsm", "export-metrics",
      "export-report", "quit", "help", "about", "reset-camera", "pick-mode", "recent"}},
    {"dialog", {"ok", "cancel", "type"}},
    {"prompt", {"save", "discard", "cancel"}},
    {"pick", {}},
    {"hover", {}},
    {"panel", {"Open sketch...", "Save sketch", "Save as...", "Export mesh..."}},
    {"closeWindow", {}},
    {"showMenu", {"File", "View", "Tools", "Help", "none"}},
    {"expectWindow", {}},
};
inline const char* const kWindowExpectations[] = {
    "dialogOpen", "dialogEntries", "promptOpen",    "picks",       "distanceMin", "distanceMax", "recent",
    "quitting",   "helpOpen",      "legendClasses", "dialogError", "tooltip",     "sceneRedrawn"};

/// The entry of `table` called `name`, or nullptr.
template <class Entry, std::size_t N>
const Entry* entryNamed(const Entry (&table)[N], const std::string& name) {
  for (const Entry& e : table)
    if (name == e.name) return &e;
  return nullptr;
}

}  // namespace treesketch::viewer::script
