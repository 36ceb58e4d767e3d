// `treesketch demo [--out DIR] [--seed S] [--subdiv K]`: the whole pipeline on a built-in tree,
// with no input file. Each step is one function below, run in order by runDemo; later pipeline
// stages (reconstruct, compare) are added as further steps that read and extend DemoState.
//   1. generate  — the procedural tree (gen/): skeleton, branch mesh, leaf quads
//   2. reference — write tree_branches.obj, tree_leaves.obj, tree_skeleton.json
//   3. scan      — the thesis's sphere scanner over branches + leaves (scan/)
//   4. cloud     — write cloud.ply (with the mesh id of each point: 0 wood, 1 leaf)
//   5. sketch, reconstruct — a simulated user's sketch on the true skeleton (front view, pixel
//                  jitter) and the thesis's uniform automatic sketch; both reconstructed
//                  (sketch_*.json, recon_*.obj)
//   6. automatic — treesketch's automatic model, on the scan's wood points (a leaf-off scan of
//                  the same tree) and with the leaf-on settings on every point; the first one's
//                  outputs as a user gets them (recon_auto.obj, cylinders_auto.csv, qsm_auto.txt,
//                  metrics_auto.json, report_auto.json) and a picture over the cloud (auto.png)
//   7. compare   — each reconstruction against the branch mesh, both directions (Hausdorff,
//                  as MeshLab/Metro); error mesh of the user's reconstruction (error_user.ply)
//   8. summary   — counts, wood fraction, bounds, the comparison table, the automatic model's
//                  forestry figures, timings -> stdout and summary.txt
#include <cstdio>
#include <filesystem>
#include <memory>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "commands.h"
#include "treesketch/compare/error_mesh.h"
#include "treesketch/compare/hausdorff.h"
#include "treesketch/eval/evaluation.h"
#include "treesketch/eval/tree_suite.h"
#include "treesketch/gen/skeleton_io.h"
#include "treesketch/gen/tree_generator.h"
#include "treesketch/io/mesh_io.h"
#include "treesketch/io/point_cloud_io.h"
#include "treesketch/io/sketch_file.h"
#include "treesketch/model/tree_model.h"
#include "treesketch/render/color_map.h"
#include "treesketch/render/png_writer.h"
#include "treesketch/render/scene_render.h"
#include "treesketch/scan/sphere_scan.h"
#include "treesketch/util/atomic_file.h"
#include "treesketch/util/error.h"
#include "treesketch/util/progress.h"
#include "treesketch/util/stopwatch.h"

namespace treesketch::cli {

namespace {

namespace fs = std::filesystem;

struct DemoArgs {
  std::string out = "out/demo";
  std::uint64_t seed = 1;
  int subdiv = 6;  // thesis §4.2: 6 subdivisions = 73,728 rays
  std::string preset = "default";
  int detail = 1;
  int userNodes = 30;     ///< simulated user's node budget
  int uniformNodes = 18;  ///< thesis Table 5.2
};

/// One reconstruction of the demo tree and its comparison with the branch mesh.
struct DemoMethod {
  std::string name;
  eval::MethodOutput output;
  compare::BothReport report;
};

/// Everything the steps produce, passed from one step to the next.
struct DemoState {
  DemoArgs args;
  fs::path dir;
  gen::TreeOptions treeOptions;
  gen::GeneratedTree tree;
  scan::ScanResult scan;
  std::vector<DemoMethod> methods;
  std::vector<std::pair<std::string, double>> timings;  ///< step name, milliseconds
  std::ostringstream summary;                           ///< filled by the steps, printed at the end
};

/// Runs `step`, recording its wall time under `name`.
template <typename F>
void timed(DemoState& s, const std::string& name, F&& step) {
  const Stopwatch timer;
  step();
  s.timings.emplace_back(name, timer.ms());
}

std::string formatBox(const geom::BBox& b) {
  if (b.empty()) return "empty";
  char buf[160];
  std::snprintf(buf, sizeof buf, "[%.3f %.3f %.3f] - [%.3f %.3f %.3f] m (diagonal %.3f m)", b.min.x(), b.min.y(),
                b.min.z(), b.max.x(), b.max.y(), b.max.z(), b.diagonal());
  return buf;
}

void prepareOutputDir(DemoState& s) {
  s.dir = s.args.out;
  if (fs::exists(s.dir) && !fs::is_directory(s.dir))
    throw OutputError(s.dir.string() + ": exists and is not a folder; expected the output folder");
  checkOutputWritable(s.dir / "summary.txt");  // creates the folder, checks it can be written
}

void stepGenerate(DemoState& s) {
  s.treeOptions = gen::presetOptions(s.args.preset);
  s.treeOptions.seed = s.args.seed;
  s.treeOptions.detail = s.args.detail;
  s.tree = gen::generateTree(s.treeOptions);
  const gen::Skeleton& sk = s.tree.skeleton;
  int perLevel[5] = {0, 0, 0, 0, 0};
  for (const auto& b : sk.branches) ++perLevel[std::min(b.level, 4)];
  s.summary << "tree: preset " << s.args.preset << ", seed " << s.args.seed << ", detail " << s.args.detail << ", up "
            << geom::toString(sk.up) << "\n";
  s.summary << "  branches: " << sk.branches.size() << " (per level:";
  for (int l = 0; l <= sk.maxLevel() && l < 5; ++l) s.summary << " " << perLevel[l];
  s.summary << "), sections " << sk.sectionCount() << ", total length " << gen::totalLength(sk) << " m\n";
  s.summary << "  trunk base radius " << sk.branches[0].sections[0].radius << " m, wood volume " << gen::woodVolume(sk)
            << " m^3\n";
  s.summary << "  branch mesh: " << s.tree.branches.mesh.vertices.size() << " vertices, "
            << s.tree.branches.mesh.triangles.size() << " triangles, area " << s.tree.branches.mesh.area() << " m^2\n";
  s.summary << "  leaf mesh: " << s.tree.leaves.triangles.size() / 2 << " quads, area " << s.tree.leaves.area()
            << " m^2\n";
  s.summary << "  bounds (branches): " << formatBox(s.tree.branches.mesh.bounds()) << "\n";
}

void stepWriteReference(DemoState& s) {
  io::writeMesh(s.dir / "tree_branches.obj", s.tree.branches.mesh);
  io::writeMesh(s.dir / "tree_leaves.obj", s.tree.leaves);
  gen::writeSkeletonJson(s.dir / "tree_skeleton.json", s.tree.skeleton);
}

void stepScan(DemoState& s) {
  scan::SphereScanOptions o;
  o.subdivisions = s.args.subdiv;
  o.seed = s.args.seed;
  o.recordMesh = true;
  ProgressBar bar("scan", ProgressBar::stderrIsTerminal());
  std::vector<geom::TriMesh> meshes{s.tree.branches.mesh};
  if (!s.tree.leaves.empty()) meshes.push_back(s.tree.leaves);
  s.scan = scan::sphereScan(meshes, o, bar.callback());
  const scan::ScanStats& st = s.scan.stats;
  s.summary << "scan: sphere pattern, subdivisions " << s.args.subdiv << ", " << st.raysCast << " rays, " << st.hits
            << " points (" << (st.raysCast ? 100.0 * st.hits / st.raysCast : 0.0) << "% hit)\n";
  s.summary << "  wood fraction " << st.fraction(0) << " (" << (st.hitsPerMesh.empty() ? 0 : st.hitsPerMesh[0])
            << " points on branches, " << (st.hitsPerMesh.size() > 1 ? st.hitsPerMesh[1] : 0) << " on leaves)\n";
  s.summary << "  bounds (cloud): " << formatBox(s.scan.cloud.bounds()) << "\n";
}

void stepWriteCloud(DemoState& s) {
  s.scan.cloud.up = s.tree.skeleton.up;  // the PLY says its up, so later commands need no --up
  io::writePointCloud(s.dir / "cloud.ply", s.scan.cloud);
}

void stepReconstruct(DemoState& s) {
  eval::TreeCase tc = eval::treeCaseFromGenerated("demo", s.tree);
  eval::EvalOptions eo;
  eo.seed = s.args.seed;
  for (const std::string name : {"user", "uniform"}) {
    int nodes = name == "uniform" ? s.args.uniformNodes : s.args.userNodes;
    DemoMethod m;
    m.name = name;
    m.output = eval::runMethod(name, eval::MethodInput{tc, s.scan.cloud, eo, nodes});
    io::writeSketch(s.dir / ("sketch_" + name + ".json"), m.output.sketch);
    io::writeMesh(s.dir / ("recon_" + name + ".obj"), m.output.mesh);
    s.methods.push_back(std::move(m));
  }
}

/// The scan's points that hit wood: what a leaf-off scan of the same tree would see.
geom::PointCloud woodPoints(const geom::PointCloud& cloud) {
  geom::PointCloud wood;
  wood.up = cloud.up;
  for (std::size_t i = 0; i < cloud.size(); ++i)
    if (i < cloud.meshId.size() && cloud.meshId[i] == 0) wood.positions.push_back(cloud.positions[i]);
  return wood;
}

/// The automatic model as a user gets it: its files, and a picture of it over the cloud.
void writeAutoOutputs(DemoState& s, const model::TreeModel& tree, const geom::PointCloud& cloud) {
  model::OutputPaths out;
  out.mesh = (s.dir / "recon_auto.obj").string();
  out.cylinders = (s.dir / "cylinders_auto.csv").string();
  out.qsm = (s.dir / "qsm_auto.txt").string();
  out.metrics = (s.dir / "metrics_auto.json").string();
  out.report = (s.dir / "report_auto.json").string();
  const model::ModelMeasures m = model::measure(tree, cloud);
  model::writeOutputs(tree, m, out, {{"cloud", "cloud.ply (wood points)"}, {"auto", true}});
  s.summary << "automatic model (wood points): " << tree.cylinders.size() << " cylinders; " << m.summary() << "\n";
  char line[300];
  // The scan sees the branch mesh, whose rings are polygons inscribed in the skeleton's circles.
  std::snprintf(line, sizeof line,
                "  height %.2f m, DBH %.1f cm, volume %.4f m^3 (the branch mesh holds %.4f, its round sections "
                "%.4f), stem %.4f, branches %.4f m^3 in %zu branches\n",
                m.metrics.height, 100.0 * m.metrics.figures.trunkDiameter, m.metrics.figures.volume,
                gen::branchMeshVolume(s.tree.skeleton, s.tree.branches), gen::woodVolume(s.tree.skeleton),
                m.metrics.stemVolume, m.metrics.branchVolume, m.metrics.branches);
  s.summary << line;

  render::RenderScene scene;
  scene.cloud = s.scan.cloud.positions;
  scene.cloudColors = render::heightColors(scene.cloud, tree.up);
  for (auto& c : scene.cloudColors) c = render::blend(c, {255, 255, 255}, 0.65);
  scene.cloudBehindMeshes = true;
  scene.meshes.push_back(tree.mesh);
  const int size = 900;
  geom::Camera camera = render::fitCamera(scene.bounds(), render::parseRenderView("front"), tree.up, size, size);
  camera = render::tightenCamera(camera, scene.cloud);
  render::writePng(s.dir / "auto.png", render::renderScene(scene, camera, size, size));
}

void stepAutomatic(DemoState& s) {
  eval::TreeCase tc = eval::treeCaseFromGenerated("demo", s.tree);
  eval::EvalOptions eo;
  eo.seed = s.args.seed;
  const geom::PointCloud wood = woodPoints(s.scan.cloud);
  DemoMethod leafOff;
  leafOff.name = "auto";
  leafOff.output = eval::runMethod("skeleton", eval::MethodInput{tc, wood, eo, 0, false});
  DemoMethod leafOn;
  leafOn.name = "auto-leaf";
  leafOn.output = eval::runMethod("skeleton", eval::MethodInput{tc, s.scan.cloud, eo, 0, true});
  if (!leafOff.output.model.empty()) writeAutoOutputs(s, leafOff.output.model, wood);
  s.methods.push_back(std::move(leafOff));
  s.methods.push_back(std::move(leafOn));
}

void stepCompare(DemoState& s) {
  compare::CompareOptions co;
  co.sampling.seed = s.args.seed;
  co.keepSamples = true;
  const geom::TriMesh& original = s.tree.branches.mesh;
  const double diag = original.bounds().diagonal();
  char line[256];
  s.summary << "reconstruction and comparison with the branch mesh (Hausdorff, % of its bbox diagonal " << diag
            << " m):\n";
  std::snprintf(line, sizeof line, "  %-9s %6s %6s %9s | %-25s | %-25s\n", "sketch", "nodes", "fitted", "ms",
                "backward max/mean/RMS %", "forward max/mean/RMS %");
  s.summary << line;
  for (auto& m : s.methods) {
    if (m.output.mesh.empty()) {
      s.summary << "  " << m.name << ": no circle fitted, nothing to compare\n";
      continue;
    }
    m.report = compare::compareBoth(original, m.output.mesh, co);
    auto pct = [&](double v) { return 100.0 * v / diag; };
    const auto& b = m.report.backward;
    const auto& f = m.report.forward;
    std::snprintf(line, sizeof line, "  %-9s %6d %6d %9.1f | %7.3f %7.3f %7.3f       | %7.3f %7.3f %7.3f\n",
                  m.name.c_str(), m.output.nodes, m.output.fitted, m.output.ms, pct(b.max), pct(b.mean), pct(b.rms),
                  pct(f.max), pct(f.mean), pct(f.rms));
    s.summary << line;
    if (m.name == "user") {
      std::vector<double> vd = compare::vertexDistancesFromReport(m.report.forward, original.vertices.size());
      compare::ErrorMeshOptions eo;
      io::writeMesh(s.dir / "error_user.ply", compare::makeErrorMesh(original, vd, eo));
    }
  }
  s.summary << "  (backward: reconstruction sampled against the original; forward: the original against the "
               "reconstruction; user and uniform: the thesis's sketches; auto: treesketch's automatic model on the "
               "wood points, auto-leaf: with --leaf-on on every point)\n";
}

void stepSummary(DemoState& s) {
  std::ostringstream text;
  text << "treesketch demo -> " << s.dir.string() << "\n" << s.summary.str() << "timings:\n";
  double total = 0;
  for (const auto& [name, ms] : s.timings) {
    char line[120];
    std::snprintf(line, sizeof line, "  %-10s %10.1f ms\n", name.c_str(), ms);
    text << line;
    total += ms;
  }
  char line[120];
  std::snprintf(line, sizeof line, "  %-10s %10.1f ms\n", "total", total);
  text << line;
  text << "files: tree_branches.obj tree_leaves.obj tree_skeleton.json cloud.ply sketch_user.json sketch_uniform.json "
          "recon_user.obj recon_uniform.obj recon_auto.obj cylinders_auto.csv qsm_auto.txt metrics_auto.json "
          "report_auto.json auto.png error_user.ply summary.txt\n";
  const std::string str = text.str();
  writeFileAtomically(
      s.dir / "summary.txt", [&](std::ostream& out) { out << str; }, false);
  std::fputs(str.c_str(), stdout);
}

void runDemo(const DemoArgs& args) {
  DemoState s;
  s.args = args;
  s.summary.precision(4);
  prepareOutputDir(s);
  timed(s, "generate", [&] { stepGenerate(s); });
  timed(s, "reference", [&] { stepWriteReference(s); });
  timed(s, "scan", [&] { stepScan(s); });
  timed(s, "cloud", [&] { stepWriteCloud(s); });
  timed(s, "sketch+fit", [&] { stepReconstruct(s); });
  timed(s, "automatic", [&] { stepAutomatic(s); });
  timed(s, "compare", [&] { stepCompare(s); });
  stepSummary(s);
}

}  // namespace

void registerDemo(CLI::App& app, Action& action) {
  auto* sub = app.add_subcommand("demo", "Generate a tree, scan it and write everything to a folder (no input needed)");
  auto a = std::make_shared<DemoArgs>();
  sub->add_option("--out", a->out, "Output directory (created if missing)")->capture_default_str();
  sub->add_option("--seed", a->seed, "Random seed of the tree and the scan")->capture_default_str();
  sub->add_option("--subdiv", a->subdiv, "Scanner sphere subdivisions k: 18*4^k rays (thesis: 6-8)")
      ->check(CLI::Range(1, 10))
      ->capture_default_str();
  sub->add_option("--preset", a->preset, "Tree preset: default, conifer or sparse")
      ->check(CLI::IsMember(gen::presetNames()))
      ->capture_default_str();
  sub->add_option("--detail", a->detail, "Mesh detail multiplier (triangles ~ detail^2)")
      ->check(CLI::Range(1, 16))
      ->capture_default_str();
  sub->add_option("--user-nodes", a->userNodes, "Node budget of the simulated user's sketch")
      ->check(CLI::Range(2, 10000))
      ->capture_default_str();
  sub->add_option("--uniform-nodes", a->uniformNodes, "Nodes of the uniform automatic sketch (thesis: 18)")
      ->check(CLI::Range(1, 10000))
      ->capture_default_str();
  sub->callback([a, &action] { action = [a] { runDemo(*a); }; });
}

}  // namespace treesketch::cli
