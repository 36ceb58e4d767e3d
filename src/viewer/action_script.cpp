#include "treesketch/viewer/action_script.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <thread>

#include "treesketch/util/error.h"
#include "treesketch/viewer/color_legend.h"

namespace treesketch::viewer {

using nlohmann::json;
using Kind = ScriptAction::Kind;

namespace {

// The script's vocabularies, each in one table that both the parser (which names exist) and the
// runner (what a name does) read, so that the two cannot disagree.

/// {"button": NAME} and the bare "NAME" verbs.
struct Button {
  const char* name;
  void (*press)(ViewerState&);
};
const Button kButtons[] = {
    {"undo", [](ViewerState& s) { s.undo(); }},
    {"redo", [](ViewerState& s) { s.redo(); }},
    {"fit", [](ViewerState& s) { s.fitView(); }},
    {"clear", [](ViewerState& s) { s.clearSketch(); }},
    {"autoSketch", [](ViewerState& s) { s.requestAutoSketchUniform(); }},
    {"autoSkeleton", [](ViewerState& s) { s.requestAutoSketchSkeleton(); }},
    {"delete", [](ViewerState& s) { s.deleteSelected(false); }},
    {"deleteSubtree", [](ViewerState& s) { s.deleteSelected(true); }},
    {"refit", [](ViewerState& s) { s.refitSelected(); }},
    {"refitAll", [](ViewerState& s) { s.refitAll(); }},
    {"clearNotWood", [](ViewerState& s) { s.clearNotWood(); }},
    {"cancel", [](ViewerState& s) { s.cancelJob(); }},
};

/// {"tool": NAME}.
struct ToolName {
  const char* name;
  ViewerState::Tool tool;
};
const ToolName kTools[] = {
    {"sketch", ViewerState::Tool::Sketch},     {"stroke", ViewerState::Tool::Stroke},
    {"lasso", ViewerState::Tool::Lasso},       {"region", ViewerState::Tool::Region},
    {"reattach", ViewerState::Tool::Reattach},
};

/// {"slider": NAME, "value": number}.
struct Slider {
  const char* name;
  void (*set)(ViewerState&, double);
};
const Slider kSliders[] = {
    {"sliceHalfThickness", [](ViewerState& s, double v) { s.setSliceHalfThickness(v); }},
    {"lineEpsilon", [](ViewerState& s, double v) { s.setLineEpsilon(v); }},
    {"pointSize",
     [](ViewerState& s, double v) {
       if (!(v > 0)) throw OptionsError("pointSize must be positive");
       s.display().pointSize = static_cast<float>(v);
     }},
};

bool parseBool(const std::string& s) {
  if (s == "true" || s == "on" || s == "1") return true;
  if (s == "false" || s == "off" || s == "0") return false;
  throw OptionsError("expected true or false, got '" + s + "'");
}

/// {"option": NAME, "value": ...}; the value arrives as text ("true"/"false" for booleans).
struct Option {
  const char* name;
  void (*apply)(ViewerState&, const std::string&);
};
const Option kOptions[] = {
    {"colorMode", [](ViewerState& s, const std::string& v) { s.display().colorMode = parseColorMode(v); }},
    {"meshStyle", [](ViewerState& s, const std::string& v) { s.display().meshStyle = parseMeshStyle(v); }},
    {"projection",
     [](ViewerState& s, const std::string& v) {
       if (v != "ortho" && v != "orthographic" && v != "perspective")
         throw OptionsError("projection must be 'ortho' or 'perspective', got '" + v + "'");
       s.setOrthographic(v != "perspective");
     }},
    {"showCloud", [](ViewerState& s, const std::string& v) { s.display().showCloud = parseBool(v); }},
    {"showNodes", [](ViewerState& s, const std::string& v) { s.display().showNodes = parseBool(v); }},
    {"showCircles", [](ViewerState& s, const std::string& v) { s.display().showCircles = parseBool(v); }},
    {"showRegion", [](ViewerState& s, const std::string& v) { s.display().showSamplingRegion = parseBool(v); }},
    {"labels", [](ViewerState& s, const std::string& v) { s.display().labels = parseLabelMode(v); }},
    {"upAxis", [](ViewerState& s, const std::string& v) { s.setUpDirection(parseUpDirection(v)); }},
    {"holdJobs", [](ViewerState& s, const std::string& v) { s.holdJobs(parseBool(v)); }},
};

/// {"expect": {NAME: n, ...}}: what each name reads from the state; `atLeast` keys pass with any
/// value >= n (the mesh's triangle count depends on the fits' details), the others need n exactly.
struct Expectation {
  const char* name;
  double (*read)(const ViewerState&);
  bool atLeast;
};
const Expectation kExpectations[] = {
    {"nodes", [](const ViewerState& s) { return double(s.sketch().size()); }, false},
    {"fitted", [](const ViewerState& s) { return double(s.fittedCount()); }, false},
    {"skipped", [](const ViewerState& s) { return double(s.skippedCount()); }, false},
    {"selected", [](const ViewerState& s) { return double(s.selected()); }, false},
    {"active", [](const ViewerState& s) { return double(s.active()); }, false},
    {"errors", [](const ViewerState& s) { return double(s.errorCount()); }, false},
    {"meshTriangles", [](const ViewerState& s) { return double(s.mesh().triangles.size()); }, true},
    {"kept", [](const ViewerState& s) { return double(s.sketch().keptCircleCount()); }, false},
    {"notWood", [](const ViewerState& s) { return double(s.sketch().notWood().size()); }, false},
    {"recoveryOffered", [](const ViewerState& s) { return double(s.recoveryPending()); }, false},
    {"confirmPending", [](const ViewerState& s) { return double(s.confirmationPending()); }, false},
    {"handEdits", [](const ViewerState& s) { return double(s.hasHandEdits()); }, false},
    {"labelsShown", [](const ViewerState& s) { return double(s.labelsShown()); }, false},
    {"statusShown", [](const ViewerState& s) { return double(s.statusLine().has_value()); }, false},
    {"lyingDown", [](const ViewerState& s) { return double(s.upWarningShown()); }, false},
    {"legend", [](const ViewerState& s) { return double(colorLegend(s).kind != Legend::Kind::None); }, false},
    {"busy", [](const ViewerState& s) { return double(s.busy()); }, false},
    {"points", [](const ViewerState& s) { return double(s.cloud().size()); }, false},
};

/// The model file an export verb writes: "export" the mesh, "export-cylinders", "export-qsm",
/// "export-metrics", "export-report" the others; nothing for any other word.
std::optional<ViewerState::ModelFile> exportedFile(const std::string& verb) {
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
std::string pathVerb(const nlohmann::json& j) {
  for (const char* verb : {"save", "load", "export", "export-cylinders", "export-qsm", "export-metrics",
                           "export-report", "screenshot"})
    if (j.contains(verb)) return verb;
  return {};
}

/// Window verbs and the values each takes (checked here so a typo fails at parse time; what they do
/// is apps/viewer's, through ScriptHooks::window).
struct WindowVerb {
  const char* name;
  std::vector<std::string> values;  ///< allowed string values; empty: not a string verb
};
const WindowVerb kWindowVerbs[] = {
    {"menu",
     {"open-cloud", "open-sketch", "save", "save-as", "export", "export-cylinders", "export-qsm", "export-metrics",
      "export-report", "quit", "help", "about", "reset-camera", "pick-mode",
      "recent"}},
    {"dialog", {"ok", "cancel", "type"}},
    {"prompt", {"save", "discard", "cancel"}},
    {"pick", {}},
    {"hover", {}},
    {"closeWindow", {}},
    {"showMenu", {"File", "View", "Tools", "Help", "none"}},
    {"expectWindow", {}},
};
const char* const kWindowExpectations[] = {"dialogOpen",  "dialogEntries", "promptOpen",  "picks",
                                           "distanceMin", "distanceMax",   "recent",      "quitting",
                                           "helpOpen",    "legendClasses", "dialogError", "tooltip"};

/// The entry of `table` called `name`, or nullptr.
template <class Entry, std::size_t N>
const Entry* entryNamed(const Entry (&table)[N], const std::string& name) {
  for (const Entry& e : table)
    if (name == e.name) return &e;
  return nullptr;
}

class Parser {
 public:
  explicit Parser(std::string source) : source_(std::move(source)) {}

  [[noreturn]] void fail(std::size_t index, const std::string& what) const {
    throw InputError(source_ + ": action " + std::to_string(index) + ": " + what);
  }

  double number(const json& j, std::size_t index, const std::string& what) const {
    if (!j.is_number()) fail(index, what + ": expected a number, got " + j.dump());
    double v = j.get<double>();
    if (!std::isfinite(v)) fail(index, what + ": not a finite number");
    return v;
  }

  geom::Vec2 point(const json& j, std::size_t index, const std::string& what) const {
    if (!j.is_array() || j.size() != 2) fail(index, what + ": expected [x, y], got " + j.dump());
    return geom::Vec2(number(j[0], index, what + " x"), number(j[1], index, what + " y"));
  }

  std::string string(const json& j, std::size_t index, const std::string& what) const {
    if (!j.is_string()) fail(index, what + ": expected a string, got " + j.dump());
    return j.get<std::string>();
  }

  MouseButton button(const std::string& s, std::size_t index) const {
    if (s == "left") return MouseButton::Left;
    if (s == "right") return MouseButton::Right;
    if (s == "middle") return MouseButton::Middle;
    fail(index, "button must be 'left', 'right' or 'middle', got '" + s + "'");
  }

  int mods(const std::string& s, std::size_t index) const {
    int m = kModNone;
    std::stringstream ss(s);
    std::string part;
    while (std::getline(ss, part, '+')) {
      if (part == "shift")
        m |= kModShift;
      else if (part == "ctrl")
        m |= kModCtrl;
      else if (part == "alt")
        m |= kModAlt;
      else if (!part.empty())
        fail(index, "modifier must be shift, ctrl or alt, got '" + part + "'");
    }
    return m;
  }

  ScriptAction fromString(const std::string& s, std::size_t index) const {
    ScriptAction a;
    a.index = index;
    std::string verb = s, arg;
    if (auto sp = s.find(' '); sp != std::string::npos) {
      verb = s.substr(0, sp);
      arg = s.substr(s.find_first_not_of(' ', sp) == std::string::npos ? s.size() : s.find_first_not_of(' ', sp));
    }
    const bool exportVerb = exportedFile(verb).has_value();
    if (verb == "save" || verb == "load" || exportVerb || verb == "screenshot") {
      a.kind = verb == "save"   ? Kind::Save
               : verb == "load" ? Kind::Load
               : exportVerb     ? Kind::Export
                                : Kind::Screenshot;
      a.name = verb;
      a.path = arg;
      if (arg.empty() && (a.kind == Kind::Export || a.kind == Kind::Screenshot)) fail(index, verb + " needs a PATH");
    } else if (verb == "key") {
      if (arg.empty()) fail(index, "key needs a key name");
      a.kind = Kind::Key;
      a.name = arg;
    } else if (verb == "view") {
      a.kind = Kind::View;
      a.name = arg;
      checkView(a.name, index);
    } else if (entryNamed(kButtons, verb)) {
      a.kind = Kind::Button;
      a.name = verb;
    } else if (verb == "wait") {
      a.kind = Kind::Wait;
      a.steps = arg.empty() ? 1 : std::atoi(arg.c_str());
    } else if (verb == "closeWindow") {
      a.kind = Kind::Window;
      a.name = verb;
    } else if (verb == "menu" || verb == "prompt" || verb == "dialog") {
      a.kind = Kind::Window;
      a.name = verb;
      a.text = arg;
      checkWindowValue(a, index);
    } else {
      fail(index, "unknown action '" + s + "'");
    }
    return a;
  }

  void checkView(const std::string& v, std::size_t index) const {
    if (v != "front" && v != "side" && v != "top" && v != "fit")
      fail(index, "view must be front, side, top or fit, got '" + v + "'");
  }

  void checkWindowValue(const ScriptAction& a, std::size_t index) const {
    for (const WindowVerb& v : kWindowVerbs) {
      if (a.name != v.name || v.values.empty()) continue;
      if (std::find(v.values.begin(), v.values.end(), a.text) != v.values.end()) return;
      std::string list;
      for (const std::string& s : v.values) list += (list.empty() ? "" : ", ") + s;
      fail(index, a.name + " must be one of " + list + ", got '" + a.text + "'");
    }
  }

  /// {"menu": ...}, {"dialog": ...}, {"prompt": ...}, {"pick": [x, y]}, {"closeWindow": ...},
  /// {"expectWindow": {...}}; false when `j` holds none of them.
  bool windowVerb(const json& j, std::size_t index, ScriptAction& a) const {
    for (const WindowVerb& v : kWindowVerbs) {
      if (!j.contains(v.name)) continue;
      a.kind = Kind::Window;
      a.name = v.name;
      const json& arg = j[v.name];
      if (a.name == "pick" || a.name == "hover") {
        a.from = a.to = point(arg, index, a.name);
      } else if (a.name == "expectWindow") {
        if (!arg.is_object()) fail(index, "expectWindow: expected an object");
        for (const auto& [k, val] : arg.items()) {
          if (std::find_if(std::begin(kWindowExpectations), std::end(kWindowExpectations),
                           [&](const char* n) { return k == n; }) == std::end(kWindowExpectations))
            fail(index, "expectWindow: unknown key '" + k + "'");
          a.expect.emplace_back(k, number(val, index, "expectWindow " + k));
        }
      } else if (!v.values.empty()) {
        a.text = string(arg, index, a.name);
        checkWindowValue(a, index);
      }
      if (j.contains("path")) a.path = string(j["path"], index, "path");
      if (j.contains("value")) a.value = number(j["value"], index, "value");
      if (a.name == "menu" && a.text == "recent" && !j.contains("value"))
        fail(index, "menu recent needs a \"value\" (0 = the newest entry)");
      return true;
    }
    return false;
  }

  ScriptAction fromObject(const json& j, std::size_t index) const {
    ScriptAction a = verbFromObject(j, index);
    if (j.contains("expectError")) {
      if (!j["expectError"].is_boolean()) fail(index, "expectError: expected true or false");
      a.expectError = j["expectError"].get<bool>();
    }
    return a;
  }

  ScriptAction verbFromObject(const json& j, std::size_t index) const {
    ScriptAction a;
    a.index = index;
    if (j.contains("button") && !j["button"].is_string()) fail(index, "button: expected a string");
    if (j.contains("mods")) a.mods = mods(string(j["mods"], index, "mods"), index);
    if (j.contains("click")) {
      a.kind = Kind::Click;
      a.from = a.to = point(j["click"], index, "click");
      if (j.contains("button")) a.button = button(j["button"].get<std::string>(), index);
    } else if (j.contains("drag")) {
      a.kind = Kind::Drag;
      const json& d = j["drag"];
      if (!d.is_array() || d.size() != 2) fail(index, "drag: expected [[x0, y0], [x1, y1]]");
      a.from = point(d[0], index, "drag start");
      a.to = point(d[1], index, "drag end");
      if (j.contains("button")) a.button = button(j["button"].get<std::string>(), index);
      if (j.contains("steps")) a.steps = static_cast<int>(number(j["steps"], index, "steps"));
      if (a.steps < 1) fail(index, "steps must be at least 1");
    } else if (j.contains("scroll")) {
      a.kind = Kind::Scroll;
      a.value = number(j["scroll"], index, "scroll");
    } else if (j.contains("key")) {
      a.kind = Kind::Key;
      a.name = string(j["key"], index, "key");
    } else if (j.contains("slider")) {
      a.kind = Kind::Slider;
      a.name = string(j["slider"], index, "slider");
      if (!entryNamed(kSliders, a.name))
        fail(index, "slider must be sliceHalfThickness, lineEpsilon or pointSize, got '" + a.name + "'");
      if (!j.contains("value")) fail(index, "slider needs a \"value\"");
      a.value = number(j["value"], index, "value");
    } else if (j.contains("option")) {
      a.kind = Kind::Option;
      a.name = string(j["option"], index, "option");
      if (!j.contains("value")) fail(index, "option needs a \"value\"");
      const json& v = j["value"];
      if (v.is_boolean())
        a.text = v.get<bool>() ? "true" : "false";
      else
        a.text = string(v, index, "value");
      if (!entryNamed(kOptions, a.name)) fail(index, "unknown option '" + a.name + "'");
    } else if (j.contains("view")) {
      a.kind = Kind::View;
      a.name = string(j["view"], index, "view");
      checkView(a.name, index);
    } else if (j.contains("select")) {
      a.kind = Kind::Select;
      a.value = number(j["select"], index, "select");
    } else if (j.contains("button")) {
      ScriptAction b = fromString(j["button"].get<std::string>(), index);
      if (b.kind != Kind::Button) fail(index, "unknown button '" + j["button"].get<std::string>() + "'");
      return b;
    } else if (const std::string verb = pathVerb(j); !verb.empty()) {
      const json& p = j[verb];
      std::string path = p.is_null() ? std::string() : string(p, index, verb);
      return fromString(path.empty() ? verb : verb + " " + path, index);
    } else if (j.contains("stroke") || j.contains("lasso") || j.contains("region")) {
      a.kind = Kind::Path;
      a.name = j.contains("stroke") ? "stroke" : j.contains("lasso") ? "lasso" : "region";
      const json& pts = j[a.name];
      const std::size_t need = a.name == "stroke" ? 2 : 3;
      if (!pts.is_array() || pts.size() < need)
        fail(index, a.name + ": expected a list of at least " + std::to_string(need) + " [x, y] points");
      for (std::size_t k = 0; k < pts.size(); ++k) a.points.push_back(point(pts[k], index, a.name + " point"));
    } else if (j.contains("deleteSubtree") || j.contains("automaticBelow")) {
      a.kind = Kind::NodeOp;
      a.name = j.contains("deleteSubtree") ? "deleteSubtree" : "automaticBelow";
      a.value = number(j[a.name], index, a.name);
    } else if (j.contains("reattach")) {
      a.kind = Kind::NodeOp;
      a.name = "reattach";
      const json& r = j["reattach"];
      if (!r.is_array() || r.size() != 2) fail(index, "reattach: expected [nodeId, newParentId]");
      a.value = number(r[0], index, "reattach node");
      a.value2 = number(r[1], index, "reattach parent");
    } else if (j.contains("tool")) {
      a.kind = Kind::Tool;
      a.name = string(j["tool"], index, "tool");
      if (!entryNamed(kTools, a.name))
        fail(index, "tool must be sketch, stroke, lasso, region or reattach, got '" + a.name + "'");
    } else if (j.contains("start")) {
      a.kind = Kind::Start;
      a.name = string(j["start"], index, "start");
      if (a.name != "autoSkeleton")
        fail(index, "start: only 'autoSkeleton' runs in the background, got '" + a.name + "'");
    } else if (j.contains("confirm")) {
      a.kind = Kind::Confirm;
      if (!j["confirm"].is_boolean()) fail(index, "confirm: expected true or false");
      a.value = j["confirm"].get<bool>() ? 1.0 : 0.0;
    } else if (j.contains("recovery")) {
      a.kind = Kind::Recovery;
      a.name = string(j["recovery"], index, "recovery");
      if (a.name != "restore" && a.name != "discard" && a.name != "keep")
        fail(index, "recovery must be restore, discard or keep, got '" + a.name + "'");
    } else if (j.contains("sleep")) {
      a.kind = Kind::Sleep;
      a.value = number(j["sleep"], index, "sleep");
      if (a.value < 0) fail(index, "sleep: expected seconds >= 0");
    } else if (j.contains("wait")) {
      a.kind = Kind::Wait;
      if (j["wait"].is_string()) {
        a.name = string(j["wait"], index, "wait");
        if (a.name != "job") fail(index, "wait: expected a number of frames or \"job\"");
        a.steps = 0;
      } else {
        a.steps = static_cast<int>(number(j["wait"], index, "wait"));
      }
    } else if (windowVerb(j, index, a)) {
      // done
    } else if (j.contains("expect")) {
      a.kind = Kind::Expect;
      const json& e = j["expect"];
      if (!e.is_object()) fail(index, "expect: expected an object");
      for (const auto& [k, v] : e.items()) {
        if (!entryNamed(kExpectations, k)) fail(index, "expect: unknown key '" + k + "'");
        a.expect.emplace_back(k, number(v, index, "expect " + k));
      }
    } else {
      fail(index, "unknown action " + j.dump());
    }
    return a;
  }

  ActionScript parse(std::istream& in) const {
    json doc;
    try {
      doc = json::parse(in);
    } catch (const json::parse_error& e) {
      throw InputError(atOffset(source_, e.byte, std::string("malformed JSON: ") + e.what()));
    }
    ActionScript script;
    const json* list = &doc;
    if (doc.is_object()) {
      if (doc.contains("window")) {
        const json& w = doc["window"];
        if (!w.is_array() || w.size() != 2 || !w[0].is_number_integer() || !w[1].is_number_integer() ||
            w[0].get<int>() <= 0 || w[1].get<int>() <= 0)
          throw InputError(source_ + ": \"window\": expected [width, height] in positive pixels");
        script.windowWidth = w[0].get<int>();
        script.windowHeight = w[1].get<int>();
      }
      if (!doc.contains("actions")) throw InputError(source_ + ": expected an \"actions\" list");
      list = &doc["actions"];
    }
    if (!list->is_array()) throw InputError(source_ + ": expected a list of actions");
    for (std::size_t i = 0; i < list->size(); ++i) {
      const json& a = (*list)[i];
      if (a.is_string())
        script.actions.push_back(fromString(a.get<std::string>(), i));
      else if (a.is_object())
        script.actions.push_back(fromObject(a, i));
      else
        fail(i, "expected an object or a string, got " + a.dump());
    }
    return script;
  }

 private:
  std::string source_;
};

const char* buttonName(MouseButton b) {
  return b == MouseButton::Left ? "left" : b == MouseButton::Right ? "right" : "middle";
}

void applyOption(ViewerState& state, const std::string& name, const std::string& value) {
  const Option* option = entryNamed(kOptions, name);
  if (!option) throw OptionsError("unknown option '" + name + "'");
  option->apply(state, value);
}

/// Checks one expectation; returns "" or what differs.
std::string checkExpect(const ViewerState& state, const std::string& key, double want) {
  const Expectation* e = entryNamed(kExpectations, key);
  const double got = e ? e->read(state) : 0.0;
  if (e && e->atLeast) {
    if (got >= want) return {};
    return key + ": expected at least " + std::to_string(static_cast<long long>(want)) + ", got " +
           std::to_string(static_cast<long long>(got));
  }
  if (got == want) return {};
  return key + ": expected " + std::to_string(static_cast<long long>(want)) + ", got " +
         std::to_string(static_cast<long long>(got));
}

}  // namespace

ActionScript parseActionScript(std::istream& in, const std::string& source) { return Parser(source).parse(in); }

ActionScript parseActionScript(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path.string() + ": cannot open the script");
  return parseActionScript(in, path.string());
}

std::string describe(const ScriptAction& a) {
  auto pt = [](const geom::Vec2& p) {
    std::ostringstream s;
    s << "(" << p.x() << ", " << p.y() << ")";
    return s.str();
  };
  switch (a.kind) {
    case Kind::Click:
      return "click " + pt(a.from) + " " + buttonName(a.button);
    case Kind::Drag:
      return "drag " + pt(a.from) + " -> " + pt(a.to) + " " + buttonName(a.button);
    case Kind::Scroll:
      return "scroll " + std::to_string(a.value);
    case Kind::Key:
      return "key " + a.name;
    case Kind::Slider:
      return "slider " + a.name + " = " + std::to_string(a.value);
    case Kind::Option:
      return "option " + a.name + " = " + a.text;
    case Kind::View:
      return "view " + a.name;
    case Kind::Select:
      return "select " + std::to_string(static_cast<int>(a.value));
    case Kind::Button:
      return "button " + a.name;
    case Kind::Save:
      return "save " + a.path.string();
    case Kind::Load:
      return "load " + a.path.string();
    case Kind::Export:
      return a.name + " " + a.path.string();
    case Kind::Screenshot:
      return "screenshot " + a.path.string();
    case Kind::Wait:
      return a.name == "job" ? "wait for the background job" : "wait " + std::to_string(a.steps);
    case Kind::Path:
      return a.name + " (" + std::to_string(a.points.size()) + " points from " + pt(a.points.front()) + ")";
    case Kind::NodeOp:
      return a.name + " " + std::to_string(static_cast<int>(a.value)) +
             (a.name == "reattach" ? " to " + std::to_string(static_cast<int>(a.value2)) : std::string());
    case Kind::Tool:
      return "tool " + a.name;
    case Kind::Sleep:
      return "sleep " + std::to_string(a.value) + " s";
    case Kind::Recovery:
      return "recovery " + a.name;
    case Kind::Confirm:
      return a.value != 0 ? "confirm yes" : "confirm no";
    case Kind::Start:
      return "start " + a.name;
    case Kind::Expect: {
      std::string s = "expect";
      for (const auto& [k, v] : a.expect) s += " " + k + "=" + std::to_string(static_cast<long long>(v));
      return s;
    }
    case Kind::Window: {
      std::string s = a.name;
      if (!a.text.empty()) s += " " + a.text;
      if (a.name == "pick" || a.name == "hover") s += " " + pt(a.from);
      if (!a.path.empty()) s += " " + a.path.string();
      for (const auto& [k, v] : a.expect) {
        std::ostringstream n;
        n << v;
        s += " " + k + "=" + n.str();
      }
      return s;
    }
  }
  return "?";
}

ScriptReport runActionScript(ViewerState& state, const ActionScript& script, const ScriptHooks& hooks) {
  ScriptReport report;
  for (const ScriptAction& a : script.actions) {
    std::string what = describe(a);
    if (hooks.log) hooks.log(a, what);
    std::size_t errorsBefore = state.errorCount();
    const bool busyBefore = state.busy();
    std::string failure;
    try {
      switch (a.kind) {
        case Kind::Click:
          state.clickAt(a.from, a.button, a.mods);
          break;
        case Kind::Drag:
          // Move in steps, drawing a frame after each, as a real drag would.
          state.dragTo(a.from, a.to, a.button, a.mods, a.steps, hooks.frame);
          break;
        case Kind::Scroll:
          state.scroll(a.value);
          break;
        case Kind::Key:
          if (!state.keyPress(a.name, a.mods)) failure = "no action is bound to key '" + a.name + "'";
          break;
        case Kind::Slider:
          if (const Slider* slider = entryNamed(kSliders, a.name)) slider->set(state, a.value);
          break;
        case Kind::Option:
          applyOption(state, a.name, a.text);
          break;
        case Kind::View:
          if (a.name == "fit")
            state.fitView();
          else
            state.presetView(geom::parsePresetView(a.name));
          break;
        case Kind::Select:
          state.selectNode(static_cast<sketch::NodeId>(a.value));
          break;
        case Kind::Button:
          if (const Button* button = entryNamed(kButtons, a.name)) button->press(state);
          break;
        case Kind::Save:
        case Kind::Load: {
          std::filesystem::path p = a.path.empty() ? hooks.sketchPath : a.path;
          if (p.empty()) throw OptionsError("no sketch path: give one (\"save PATH\") or start with --sketch");
          if (a.kind == Kind::Save)
            state.saveSketch(p);
          else
            state.loadSketch(p);
          break;
        }
        case Kind::Export:
          state.exportModel(*exportedFile(a.name), a.path);
          break;
        case Kind::Screenshot:
          if (!hooks.screenshot) throw OptionsError("screenshots need a window");
          if (hooks.frame) hooks.frame();
          hooks.screenshot(a.path);
          state.info("screenshot written to " + a.path.string());
          break;
        case Kind::Wait:
          for (int i = 0; i < a.steps && hooks.frame; ++i) hooks.frame();
          break;
        case Kind::Path:
          if (a.name == "stroke")
            state.strokeLimb(a.points);
          else if (a.name == "lasso")
            state.lassoNotWood(a.points);
          else
            state.automaticInRegion(a.points);
          break;
        case Kind::NodeOp: {
          const auto id = static_cast<sketch::NodeId>(a.value);
          if (a.name == "deleteSubtree")
            state.deleteSubtree(id);
          else if (a.name == "automaticBelow")
            state.automaticBelow(id);
          else
            state.reattachNode(id, static_cast<sketch::NodeId>(a.value2));
          break;
        }
        case Kind::Tool:
          if (const ToolName* t = entryNamed(kTools, a.name)) state.setTool(t->tool);
          break;
        case Kind::Sleep: {
          auto until = std::chrono::steady_clock::now() + std::chrono::duration<double>(a.value);
          while (std::chrono::steady_clock::now() < until) {
            if (hooks.frame) hooks.frame();
            std::this_thread::sleep_for(std::chrono::milliseconds(100));
          }
          break;
        }
        case Kind::Recovery:
          state.resolveRecovery(a.name == "restore"   ? ViewerState::RecoveryChoice::Restore
                                : a.name == "discard" ? ViewerState::RecoveryChoice::Discard
                                                      : ViewerState::RecoveryChoice::Keep);
          break;
        case Kind::Start:
          state.startAutoSkeletonJob();
          break;
        case Kind::Confirm:
          if (!state.confirmationPending()) throw OptionsError("no question is waiting");
          state.answerConfirmation(a.value != 0);
          break;
        case Kind::Expect:
          for (const auto& [k, v] : a.expect) {
            std::string d = checkExpect(state, k, v);
            if (!d.empty()) failure += (failure.empty() ? "" : "; ") + d;
          }
          break;
        case Kind::Window:
          if (!hooks.window) throw OptionsError(a.name + " needs a window");
          failure = hooks.window(a);
          break;
      }
    } catch (const std::exception& e) {
      failure = e.what();
      state.error(what + ": " + e.what());
    }
    // Background work started by this action (the autoSkeleton button) ends before the next
    // action, as a person waits for the progress bar, with frames drawn meanwhile; "start" leaves
    // it running, and {"wait": "job"} waits for it.
    const bool waitForJob = a.kind == Kind::Wait ? a.name == "job" : a.kind != Kind::Start && !busyBefore;
    if (waitForJob && state.busy()) {
      if (hooks.frame) {
        // The frame takes a finished job in itself (the window's own pollJob), so the loop ends
        // when the state is no longer busy, whoever took the result: waiting for pollJob() alone
        // to return true hung when a frame took it first (CI: gui.background_job timed out).
        while (state.busy() && !state.pollJob()) {
          hooks.frame();
          std::this_thread::sleep_for(std::chrono::milliseconds(20));
        }
      } else {
        state.waitForJob();
      }
    }
    if (failure.empty() && state.errorCount() > errorsBefore) failure = state.lastMessage().text;
    if (a.expectError) {
      if (hooks.log) hooks.log(a, failure.empty() ? "no error (one was expected)" : "refused as expected: " + failure);
      failure = failure.empty() ? "expected this action to fail, it did not" : std::string();
    }
    if (!failure.empty()) {
      report.failures.push_back("action " + std::to_string(a.index) + " (" + what + "): " + failure);
      if (a.kind == Kind::Expect || a.kind == Kind::Key || a.kind == Kind::Window) state.error(report.failures.back());
    }
    ++report.actionsRun;
    if (&a == &script.actions.back() && state.busy()) state.waitForJob();  // a script ends with its work done
    if (hooks.frame && a.kind != Kind::Wait && a.kind != Kind::Screenshot) hooks.frame();
  }
  return report;
}

}  // namespace treesketch::viewer
