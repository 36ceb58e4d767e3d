// `treesketch render`: a PNG picture of a point cloud, meshes, a sketch and a skeleton, drawn by
// the library's software rasterizer (no display, no OpenGL). Inputs overlay: cloud points (grey
// or coloured by height), meshes (shaded, one colour each), sketch and skeleton lines on top.
#include <cstdio>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "commands.h"
#include "treesketch/classify/classify.h"
#include "treesketch/cloud/usable_extent.h"
#include "treesketch/io/mesh_io.h"
#include "treesketch/io/point_cloud_io.h"
#include "treesketch/io/sketch_file.h"
#include "treesketch/render/color_map.h"
#include "treesketch/render/png_writer.h"
#include "treesketch/render/polyline_obj.h"
#include "treesketch/render/scene_render.h"
#include "treesketch/util/atomic_file.h"
#include "treesketch/util/error.h"

namespace treesketch::cli {

namespace {

/// Colours of class codes: wood and leaf as `treesketch classify` writes them, anything else grey.
std::vector<render::Rgb> classColors(const std::vector<std::uint8_t>& codes) {
  std::vector<render::Rgb> out(codes.size(), render::Rgb{150, 150, 150});
  for (std::size_t i = 0; i < codes.size(); ++i) {
    if (codes[i] == classify::kWoodClass) out[i] = {125, 70, 25};
    if (codes[i] == classify::kLeafClass) out[i] = {95, 185, 80};
  }
  return out;
}

struct RenderArgs {
  std::string cloud;
  std::vector<std::string> meshes;
  std::string sketch;
  std::string skeleton;
  std::string view = "iso";
  std::string up;  // empty: the sketch's up axis, else z
  std::string size = "900x900";
  int pointSize = 2;
  std::string colorBy = "height";
  bool wireframe = false;
  std::string output;
};

void parseSize(const std::string& s, int& w, int& h) {
  std::size_t x = s.find_first_of("xX");
  try {
    std::size_t used = 0;
    if (x == std::string::npos) throw std::invalid_argument("no x");
    w = std::stoi(s.substr(0, x), &used);
    if (used != x) throw std::invalid_argument("trailing");
    h = std::stoi(s.substr(x + 1), &used);
    if (used != s.size() - x - 1) throw std::invalid_argument("trailing");
  } catch (const std::exception&) {
    throw OptionsError("--size: expected WIDTHxHEIGHT in pixels (e.g. 900x900), got '" + s + "'");
  }
  if (w < 16 || h < 16 || w > 8192 || h > 8192) throw OptionsError("--size: each side must be 16..8192 pixels");
}

void runRender(const RenderArgs& a) {
  if (a.cloud.empty() && a.meshes.empty() && a.sketch.empty() && a.skeleton.empty())
    throw OptionsError("render: nothing to draw (give --cloud, --mesh, --sketch or --skeleton)");
  int width = 0, height = 0;
  parseSize(a.size, width, height);
  for (const std::string& in : {a.cloud, a.sketch, a.skeleton})
    if (!in.empty()) checkNotAnInput(a.output, {in});
  for (const std::string& m : a.meshes) checkNotAnInput(a.output, {m});
  checkOutputWritable(a.output);
  const render::RenderView view = render::parseRenderView(a.view);

  std::optional<sketch::Sketch> sk;
  if (!a.sketch.empty()) sk = io::readSketch(a.sketch);
  const geom::UpAxis up = !a.up.empty() ? geom::parseUpAxis(a.up) : sk ? sk->up : geom::UpAxis::Z;

  render::RenderScene scene;
  scene.pointSize = a.pointSize;
  scene.meshStyle.wireframe = a.wireframe;
  geom::PointCloud cloud;
  if (!a.cloud.empty()) {
    cloud = io::readPointCloud(a.cloud);
    cloud::requireUsableExtent(cloud, a.cloud);
  }
  scene.cloud = cloud.positions;
  for (const std::string& m : a.meshes) scene.meshes.push_back(io::readMesh(m));
  const bool faint = !scene.meshes.empty();  // the cloud recedes behind a reconstruction
  scene.cloudBehindMeshes = faint;
  if (a.colorBy == "height") {
    scene.cloudColors = render::heightColors(scene.cloud, up);
    if (faint)
      for (auto& c : scene.cloudColors) c = render::blend(c, {255, 255, 255}, 0.65);
  } else if (a.colorBy == "class") {
    if (cloud.classification.empty())
      throw InputError(a.cloud + ": --color-by class needs a classification (write one with `treesketch classify`)");
    scene.cloudColors = classColors(cloud.classification);
  } else {
    scene.cloudColor = faint ? render::Rgb{185, 185, 185} : render::Rgb{110, 110, 110};
  }
  if (!a.skeleton.empty()) {
    for (auto& pts : render::readObjPolylines(a.skeleton)) scene.polylines.push_back({std::move(pts), {200, 20, 20}});
  }
  if (sk) {
    geom::BBox focusBox = scene.bounds();
    geom::Vec3 focus = focusBox.empty() ? geom::Vec3::Zero() : focusBox.centre();
    std::size_t placed = render::addSketch(scene, *sk, focus, {220, 30, 30});
    if (placed < sk->size())
      std::fprintf(stderr, "render: %zu of %zu sketch nodes had no usable position and were skipped\n",
                   sk->size() - placed, sk->size());
  }
  geom::BBox box = scene.bounds();
  if (box.empty()) throw OptionsError("render: the inputs hold nothing to draw");
  geom::Camera camera = render::fitCamera(box, view, up, width, height);
  std::vector<geom::Vec3> all = scene.cloud;  // frame what is drawn, not the box's empty corners
  for (const auto& m : scene.meshes) all.insert(all.end(), m.vertices.begin(), m.vertices.end());
  for (const auto& l : scene.polylines) all.insert(all.end(), l.points.begin(), l.points.end());
  for (const auto& d : scene.dots) all.push_back(d.position);
  camera = render::tightenCamera(camera, all);
  render::Image image = render::renderScene(scene, camera, width, height);
  render::writePng(a.output, image);
  std::printf("wrote %s (%d x %d, %s view)\n", a.output.c_str(), width, height, a.view.c_str());
}

}  // namespace

void registerRender(CLI::App& app, Action& action) {
  auto* sub = app.add_subcommand("render", "Draw a cloud, meshes, a sketch and a skeleton into a PNG (no display)");
  auto a = std::make_shared<RenderArgs>();
  sub->add_option("--cloud", a->cloud, "Point cloud (.ply .xyz .txt .csv .pts .asc .las .laz)");
  sub->add_option("--mesh", a->meshes, "Mesh (.obj .ply); repeat for several, each gets its own colour");
  sub->add_option("--sketch", a->sketch, "Sketch file (.json): nodes as dots, parent links as lines");
  sub->add_option("--skeleton", a->skeleton, "OBJ file with 'v' and 'l' lines (a skeleton), drawn as lines");
  sub->add_option("--view", a->view, "front, side, top (orthographic) or iso (perspective, 45° azimuth, 30° up)")
      ->check(CLI::IsMember({"front", "side", "top", "iso"}))
      ->capture_default_str();
  sub->add_option("--up", a->up, "Up axis, y or z (default: the sketch's, else z)")->check(CLI::IsMember({"y", "z"}));
  sub->add_option("--size", a->size, "Picture size WIDTHxHEIGHT in pixels")->capture_default_str();
  sub->add_option("--point-size", a->pointSize, "Cloud point size in pixels")
      ->check(CLI::Range(1, 32))
      ->capture_default_str();
  sub->add_option("--color-by", a->colorBy,
                  "Cloud colour: height (ramp), class (the classification: wood brown, leaf green, other grey) or none")
      ->check(CLI::IsMember({"height", "class", "none"}))
      ->capture_default_str();
  sub->add_flag("--wireframe", a->wireframe, "Draw mesh triangle edges over the shading");
  sub->add_option("-o,--output", a->output, "Output picture (.png)")->required();
  sub->callback([a, &action] { action = [a] { runRender(*a); }; });
}

}  // namespace treesketch::cli
