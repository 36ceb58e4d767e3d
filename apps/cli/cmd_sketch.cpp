// `treesketch sketch auto CLOUD --nodes N --view front|side|top|CAMERA.json [--method uniform]
// [--up y|z] [--ortho] -o SKETCH.json`: an automatic sketch of a cloud, saved for `reconstruct`
// or for refining in the desktop tool. Methods: "uniform" = the thesis baseline (§5.4).
#include <cstdio>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "commands.h"
#include "tree_job.h"
#include "treesketch/cloud/scale_check.h"
#include "treesketch/cloud/usable_extent.h"
#include "treesketch/model/tree_model.h"
#include "treesketch/io/point_cloud_io.h"
#include "treesketch/io/sketch_file.h"
#include "treesketch/io/up_axis.h"
#include "treesketch/io/view_camera.h"
#include "treesketch/skeleton/skeleton_sketch.h"
#include "treesketch/sketch/auto_sketch.h"
#include "treesketch/util/atomic_file.h"
#include "treesketch/util/error.h"

namespace treesketch::cli {

namespace {

/// What every automatic method gets.
struct AutoSketchInput {
  const std::string& source;  ///< the cloud's path, for messages
  const geom::PointCloud& cloud;
  const geom::Camera& camera;
  int nodes;
  geom::UpAxis up;
  bool leafOn;
};
using AutoSketchMethod = std::function<sketch::Sketch(const AutoSketchInput&)>;

/// The automatic methods by name. A new method is one more entry here.
const std::map<std::string, AutoSketchMethod>& autoSketchMethods() {
  static const std::map<std::string, AutoSketchMethod> methods = {
      {"uniform",
       [](const AutoSketchInput& in) { return sketch::uniformAutoSketch(in.cloud, in.camera, in.nodes, in.up); }},
      // The branching skeleton found from the cloud and fitted (skeleton module), as `reconstruct
      // --auto` makes it: every node keeps its model circle, so `reconstruct --sketch` of this file
      // gives the automatic model and the viewer shows it. --nodes and --view are not used.
      {"skeleton",
       [](const AutoSketchInput& in) {
         const auto o =
             skeleton::autoSkeletonPreset(in.leafOn ? skeleton::Foliage::LeafOn : skeleton::Foliage::LeafOff, in.up);
         const skeleton::AutoSkeletonResult r = skeleton::autoSkeletonSketch(in.cloud, o);
         // The check every automatic model gets: no sketch of unfitted circles on a degenerate cloud.
         model::checkAutoModel(in.source, r.strays.empty() ? in.cloud : cloud::keptPoints(in.cloud, r.strays), r);
         std::printf("%s of %zu\n", cloud::strayPointsLine(r.strays).c_str(), in.cloud.size());
         printScaleWarnings(cloud::checkScale(in.cloud, r.strays));
         return r.sketch;
       }},
  };
  return methods;
}

struct AutoOptions {
  std::string cloud, view = "front", method = "uniform", up, output;  // up "" = io/up_axis.h
  int nodes = 18;  // the thesis's automatic sketches had 18 nodes (Table 5.2)
  bool ortho = false;
  bool leafOn = false;  // --leaf-on: the skeleton method's settings for trees in leaf
  int width = 1280, height = 800;
};

void runAuto(const AutoOptions& o) {
  if (!o.up.empty()) geom::parseUpAxis(o.up);  // a bad value fails before the cloud is read
  if (o.nodes < 1) throw OptionsError("--nodes must be >= 1, got " + std::to_string(o.nodes));
  // A node is a slice of the cloud fitted by RANSAC: the thesis drew 18; 100,000 is past any tree
  // (1e8 ran out of memory before it was refused).
  if (o.nodes > 100000) throw OptionsError("--nodes must be at most 100000, got " + std::to_string(o.nodes));
  if (o.width < 1 || o.height < 1) throw OptionsError("--width and --height must be >= 1");
  checkNotAnInput(o.output, {o.cloud});
  checkOutputWritable(o.output);
  geom::PointCloud cloud = io::readPointCloud(o.cloud);
  cloud::requireUsableExtent(cloud, o.cloud);
  const io::UpAxisChoice choice = io::chooseUpAxis(o.up, cloud);
  const geom::UpAxis up = choice.up;
  std::printf("up axis: %s\n", choice.reason.c_str());
  geom::Viewport viewport{0, 0, static_cast<double>(o.width), static_cast<double>(o.height)};
  geom::Camera camera = io::cameraForView(o.view, cloud.bounds(), up, viewport, o.ortho);
  const auto& methods = autoSketchMethods();
  auto it = methods.find(o.method);
  if (it == methods.end()) throw OptionsError("--method: unknown method '" + o.method + "'");
  sketch::Sketch sk = it->second(AutoSketchInput{o.cloud, cloud, camera, o.nodes, up, o.leafOn});
  io::writeSketch(std::filesystem::path(o.output), sk);
  std::printf("sketch: %zu nodes (%s, view %s), %zu kept circles, from %zu points -> %s\n", sk.size(), o.method.c_str(),
              o.view.c_str(), sk.keptCircleCount(), cloud.size(), o.output.c_str());
}

}  // namespace

void registerSketch(CLI::App& app, Action& action) {
  auto* sub = app.add_subcommand("sketch", "Make sketches automatically");
  sub->require_subcommand(1);
  auto* autoCmd = sub->add_subcommand("auto", "An automatic sketch of a point cloud, saved as JSON");
  auto o = std::make_shared<AutoOptions>();
  std::vector<std::string> names;
  for (const auto& [name, m] : autoSketchMethods()) names.push_back(name);
  autoCmd->add_option("cloud", o->cloud, "Point cloud (.ply .xyz .txt .csv .pts .asc .las .laz)")->required();
  autoCmd->add_option("-n,--nodes", o->nodes, "Number of nodes (default 18, as the thesis's automatic sketches)");
  autoCmd->add_option("--view", o->view, "front, side, top, or a camera JSON file {view, projection, viewport}");
  autoCmd->add_option("--method", o->method, "Automatic method")->check(CLI::IsMember(names));
  autoCmd
      ->add_option("--up", o->up,
                   "World up axis: y or z (default: what the file declares — LAS z, a treesketch PLY its own — else z)")
      ->check(CLI::IsMember({"y", "z", "Y", "Z"}));
  autoCmd->add_flag("--leaf-on", o->leafOn,
                    "Method skeleton: the tree was scanned in leaf (finer voxels, weaker foliage rule)");
  autoCmd->add_flag("--ortho", o->ortho, "Orthographic preset camera (default perspective, 30° field of view)");
  autoCmd->add_option("--width", o->width, "Viewport width of a preset camera, pixels (default 1280)");
  autoCmd->add_option("--height", o->height, "Viewport height of a preset camera, pixels (default 800)");
  autoCmd->add_option("-o,--output", o->output, "Output sketch (.json)")->required();
  autoCmd->callback([o, &action] { action = [o] { runAuto(*o); }; });
}

}  // namespace treesketch::cli
