// The viewer's edit path on a 1M-point cloud, without a GPU: a one-node edit (drag a node by a
// pixel, or move a slice-thickness slider) -> ViewerState action -> incremental reconstruction ->
// the data a frame draws (node markers, circle and sampling-region lines, slice points). Target:
// within one 60 Hz frame (16 ms). Cloud: the demo tree (default preset, with leaves) scanned with
// ~1.18 M rays (the thesis's largest scan, 18 * 4^8); sketch: 8 clicks up the trunk in the front
// view, as a user would place them.
//
// BM_EditRebuildsFrameData adds the CPU side of re-uploading the cloud's GPU buffers after an
// edit (point colours recomputed in the distance colouring, put in the level-of-detail order).
// BM_IdleWindow runs the real window (treesketch-gui --measure-idle, under xvfb-run when there is
// no display) and reports the frames it draws and the CPU it takes while nobody touches it;
// BM_HoverPanel the same window while the mouse moves over its side panel (--measure-hover).
//
//   build-xxx/bench_viewer --benchmark_min_time=2
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <string>

#include "treesketch/viewer/demo_scene.h"
#include "treesketch/viewer/point_colors.h"
#include "treesketch/viewer/point_lod.h"
#include "treesketch/viewer/viewer_state.h"

namespace {

using treesketch::geom::Vec2;
using treesketch::geom::Vec3;
namespace viewer = treesketch::viewer;

const treesketch::geom::PointCloud& cloud() {
  static const treesketch::geom::PointCloud c = [] {
    viewer::DemoSceneOptions o;
    o.rays = 2'000'000;
    return viewer::demoTreeCloud(o);
  }();
  return c;
}

/// A state with the 1M cloud and a user-like sketch up the trunk; `node` gets a fitted node
/// in the middle of the chain (the one edited).
std::unique_ptr<viewer::ViewerState> sketchedState(treesketch::sketch::NodeId* node) {
  auto s = std::make_unique<viewer::ViewerState>();
  s->view().setViewport({340, 0, 940, 774});
  s->setCloud(cloud(), treesketch::geom::UpAxis::Y);
  s->setTool(viewer::ViewerState::Tool::AddNodes);  // clicks add nodes (the default selects)
  double top = cloud().bounds().max.y();
  for (int i = 1; i <= 8; ++i) s->clickAt(s->view().camera().project(Vec3(0, top * 0.05 * i, 0)).head<2>());
  *node = treesketch::sketch::kNoNode;
  for (treesketch::sketch::NodeId id : {3, 4, 2, 5, 1})
    if (s->scene().nodeFit(id).status == viewer::NodeStatus::Fitted) {
      *node = id;
      break;
    }
  return s;
}

void reportCounters(benchmark::State& st, const viewer::ViewerState& s) {
  st.counters["points"] = static_cast<double>(s.cloud().size());
  st.counters["nodes"] = static_cast<double>(s.sketch().size());
  st.counters["fitted"] = static_cast<double>(s.scene().fittedCount());
  st.counters["rebuild_ms"] = s.lastRebuildMs();
  st.counters["errors"] = static_cast<double>(s.status().errorCount());
}

/// Drag a node by one pixel (alternating up/down): one undoable edit, re-fit of the node and its
/// child (whose plane follows the parent), re-sweep, plus the frame's overlay data.
void BM_DragNodeOnePixel(benchmark::State& st) {
  treesketch::sketch::NodeId id;
  auto s = sketchedState(&id);
  if (id == treesketch::sketch::kNoNode) {
    st.SkipWithError("no fitted node to edit");
    return;
  }
  s->selectNode(id);
  Vec2 base = s->sketch().node(id).screen;
  int k = 0;
  for (auto _ : st) {
    s->moveNodeTo(id, base + Vec2(0, (k++ & 1) ? 1.0 : 0.0));
    benchmark::DoNotOptimize(s->scene().nodeMarkers());
    benchmark::DoNotOptimize(s->scene().sceneLines());
    benchmark::DoNotOptimize(s->scene().highlightedSlicePoints());
  }
  reportCounters(st, *s);
}
BENCHMARK(BM_DragNodeOnePixel)->Unit(benchmark::kMillisecond);

/// Slice half-thickness slider of the selected node (alternating two values).
void BM_SliderSliceThickness(benchmark::State& st) {
  treesketch::sketch::NodeId id;
  auto s = sketchedState(&id);
  if (id == treesketch::sketch::kNoNode) {
    st.SkipWithError("no fitted node to edit");
    return;
  }
  s->selectNode(id);
  double eps = s->sketch().node(id).params.sliceHalfThickness;
  int k = 0;
  for (auto _ : st) {
    s->setSliceHalfThickness(eps * ((k++ & 1) ? 1.1 : 1.0));
    benchmark::DoNotOptimize(s->scene().sceneLines());
    benchmark::DoNotOptimize(s->scene().highlightedSlicePoints());
  }
  reportCounters(st, *s);
}
BENCHMARK(BM_SliderSliceThickness)->Unit(benchmark::kMillisecond);

/// Add a node at the top of the chain by a click, then undo it (two edits per iteration).
void BM_AddNodeThenUndo(benchmark::State& st) {
  treesketch::sketch::NodeId id;
  auto s = sketchedState(&id);
  Vec2 at = s->view().camera().project(Vec3(0, cloud().bounds().max.y() * 0.45, 0)).head<2>();
  for (auto _ : st) {
    s->addNodeAt(at);
    s->undo();
  }
  reportCounters(st, *s);
}
BENCHMARK(BM_AddNodeThenUndo)->Unit(benchmark::kMillisecond);

/// What an orbiting frame recomputes on the CPU with no edit: markers, lines, slice highlight.
void BM_FrameOverlayData(benchmark::State& st) {
  treesketch::sketch::NodeId id;
  auto s = sketchedState(&id);
  if (id != treesketch::sketch::kNoNode) s->selectNode(id);
  int k = 0;
  for (auto _ : st) {
    s->view().orbit().rotate(Vec2(700, 400), Vec2(700 + ((k++ & 1) ? 2 : -2), 400));
    benchmark::DoNotOptimize(s->scene().nodeMarkers());
    benchmark::DoNotOptimize(s->scene().sceneLines());
    benchmark::DoNotOptimize(s->scene().highlightedSlicePoints());
  }
  reportCounters(st, *s);
}
BENCHMARK(BM_FrameOverlayData)->Unit(benchmark::kMillisecond);

/// One edit (drag a node by a pixel) and everything the next frame needs on the CPU to redraw it:
/// the rebuild, the overlay data, and the cloud's colours recomputed and put in the upload order
/// (in the distance colouring every edit changes them; in the height colouring none does).
void BM_EditRebuildsFrameData(benchmark::State& st) {
  treesketch::sketch::NodeId id;
  auto s = sketchedState(&id);
  if (id == treesketch::sketch::kNoNode) {
    st.SkipWithError("no fitted node to edit");
    return;
  }
  s->view().setColorMode(st.range(0) ? viewer::ColorMode::CircleDistance : viewer::ColorMode::Height);
  viewer::PointLod lod;
  lod.build(s->cloud().size());
  const std::uint8_t* upload = nullptr;
  s->selectNode(id);
  Vec2 base = s->sketch().node(id).screen;
  int k = 0;
  std::uint64_t colourUploads = 0;
  for (auto _ : st) {
    s->moveNodeTo(id, base + Vec2(0, (k++ & 1) ? 1.0 : 0.0));
    benchmark::DoNotOptimize(s->scene().nodeMarkers());
    benchmark::DoNotOptimize(s->scene().sceneLines());
    std::uint64_t before = s->scene().colorsVersion();
    const auto& colors = s->scene().pointColors();
    if (s->scene().colorsVersion() != before) {
      upload = lod.keptColors(colors).data();  // as the window: only the changed points rewritten
      ++colourUploads;
    }
    benchmark::DoNotOptimize(upload);
  }
  reportCounters(st, *s);
  st.counters["colour_uploads_per_edit"] = double(colourUploads) / double(st.iterations());
}
BENCHMARK(BM_EditRebuildsFrameData)->Arg(0)->Arg(1)->ArgName("distance")->Unit(benchmark::kMillisecond);

/// The distance colouring alone after each one-pixel drag, two ways on the same model, timed in
/// turn within each iteration (so both see the same load): the grid keeping its colours and
/// measuring only near the pieces the edit changed, and a grid measuring near every piece (what
/// every edit did before the colours were kept). Counters: milliseconds of each, their ratio, and
/// the points each measured one by one. The two must give the same colours (checked each time).
void BM_SurfaceColoursAfterEdit(benchmark::State& st) {
  treesketch::sketch::NodeId id;
  auto s = sketchedState(&id);
  if (id == treesketch::sketch::kNoNode) {
    st.SkipWithError("no fitted node to edit");
    return;
  }
  const double scale = s->options().distanceColorScale * s->bounds().diagonal();
  viewer::DistanceColorGrid kept, full;
  kept.build(s->cloud(), scale);
  full.build(s->cloud(), scale);
  std::vector<viewer::Rgb> keptColours, fullColours;
  kept.surfaceColors(s->scene().treeModel().cylinders, keptColours);
  s->selectNode(id);
  const Vec2 base = s->sketch().node(id).screen;
  int k = 0;
  double keptMs = 0, fullMs = 0, keptPoints = 0, fullPoints = 0;
  using Clock = std::chrono::steady_clock;
  auto ms = [](Clock::duration d) { return std::chrono::duration<double, std::milli>(d).count(); };
  for (auto _ : st) {
    s->moveNodeTo(id, base + Vec2(0, (k & 1) ? 1.0 : 0.0));
    const treesketch::geom::CylinderModel model = s->scene().treeModel().cylinders;
    auto runKept = [&] {
      const auto t = Clock::now();
      kept.surfaceColors(model, keptColours);
      keptMs += ms(Clock::now() - t);
    };
    auto runFull = [&] {
      const auto t = Clock::now();
      full.forgetSurface();
      full.surfaceColors(model, fullColours);
      fullMs += ms(Clock::now() - t);
    };
    if (k++ & 1) {
      runKept();
      runFull();
    } else {
      runFull();
      runKept();
    }
    keptPoints += static_cast<double>(kept.lastPointsMeasured());
    fullPoints += static_cast<double>(full.lastPointsMeasured());
    if (keptColours != fullColours) {
      st.SkipWithError("the kept colours differ from the full measure");
      return;
    }
  }
  const double n = static_cast<double>(st.iterations());
  st.counters["kept_ms"] = keptMs / n;
  st.counters["full_ms"] = fullMs / n;
  st.counters["full_over_kept"] = fullMs / std::max(keptMs, 1e-9);
  st.counters["kept_points"] = keptPoints / n;
  st.counters["full_points"] = fullPoints / n;
  reportCounters(st, *s);
}
BENCHMARK(BM_SurfaceColoursAfterEdit)->Unit(benchmark::kMillisecond);

/// The real window left alone: frames drawn and CPU used per second of idle (after 1 s settling).
void BM_IdleWindow(benchmark::State& st) {
  const std::string gui = TS_GUI_PATH;
  if (!std::filesystem::exists(gui)) {
    st.SkipWithError("treesketch-gui is not built");
    return;
  }
  std::string cmd = "LIBGL_ALWAYS_SOFTWARE=1 " + gui + " --demo-rays 30000 --measure-idle 5 2>&1";
  if (!std::getenv("DISPLAY"))
    cmd = "LIBGL_ALWAYS_SOFTWARE=1 xvfb-run -a -s '-screen 0 1280x800x24' " + gui +
          " --demo-rays 30000 --measure-idle 5 2>&1";
  for (auto _ : st) {
    FILE* p = popen(cmd.c_str(), "r");
    if (!p) {
      st.SkipWithError("cannot run treesketch-gui");
      return;
    }
    char line[512];
    double wall = 0, perSecond = -1, cpu = 0, percent = 0;
    unsigned long long frames = 0;
    while (std::fgets(line, sizeof line, p)) {
      if (std::sscanf(line, "treesketch-gui: idle %lf s: %llu frames drawn (%lf per second), CPU %lf s (%lf", &wall,
                      &frames, &perSecond, &cpu, &percent) == 5)
        break;
    }
    pclose(p);
    if (perSecond < 0) {
      st.SkipWithError("no idle measure from treesketch-gui (no display and no xvfb-run?)");
      return;
    }
    st.counters["idle_s"] = wall;
    st.counters["frames_per_idle_s"] = perSecond;
    st.counters["cpu_pct_of_core"] = percent;
  }
}
BENCHMARK(BM_IdleWindow)->Iterations(1)->Unit(benchmark::kSecond);

/// The real window with the mouse moving over its side panel (40 moves, 50 ms apart) on a ~1.1 M
/// point cloud: frames drawn, scene draws (the cloud drawn anew) and CPU per move. A frame drawn for
/// the panel alone shows the scene's kept image.
void BM_HoverPanel(benchmark::State& st) {
  const std::string gui = TS_GUI_PATH;
  if (!std::filesystem::exists(gui)) {
    st.SkipWithError("treesketch-gui is not built");
    return;
  }
  const std::string run = gui + " --demo-rays 2000000 --measure-hover 40 2>&1";
  const std::string cmd = std::string("LIBGL_ALWAYS_SOFTWARE=1 ") +
                          (std::getenv("DISPLAY") ? "" : "xvfb-run -a -s '-screen 0 1280x800x24' ") + run;
  for (auto _ : st) {
    FILE* p = popen(cmd.c_str(), "r");
    if (!p) {
      st.SkipWithError("cannot run treesketch-gui");
      return;
    }
    char line[512];
    int moves = 0;
    double wall = 0, framesPerMove = -1, scenesPerMove = -1, cpu = 0, cpuMsPerMove = 0;
    unsigned long long frames = 0, scenes = 0;
    while (std::fgets(line, sizeof line, p)) {
      if (std::sscanf(line,
                      "treesketch-gui: hover %d moves over the panel in %lf s: %llu frames (%lf per move), %llu scene "
                      "draws (%lf per move), CPU %lf s (%lf",
                      &moves, &wall, &frames, &framesPerMove, &scenes, &scenesPerMove, &cpu, &cpuMsPerMove) == 8)
        break;
    }
    pclose(p);
    if (scenesPerMove < 0) {
      st.SkipWithError("no hover measure from treesketch-gui (no display and no xvfb-run?)");
      return;
    }
    st.counters["frames_per_move"] = framesPerMove;
    st.counters["scene_draws_per_move"] = scenesPerMove;
    st.counters["cpu_ms_per_move"] = cpuMsPerMove;
  }
}
BENCHMARK(BM_HoverPanel)->Iterations(1)->Unit(benchmark::kSecond);

}  // namespace

BENCHMARK_MAIN();
