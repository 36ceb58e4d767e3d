// The action script's runner: each action done on the ViewerState as a person's input would do it.
#include "treesketch/viewer/action_script.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <optional>
#include <sstream>
#include <thread>

#include "treesketch/util/error.h"
#include "viewer/script_vocabulary.h"

namespace treesketch::viewer {

using Kind = ScriptAction::Kind;
using namespace script;

namespace {

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

namespace {

// Does an action of the pointer, the keys, the panels or the editing tools; returns what failed
// ("" when nothing did), or nothing when the action is none of these.
std::optional<std::string> performInput(ViewerState& state, const ScriptAction& a, const ScriptHooks& hooks) {
  switch (a.kind) {
    case Kind::Click:
      state.clickAt(a.from, a.button, a.mods);
      break;
    case Kind::Drag:
      if (a.name == "release") {  // ends a drag held by "hold"
        state.mouseUp(a.to, a.button, a.mods);
      } else if (a.name == "hold") {  // press and move, the button kept down (what is drawn meanwhile)
        state.mouseDown(a.from, a.button, a.mods);
        for (int i = 1; i <= a.steps; ++i) {
          state.mouseMove(a.from + (a.to - a.from) * (double(i) / a.steps));
          if (hooks.frame) hooks.frame();
        }
      } else {
        // Move in steps, drawing a frame after each, as a real drag would.
        state.dragTo(a.from, a.to, a.button, a.mods, a.steps, hooks.frame);
      }
      break;
    case Kind::Scroll:
      state.scroll(a.value);
      break;
    case Kind::Key:
      if (!state.keyPress(a.name, a.mods)) return "no action is bound to key '" + a.name + "'";
      break;
    case Kind::Slider:
      if (const Slider* slider = entryNamed(kSliders, a.name)) slider->set(state, a.value);
      break;
    case Kind::Option:
      applyOption(state, a.name, a.text);
      break;
    case Kind::View:
      if (a.name == "fit")
        state.view().fitView();
      else
        state.view().presetView(geom::parsePresetView(a.name));
      break;
    case Kind::Select:
      state.selectNode(static_cast<sketch::NodeId>(a.value));
      break;
    case Kind::Button:
      if (const Button* button = entryNamed(kButtons, a.name)) button->press(state);
      break;
    case Kind::Path:
      if (a.name == "stroke")
        state.strokeLimb(a.points);
      else if (a.name == "lasso")
        state.lassoNotWood(a.points);
      else if (a.name == "lassoWood")
        state.lassoWood(a.points);
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
        state.reattachNode(id, static_cast<sketch::NodeId>(a.value2), a.text == "reverse");
      break;
    }
    case Kind::Tool:
      if (const ToolName* t = entryNamed(kTools, a.name)) state.setTool(t->tool);
      break;
    default:
      return std::nullopt;
  }
  return std::string();
}

// Does one action; returns what failed ("" when nothing did). Throws what the state throws.
std::string performAction(ViewerState& state, const ScriptAction& a, const ScriptHooks& hooks) {
  if (std::optional<std::string> failure = performInput(state, a, hooks)) return *failure;
  std::string failure;
  switch (a.kind) {
    case Kind::Save:
    case Kind::Load: {
      std::filesystem::path p = !a.path.empty()                          ? a.path
                                : !state.document().sketchPath().empty() ? state.document().sketchPath()
                                                                         : hooks.sketchPath;
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
      state.status().info("screenshot written to " + a.path.string());
      break;
    case Kind::Wait:
      for (int i = 0; i < a.steps && hooks.frame; ++i) hooks.frame();
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
      if (a.name == "classify")
        state.startClassifyJob();
      else if (a.name == "autoSkeletonWood")
        state.startWoodSkeletonJob();
      else
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
    default:
      break;
  }
  return failure;
}

// Background work started by an action (the autoSkeleton button) ends before the next action, as
// a person waits for the progress bar, with frames drawn meanwhile; "start" leaves it running, and
// {"wait": "job"} waits for it.
void waitForActionJob(ViewerState& state, const ScriptAction& a, bool busyBefore, const ScriptHooks& hooks) {
  const bool waitForJob = a.kind == Kind::Wait ? a.name == "job" : a.kind != Kind::Start && !busyBefore;
  if (waitForJob && state.jobs().busy()) {
    if (hooks.frame) {
      // The frame takes a finished job in itself (the window's own pollJob), so the loop ends
      // when the state is no longer busy, whoever took the result: waiting for pollJob() alone
      // to return true hung when a frame took it first (CI: gui.background_job timed out).
      while (state.jobs().busy() && !state.pollJob()) {
        hooks.frame();
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
      }
    } else {
      state.waitForJob();
    }
  }
}

}  // namespace

ScriptReport runActionScript(ViewerState& state, const ActionScript& script, const ScriptHooks& hooks) {
  ScriptReport report;
  for (const ScriptAction& a : script.actions) {
    std::string what = describe(a);
    if (hooks.log) hooks.log(a, what);
    std::size_t errorsBefore = state.status().errorCount();
    const bool busyBefore = state.jobs().busy();
    std::string failure;
    try {
      failure = performAction(state, a, hooks);
    } catch (const std::exception& e) {
      failure = e.what();
      state.status().error(what + ": " + e.what());
    }
    waitForActionJob(state, a, busyBefore, hooks);
    if (failure.empty() && state.status().errorCount() > errorsBefore) failure = state.status().lastMessage().text;
    if (a.expectError) {
      if (hooks.log) hooks.log(a, failure.empty() ? "no error (one was expected)" : "refused as expected: " + failure);
      failure = failure.empty() ? "expected this action to fail, it did not" : std::string();
    }
    if (!failure.empty()) {
      report.failures.push_back("action " + std::to_string(a.index) + " (" + what + "): " + failure);
      if (a.kind == Kind::Expect || a.kind == Kind::Key || a.kind == Kind::Window)
        state.status().error(report.failures.back());
    }
    ++report.actionsRun;
    if (&a == &script.actions.back() && state.jobs().busy()) state.waitForJob();  // a script ends with its work done
    if (hooks.frame && a.kind != Kind::Wait && a.kind != Kind::Screenshot) hooks.frame();
  }
  return report;
}

}  // namespace treesketch::viewer
