// What the window draws over the 3D view and above the panels: the point colouring's legend, the
// axis gizmo, the scale bar, picked points and the measured distance; and the modal windows (the
// file dialog, the unsaved-work prompt, the "opening ..." notice) and the help and about windows.
// The numbers come from the library (viewer/color_legend.h, view_overlays.h, picking.h).
#include <imgui.h>

#include <algorithm>
#include <cstdio>

#include "build_info.h"
#include "treesketch/viewer/key_bindings.h"
#include "treesketch/viewer/view_overlays.h"
#include "window_ui.h"

namespace treesketch::gui {

namespace {

ImU32 col(const render::Rgb& c, int alpha = 255) { return IM_COL32(c.r, c.g, c.b, alpha); }

constexpr ImGuiWindowFlags kOverlayFlags = ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_AlwaysAutoResize |
                                           ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_NoFocusOnAppearing |
                                           ImGuiWindowFlags_NoNav | ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoInputs;

std::string tickText(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}

/// The legend window at the 3D view's top right.
void drawLegend(const viewer::Legend& l, const geom::Viewport& vp) {
  if (l.kind == viewer::Legend::Kind::None && l.note.empty()) return;
  ImGui::SetNextWindowPos(ImVec2(float(vp.x + vp.width - 10), float(vp.y + 10)), ImGuiCond_Always, ImVec2(1, 0));
  ImGui::SetNextWindowBgAlpha(0.75f);
  ImGui::Begin("##legend", nullptr, kOverlayFlags);
  if (!l.title.empty()) ImGui::TextUnformatted(l.title.c_str());
  if (l.kind == viewer::Legend::Kind::Scale && !l.ramp.empty()) {
    // A horizontal colour bar with round values under it.
    const float w = 220.0f, h = 14.0f;
    ImVec2 p = ImGui::GetCursorScreenPos();
    ImDrawList* dl = ImGui::GetWindowDrawList();
    const std::size_t n = l.ramp.size();
    for (std::size_t i = 0; i + 1 < n; ++i) {
      float x0 = p.x + w * float(i) / float(n - 1), x1 = p.x + w * float(i + 1) / float(n - 1);
      dl->AddRectFilledMultiColor(ImVec2(x0, p.y), ImVec2(x1, p.y + h), col(l.ramp[i]), col(l.ramp[i + 1]),
                                  col(l.ramp[i + 1]), col(l.ramp[i]));
    }
    dl->AddRect(p, ImVec2(p.x + w, p.y + h), IM_COL32(255, 255, 255, 160));
    const double span = l.range.max - l.range.min;
    float textY = p.y + h + 2;
    if (span > 0) {
      for (double t : l.ticks) {
        float x = p.x + w * float((t - l.range.min) / span);
        dl->AddLine(ImVec2(x, p.y + h - 4), ImVec2(x, p.y + h + 2), IM_COL32(255, 255, 255, 220));
        std::string s = tickText(t);
        float tw = ImGui::CalcTextSize(s.c_str()).x;
        dl->AddText(ImVec2(std::clamp(x - tw / 2, p.x - 4, p.x + w - tw + 4), textY), IM_COL32(235, 235, 235, 255),
                    s.c_str());
      }
    } else {
      dl->AddText(ImVec2(p.x, textY), IM_COL32(235, 235, 235, 255), tickText(l.range.min).c_str());
    }
    ImGui::Dummy(ImVec2(w, h + ImGui::GetTextLineHeight() + 4));
    char ends[96];
    std::snprintf(ends, sizeof ends, "%.4g to %.4g", l.range.min, l.range.max);
    ImGui::TextDisabled("%s", ends);
  }
  if (l.kind == viewer::Legend::Kind::Classes) {
    for (const viewer::LegendClass& c : l.classes) {
      ImVec2 p = ImGui::GetCursorScreenPos();
      float s = ImGui::GetTextLineHeight();
      ImGui::GetWindowDrawList()->AddRectFilled(p, ImVec2(p.x + s, p.y + s), col(c.color));
      ImGui::Dummy(ImVec2(s, s));
      ImGui::SameLine();
      ImGui::Text("%3d %s (%zu)", c.code, c.name.c_str(), c.count);
    }
  }
  if (!l.note.empty()) ImGui::TextDisabled("%s", l.note.c_str());
  ImGui::End();
}

/// The axis triad at the 3D view's bottom left: X red, Y green, Z blue, nearer axes drawn last.
void drawGizmo(const geom::Camera& cam, const geom::Viewport& vp) {
  ImDrawList* dl = ImGui::GetBackgroundDrawList();
  const float len = 34.0f;
  ImVec2 o(float(vp.x + 52), float(vp.y + vp.height - 52));
  dl->AddCircleFilled(o, len + 12, IM_COL32(20, 22, 26, 150), 32);
  static const ImU32 colors[3] = {IM_COL32(235, 70, 60, 255), IM_COL32(90, 210, 80, 255), IM_COL32(70, 130, 255, 255)};
  static const char* names[3] = {"X", "Y", "Z"};
  for (const viewer::GizmoAxis& a : viewer::axisGizmo(cam)) {
    ImVec2 e(o.x + len * float(a.direction.x()), o.y + len * float(a.direction.y()));
    ImU32 c = colors[a.axis];
    if (a.towardsViewer < 0) c = (c & 0x00FFFFFF) | (150u << 24);  // pointing away: dimmer
    dl->AddLine(o, e, c, a.towardsViewer < 0 ? 2.0f : 3.0f);
    dl->AddCircleFilled(e, 3.0f, c);
    ImVec2 t(o.x + (len + 8) * float(a.direction.x()) - 4, o.y + (len + 8) * float(a.direction.y()) - 7);
    dl->AddText(t, c, names[a.axis]);
  }
}

/// The scale bar at the 3D view's bottom right.
void drawScaleBar(const viewer::ViewerState& state, const geom::Viewport& vp) {
  viewer::ScaleBar bar = viewer::scaleBarFor(state.view().orbit().worldPerPixel(), 160.0);
  if (!bar.valid()) return;
  ImDrawList* dl = ImGui::GetBackgroundDrawList();
  float x1 = float(vp.x + vp.width - 24), x0 = x1 - float(bar.pixels), y = float(vp.y + vp.height - 24);
  ImU32 white = IM_COL32(240, 240, 240, 255), shade = IM_COL32(0, 0, 0, 160);
  dl->AddRectFilled(ImVec2(x0 - 6, y - 22), ImVec2(x1 + 6, y + 6), shade, 3.0f);
  dl->AddLine(ImVec2(x0, y), ImVec2(x1, y), white, 2.0f);
  dl->AddLine(ImVec2(x0, y - 6), ImVec2(x0, y + 3), white, 2.0f);
  dl->AddLine(ImVec2(x1, y - 6), ImVec2(x1, y + 3), white, 2.0f);
  float tw = ImGui::CalcTextSize(bar.label.c_str()).x;
  dl->AddText(ImVec2((x0 + x1) / 2 - tw / 2, y - 20), white, bar.label.c_str());
}

}  // namespace

void WindowActions::drawOverlays() {
  if (state_.cloud().empty()) return;
  const geom::Camera cam = state_.view().camera();
  const geom::Viewport& vp = cam.viewport;
  if (showLegend_) drawLegend(legend(), vp);
  if (showGizmo_) drawGizmo(cam, vp);
  if (showScaleBar_) drawScaleBar(state_, vp);

  // Picks: markers, the measured segment with its length, and the points' coordinates and attributes.
  if (picks_.count() == 0) {
    if (pickMode_) {
      ImGui::SetNextWindowPos(ImVec2(float(vp.x + 10), float(vp.y + 10)));
      ImGui::SetNextWindowBgAlpha(0.75f);
      ImGui::Begin("##pickinfo", nullptr, kOverlayFlags);
      ImGui::TextUnformatted("Pick mode: click a point (M or Esc to leave)");
      ImGui::End();
    }
    return;
  }
  ImDrawList* dl = ImGui::GetBackgroundDrawList();
  dl->PushClipRect(ImVec2(float(vp.x), float(vp.y)), ImVec2(float(vp.x + vp.width), float(vp.y + vp.height)));
  auto screenOf = [&](const geom::Vec3& p, bool* visible) {
    geom::Vec3 s = cam.project(p);
    *visible = s.z() >= 0.0 && s.z() <= 1.0;
    return ImVec2(float(s.x()), float(s.y()));
  };
  bool va = false, vb = false;
  ImVec2 a = screenOf(picks_.first().position, &va);
  const ImU32 yellow = IM_COL32(255, 225, 40, 255), dark = IM_COL32(10, 10, 10, 255);
  if (picks_.hasMeasurement()) {
    ImVec2 b = screenOf(picks_.second().position, &vb);
    viewer::Measurement m = picks_.measurement(state_.up());
    if (va && vb) {
      dl->AddLine(a, b, dark, 4.0f);
      dl->AddLine(a, b, yellow, 2.0f);
      std::string label = viewer::formatLength(m.distance);
      ImVec2 mid((a.x + b.x) / 2 + 8, (a.y + b.y) / 2 - 8);
      ImVec2 ts = ImGui::CalcTextSize(label.c_str());
      dl->AddRectFilled(ImVec2(mid.x - 3, mid.y - 2), ImVec2(mid.x + ts.x + 3, mid.y + ts.y + 2),
                        IM_COL32(0, 0, 0, 190), 3.0f);
      dl->AddText(mid, yellow, label.c_str());
    }
    if (vb) {
      dl->AddCircle(b, 7.0f, dark, 16, 4.0f);
      dl->AddCircle(b, 7.0f, yellow, 16, 2.0f);
      dl->AddText(ImVec2(b.x + 9, b.y + 2), yellow, "B");
    }
  }
  if (va) {
    dl->AddCircle(a, 7.0f, dark, 16, 4.0f);
    dl->AddCircle(a, 7.0f, yellow, 16, 2.0f);
    dl->AddText(ImVec2(a.x + 9, a.y + 2), yellow, "A");
  }
  dl->PopClipRect();

  ImGui::SetNextWindowPos(ImVec2(float(vp.x + 10), float(vp.y + 10)));
  ImGui::SetNextWindowBgAlpha(0.8f);
  ImGui::Begin("##pickinfo", nullptr, kOverlayFlags);
  const viewer::PickedPoint* points[2] = {&picks_.first(), &picks_.second()};
  for (int i = 0; i < picks_.count(); ++i) {
    ImGui::TextColored(ImVec4(1.0f, 0.88f, 0.16f, 1), "%c  point %zu", i == 0 ? 'A' : 'B', points[i]->index);
    for (const std::string& line : viewer::describePoint(state_.cloud(), points[i]->index))
      ImGui::Text("   %s", line.c_str());
  }
  if (picks_.hasMeasurement()) {
    viewer::Measurement m = picks_.measurement(state_.up());
    ImGui::Separator();
    ImGui::Text("A-B  %.4f  (%s)", m.distance, viewer::formatLength(m.distance).c_str());
    ImGui::Text("     vertical %.4f, horizontal %.4f", m.vertical, m.horizontal);
    ImGui::Text("     dx %.4f  dy %.4f  dz %.4f", m.delta.x(), m.delta.y(), m.delta.z());
  }
  if (!pickMode_) ImGui::TextDisabled("(pick mode off: Tools > Clear picks)");
  ImGui::End();
}

void WindowActions::drawWindows() {
  // One modal at a time: a prompt raised while a dialog is open (the close button) replaces it.
  // Done here, not where the prompt is raised, which may be inside the dialog's own callback.
  if (promptOpen_ && dialog_.isOpen()) dialog_.cancel();
  dialog_.draw();

  if (!pendingOpen_.empty()) {
    ImGuiViewport* v = ImGui::GetMainViewport();
    ImGui::SetNextWindowPos(ImVec2(v->Pos.x + v->Size.x / 2, v->Pos.y + v->Size.y / 2), 0, ImVec2(0.5f, 0.5f));
    ImGui::Begin("##opening", nullptr, kOverlayFlags);
    ImGui::Text("Opening %s ...", pendingOpen_.string().c_str());
    ImGui::End();
  }

  const char* promptId = "Unsaved sketch";
  if (promptOpen_ && !ImGui::IsPopupOpen(promptId)) ImGui::OpenPopup(promptId);
  if (ImGui::BeginPopupModal(promptId, nullptr, ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoSavedSettings)) {
    if (!promptOpen_) {
      ImGui::CloseCurrentPopup();
    } else {
      ImGui::Text("The sketch (%zu nodes) has changes that are not in", state_.sketch().size());
      ImGui::Text(
          "%s.", state_.document().sketchPath().empty() ? "any file" : state_.document().sketchPath().string().c_str());
      ImGui::Text("Save them before %s?", promptWhat_.c_str());
      ImGui::Spacing();
      if (ImGui::Button("Save", ImVec2(100, 0))) answerPrompt("save");
      if (ImGui::IsItemHovered()) ImGui::SetTooltip("Save the sketch to its file, then go on");
      ImGui::SameLine();
      if (ImGui::Button("Discard", ImVec2(100, 0))) answerPrompt("discard");
      if (ImGui::IsItemHovered())
        ImGui::SetTooltip("Go on without saving (the autosave file still holds the last edit)");
      ImGui::SameLine();
      if (ImGui::Button("Cancel", ImVec2(100, 0))) answerPrompt("cancel");
      if (ImGui::IsItemHovered()) ImGui::SetTooltip("Stay here; nothing happens");
      if (!promptOpen_) ImGui::CloseCurrentPopup();
    }
    ImGui::EndPopup();
  }

  if (showHelp_) {
    ImGuiViewport* v = ImGui::GetMainViewport();
    ImGui::SetNextWindowPos(ImVec2(v->Pos.x + v->Size.x / 2 + 170, v->Pos.y + v->Size.y / 2), ImGuiCond_Appearing,
                            ImVec2(0.5f, 0.5f));
    ImGui::SetNextWindowBgAlpha(0.92f);
    ImGui::Begin("Keys and mouse (F1)", &showHelp_,
                 ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoSavedSettings);
    std::string group;
    if (ImGui::BeginTable("##keys", 2, ImGuiTableFlags_SizingFixedFit | ImGuiTableFlags_RowBg)) {
      for (const viewer::KeyBinding& k : viewer::keyBindings()) {
        if (k.group != group) {
          group = k.group;
          ImGui::TableNextRow();
          ImGui::TableSetColumnIndex(0);
          ImGui::TextColored(ImVec4(0.55f, 0.8f, 1.0f, 1), "%s", group.c_str());
        }
        ImGui::TableNextRow();
        ImGui::TableSetColumnIndex(0);
        ImGui::TextUnformatted(k.keys.c_str());
        ImGui::TableSetColumnIndex(1);
        ImGui::TextUnformatted(k.action.c_str());
      }
      ImGui::EndTable();
    }
    ImGui::End();
  }

  if (showAbout_) {
    ImGui::Begin("About treesketch", &showAbout_, ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoSavedSettings);
    ImGui::TextUnformatted(cli::versionString().c_str());
    ImGui::TextUnformatted("User-assisted tree reconstruction from point clouds,");
    ImGui::TextUnformatted("after W. Leavenworth's thesis (Purdue, 2012).");
    ImGui::TextDisabled("Dear ImGui %s, GLFW, OpenGL 3.3", IMGUI_VERSION);
    ImGui::End();
  }
}

}  // namespace treesketch::gui
