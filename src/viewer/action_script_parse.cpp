// The action script's parser: JSON (or one-line strings) to ScriptActions, every name checked
// against the vocabularies so that a typo fails before anything runs.
#include <algorithm>
#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "treesketch/util/error.h"
#include "treesketch/viewer/action_script.h"
#include "viewer/script_vocabulary.h"

namespace treesketch::viewer {

using nlohmann::json;
using Kind = ScriptAction::Kind;
using namespace script;

namespace {

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
      a.kind = verb == "save" ? Kind::Save : verb == "load" ? Kind::Load : exportVerb ? Kind::Export : Kind::Screenshot;
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

  /// {"click"}, {"drag"}, {"release"}, {"scroll"}, {"key"}, {"slider"}, {"option"}, {"view"}, {"select"}; false
  /// when `j` holds none of them.
  bool inputVerb(const json& j, std::size_t index, ScriptAction& a) const {
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
      if (j.contains("hold")) {
        if (!j["hold"].is_boolean()) fail(index, "hold: expected true or false");
        if (j["hold"].get<bool>()) a.name = "hold";  // the button stays down until "release"
      }
    } else if (j.contains("release")) {
      a.kind = Kind::Drag;
      a.name = "release";
      a.from = a.to = point(j["release"], index, "release");
      if (j.contains("button")) a.button = button(j["button"].get<std::string>(), index);
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
    } else {
      return false;
    }
    return true;
  }

  /// {"stroke"}, {"lasso"}, {"lassoWood"}, {"region"}, {"deleteSubtree"}, {"automaticBelow"}, {"reattach"},
  /// {"tool"}; false when `j` holds none of them.
  bool editVerb(const json& j, std::size_t index, ScriptAction& a) const {
    if (j.contains("stroke") || j.contains("lasso") || j.contains("lassoWood") || j.contains("region")) {
      a.kind = Kind::Path;
      a.name = j.contains("stroke")      ? "stroke"
               : j.contains("lasso")     ? "lasso"
               : j.contains("lassoWood") ? "lassoWood"
                                         : "region";
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
      if (j.contains("reverse")) {
        if (!j["reverse"].is_boolean()) fail(index, "reverse: expected true or false");
        if (j["reverse"].get<bool>()) a.text = "reverse";
      }
    } else if (j.contains("tool")) {
      a.kind = Kind::Tool;
      a.name = string(j["tool"], index, "tool");
      if (!entryNamed(kTools, a.name))
        fail(index, "tool must be sketch, stroke, lasso, lassoWood, region or reattach, got '" + a.name + "'");
    } else {
      return false;
    }
    return true;
  }

  /// {"start"}, {"confirm"}, {"recovery"}, {"sleep"}, {"wait"}; false when `j` holds none of them.
  bool sessionVerb(const json& j, std::size_t index, ScriptAction& a) const {
    if (j.contains("start")) {
      a.kind = Kind::Start;
      a.name = string(j["start"], index, "start");
      if (a.name != "autoSkeleton" && a.name != "autoSkeletonWood" && a.name != "classify")
        fail(index, "start: only 'autoSkeleton', 'autoSkeletonWood' and 'classify' run in the background, got '" +
                        a.name + "'");
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
    } else {
      return false;
    }
    return true;
  }

  ScriptAction verbFromObject(const json& j, std::size_t index) const {
    ScriptAction a;
    a.index = index;
    if (j.contains("button") && !j["button"].is_string()) fail(index, "button: expected a string");
    if (j.contains("mods")) a.mods = mods(string(j["mods"], index, "mods"), index);
    if (inputVerb(j, index, a)) return a;
    if (j.contains("button")) {
      ScriptAction b = fromString(j["button"].get<std::string>(), index);
      if (b.kind != Kind::Button) fail(index, "unknown button '" + j["button"].get<std::string>() + "'");
      return b;
    }
    if (const std::string verb = pathVerb(j); !verb.empty()) {
      const json& p = j[verb];
      std::string path = p.is_null() ? std::string() : string(p, index, verb);
      return fromString(path.empty() ? verb : verb + " " + path, index);
    }
    if (editVerb(j, index, a) || sessionVerb(j, index, a) || windowVerb(j, index, a)) return a;
    if (j.contains("expect")) {
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

}  // namespace

ActionScript parseActionScript(std::istream& in, const std::string& source) { return Parser(source).parse(in); }

ActionScript parseActionScript(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path.string() + ": cannot open the script");
  return parseActionScript(in, path.string());
}

}  // namespace treesketch::viewer
