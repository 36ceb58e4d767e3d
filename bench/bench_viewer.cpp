// The viewer's edit path on a 1M-point cloud, without a GPU: a one-node edit (drag a node by a
// pixel, or move a slice-thickness slider) -> ViewerState action -> incremental reconstruction ->
// the data a frame draws (node markers, circle and sampling-region lines, slice points). Target:
// within one 60 Hz frame (16 ms). Cloud: the demo tree (default preset, with leaves) scanned with
// ~1.18 M rays (the thesis's largest scan, 18 * 4^8); sketch: 8 clicks up the trunk in the front
// view, as a user would place them.
//
//   build-xxx/bench_viewer --benchmark_min_time=2
#include <benchmark/benchmark.h>

#include <cstdio>
#include <memory>

#include "treesketch/viewer/demo_scene.h"
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
  s->setViewport({340, 0, 940, 774});
  s->setCloud(cloud(), treesketch::geom::UpAxis::Y);
  double top = cloud().bounds().max.y();
  for (int i = 1; i <= 8; ++i) s->clickAt(s->camera().project(Vec3(0, top * 0.05 * i, 0)).head<2>());
  *node = treesketch::sketch::kNoNode;
  for (treesketch::sketch::NodeId id : {3, 4, 2, 5, 1})
    if (s->nodeFit(id).status == viewer::NodeStatus::Fitted) {
      *node = id;
      break;
    }
  return s;
}

void reportCounters(benchmark::State& st, const viewer::ViewerState& s) {
  st.counters["points"] = static_cast<double>(s.cloud().size());
  st.counters["nodes"] = static_cast<double>(s.sketch().size());
  st.counters["fitted"] = static_cast<double>(s.fittedCount());
  st.counters["rebuild_ms"] = s.lastRebuildMs();
  st.counters["errors"] = static_cast<double>(s.errorCount());
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
    benchmark::DoNotOptimize(s->nodeMarkers());
    benchmark::DoNotOptimize(s->sceneLines());
    benchmark::DoNotOptimize(s->highlightedSlicePoints());
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
    benchmark::DoNotOptimize(s->sceneLines());
    benchmark::DoNotOptimize(s->highlightedSlicePoints());
  }
  reportCounters(st, *s);
}
BENCHMARK(BM_SliderSliceThickness)->Unit(benchmark::kMillisecond);

/// Add a node at the top of the chain by a click, then undo it (two edits per iteration).
void BM_AddNodeThenUndo(benchmark::State& st) {
  treesketch::sketch::NodeId id;
  auto s = sketchedState(&id);
  Vec2 at = s->camera().project(Vec3(0, cloud().bounds().max.y() * 0.45, 0)).head<2>();
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
    s->orbit().rotate(Vec2(700, 400), Vec2(700 + ((k++ & 1) ? 2 : -2), 400));
    benchmark::DoNotOptimize(s->nodeMarkers());
    benchmark::DoNotOptimize(s->sceneLines());
    benchmark::DoNotOptimize(s->highlightedSlicePoints());
  }
  reportCounters(st, *s);
}
BENCHMARK(BM_FrameOverlayData)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
