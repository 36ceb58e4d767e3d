// Every widget of the side panel answers to its own ImGui ID. Two widgets with one label (the View
// "nodes" checkbox and the Sketch "nodes" slider) share an ID, and then the mouse on one moves the
// other. Headless: Dear ImGui runs without a window or GL; the mouse is moved over a grid covering
// the panel and the hovered ID is recorded at each point; one widget covers one connected region,
// so an ID seen in two separate regions belongs to two widgets. Run by CTest (gui.panels_unique_ids)
// with a node selected and without, so that every section is drawn. The same scan checks that every
// hovered widget shows a tooltip. With --steady (CTest gui.panel_steady) it checks instead that
// selecting a node moves none of the controls below the Node section (a click meant for one of them
// hit another when the section grew).
#include <imgui.h>
#include <imgui_internal.h>

#include <cmath>
#include <cstdio>
#include <map>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "../panels.h"
#include "treesketch/viewer/viewer_state.h"

using namespace treesketch;

namespace {

geom::PointCloud trunk() {
  geom::PointCloud cloud;
  for (int i = 0; i < 4000; ++i) {
    double a = 0.37 * i, y = 4.0 * i / 4000.0;
    cloud.positions.emplace_back(0.2 * std::cos(a), y, 0.2 * std::sin(a));
  }
  return cloud;
}

constexpr int kStep = 3;  // pixels; less than ImGui's item spacing (4 px vertically, 8 across)

/// Scans the panel; returns the number of IDs seen in more than one region (and prints them).
int clashes(viewer::ViewerState& state, gui::PanelState& panel, int width, int height) {
  int bad = 0;
  std::map<ImGuiID, std::set<std::pair<int, int>>> cells;
  std::map<ImGuiID, std::pair<int, int>> untipped;  // hovered widgets that showed no tooltip
  ImGuiIO& io = ImGui::GetIO();
  bool tipShown = false;
  auto frame = [&](float x, float y) {
    io.MousePos = ImVec2(x, y);
    ImGui::NewFrame();
    gui::drawPanels(state, panel, width, height);
    ImGuiID id = ImGui::GetCurrentContext()->HoveredId;
    ImGuiWindow* tip = ImGui::FindWindowByName("##Tooltip_00");  // Dear ImGui's tooltip window
    tipShown = tip && tip->Active;
    ImGui::Render();
    return id;
  };
  frame(-100, -100);
  for (int gy = 0; gy * kStep < height; ++gy)
    for (int gx = 0; gx * kStep < gui::Layout::kPanelWidth; ++gx) {
      frame(float(gx * kStep), float(gy * kStep));  // hover is resolved against the previous frame
      ImGuiID id = frame(float(gx * kStep), float(gy * kStep));
      if (id != 0) cells[id].insert({gx, gy});
      if (id != 0 && !tipShown) untipped.emplace(id, std::pair{gx * kStep, gy * kStep});
    }
  // Every control explains itself (tooltips.cpp's table, or its own tooltip).
  for (auto& [id, at] : untipped) {
    ++bad;
    std::printf("ID %08x at (%d, %d) shows no tooltip\n", id, at.first, at.second);
  }
  for (auto& [id, set] : cells) {
    // Flood-fill one region; any cell left over is a second widget with the same ID.
    std::set<std::pair<int, int>> todo = set, seen;
    std::vector<std::pair<int, int>> stack{*todo.begin()};
    while (!stack.empty()) {
      auto c = stack.back();
      stack.pop_back();
      if (!todo.erase(c)) continue;
      seen.insert(c);
      for (auto d : {std::pair{1, 0}, std::pair{-1, 0}, std::pair{0, 1}, std::pair{0, -1}})
        stack.push_back({c.first + d.first, c.second + d.second});
    }
    if (!todo.empty()) {
      ++bad;
      std::printf("ID %08x is used by two widgets: at (%d, %d) and at (%d, %d)\n", id, seen.begin()->first * kStep,
                  seen.begin()->second * kStep, todo.begin()->first * kStep, todo.begin()->second * kStep);
    }
  }
  std::printf("%zu widget IDs, %d shared or without a tooltip\n", cells.size(), bad);
  return bad;
}

/// The window y (pixels) of the panel's "Correction tools" header: the first row of a scan down the
/// panel where the mouse hovers it; -1 when not found.
int toolsHeaderY(viewer::ViewerState& state, gui::PanelState& panel, int width, int height) {
  ImGuiIO& io = ImGui::GetIO();
  auto hovered = [&](float y) {
    io.MousePos = ImVec2(40.0f, y);
    ImGui::NewFrame();
    gui::drawPanels(state, panel, width, height);
    ImGuiWindow* w = ImGui::FindWindowByName("treesketch");
    ImGuiID header = w ? w->GetID("Correction tools") : 0;
    ImGuiID id = ImGui::GetCurrentContext()->HoveredId;
    ImGui::Render();
    return header != 0 && id == header;
  };
  for (int y = 0; y < height; ++y) {
    hovered(float(y));  // hover is resolved against the previous frame
    if (hovered(float(y))) return y;
  }
  return -1;
}

/// The header's place with each kind of selection: none, a fitted node, a node that did not fit.
int steady(viewer::ViewerState& state, gui::PanelState& panel, int width, int height) {
  int bad = 0;
  state.setTool(viewer::Tool::AddNodes);  // the clicks add three nodes up the trunk
  for (int i = 1; i <= 3; ++i) state.clickAt(state.view().camera().project(geom::Vec3(0, i, 0)).head<2>());
  state.setTool(viewer::Tool::Select);
  state.selectNode(sketch::kNoNode);
  const int none = toolsHeaderY(state, panel, width, height);
  std::printf("no node selected: the Correction tools header at y = %d\n", none);
  if (none < 0) return 1;
  for (sketch::NodeId id : state.sketch().ids()) {
    if (!state.selectNode(id)) return 1;
    const int y = toolsHeaderY(state, panel, width, height);
    std::printf("node %d (%s) selected: at y = %d\n", id, viewer::toString(state.scene().nodeFit(id).status), y);
    if (y != none) ++bad;
  }
  return bad;
}

}  // namespace

int main(int argc, char** argv) {
  ImGui::CreateContext();
  ImGuiIO& io = ImGui::GetIO();
  io.IniFilename = nullptr;
  io.DeltaTime = 1.0f / 60.0f;
  const int width = 1280, height = 2400;  // tall: every section fits without scrolling
  io.DisplaySize = ImVec2(float(width), float(height));
  unsigned char* pixels = nullptr;
  int tw = 0, th = 0;
  io.Fonts->GetTexDataAsRGBA32(&pixels, &tw, &th);
  io.Fonts->SetTexID(reinterpret_cast<ImTextureID>(static_cast<std::intptr_t>(1)));

  viewer::ViewerState state;
  state.view().setViewport(gui::Layout::sceneViewport(width, height));
  if (!state.setCloud(trunk(), geom::UpAxis::Y)) return 2;
  for (int i = 1; i <= 3; ++i) state.clickAt(state.view().camera().project(geom::Vec3(0, i, 0)).head<2>());
  gui::PanelState panel;
  panel.sketchPath = "unused.sketch.json";
  if (argc > 1 && std::string(argv[1]) == "--steady") {
    state.selectNode(sketch::kNoNode);
    int moved = steady(state, panel, width, height);
    ImGui::DestroyContext();
    if (moved) std::printf("FAILED: selecting a node moved the controls below the Node section\n");
    return moved ? 1 : 0;
  }
  int bad = clashes(state, panel, width, height);  // node 2 selected: the Node section's widgets
  state.selectNode(sketch::kNoNode);
  bad += clashes(state, panel, width, height);  // no node: the sizes for new nodes
  ImGui::DestroyContext();
  if (bad) std::printf("FAILED: give each widget a unique label or a ##suffix, and a row in tooltips.cpp\n");
  return bad ? 1 : 0;
}
