// treesketch-gui-check: checks what a scripted treesketch-gui session wrote, independently of the
// window: the sketch file (node count, a single tree, screen nodes), the autosave (removed once the
// work is saved), the exported mesh (enough triangles, inside the demo cloud's box) and the
// screenshot (the cloud visible, each node's marker at its screen position). Exit 0 when every
// requested check passes; prints one line per failed check otherwise.
#include <stb_image.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "treesketch/io/mesh_io.h"
#include "treesketch/io/sketch_file.h"
#include "treesketch/viewer/demo_scene.h"

using namespace treesketch;

namespace {

int failures = 0;

void check(bool ok, const std::string& what) {
  std::cout << (ok ? "ok:     " : "FAILED: ") << what << "\n";
  if (!ok) ++failures;
}

// The marker colours of apps/viewer/panels.h (fitted, skipped, pending).
const int kMarkers[3][3] = {{60, 220, 90}, {255, 80, 40}, {200, 200, 200}};
const int kBackground[3] = {28, 31, 36};  // glClearColor(0.11, 0.12, 0.14)

struct Args {
  std::string sketchPath, autosavePath, meshPath, pngPath;
  long nodes = -1, minTriangles = -1, cloudPixels = -1;
  int colour[3] = {-1, -1, -1};               ///< --colour R,G,B: count the pixels of this colour
  long minColourPixels = -1, maxColourPixels = -1;
  std::uint64_t demoRays = 0;
  bool markers = false;
};

// The command line; exits 2 on a bad option.
Args parseArgs(int argc, char** argv) {
  Args r;
  for (int i = 1; i < argc; ++i) {
    std::string a = argv[i];
    auto next = [&]() -> std::string {
      if (i + 1 >= argc) {
        std::cerr << a << " needs a value\n";
        std::exit(2);
      }
      return argv[++i];
    };
    if (a == "--sketch")
      r.sketchPath = next();
    else if (a == "--autosave")
      r.autosavePath = next();
    else if (a == "--mesh")
      r.meshPath = next();
    else if (a == "--png")
      r.pngPath = next();
    else if (a == "--nodes")
      r.nodes = std::stol(next());
    else if (a == "--min-triangles")
      r.minTriangles = std::stol(next());
    else if (a == "--cloud-pixels")
      r.cloudPixels = std::stol(next());
    else if (a == "--demo-rays")
      r.demoRays = std::stoull(next());
    else if (a == "--markers")
      r.markers = true;
    else if (a == "--colour") {
      if (std::sscanf(next().c_str(), "%d,%d,%d", &r.colour[0], &r.colour[1], &r.colour[2]) != 3) {
        std::cerr << "--colour needs R,G,B\n";
        std::exit(2);
      }
    } else if (a == "--min-colour-pixels")
      r.minColourPixels = std::stol(next());
    else if (a == "--max-colour-pixels")
      r.maxColourPixels = std::stol(next());
    else {
      std::cerr << "unknown option " << a << "\n";
      std::exit(2);
    }
  }
  return r;
}

void checkMesh(const Args& args) {
  geom::TriMesh mesh = io::readMesh(args.meshPath);
  if (args.minTriangles >= 0)
    check(static_cast<long>(mesh.triangles.size()) >= args.minTriangles,
          "mesh has at least " + std::to_string(args.minTriangles) + " triangles (got " +
              std::to_string(mesh.triangles.size()) + ")");
  if (args.demoRays > 0) {
    viewer::DemoSceneOptions demo;
    demo.rays = args.demoRays;
    geom::BBox box = viewer::demoTreeCloud(demo).bounds();
    geom::BBox mb = mesh.bounds();
    double slack = 0.05 * box.diagonal();
    bool inside =
        (mb.min.array() >= box.min.array() - slack).all() && (mb.max.array() <= box.max.array() + slack).all();
    check(inside, "mesh lies within the demo cloud's bounding box");
  }
}

// The screenshot's checks; false when it does not read as an image.
bool checkScreenshot(const Args& args, const sketch::Sketch& sk) {
  int w = 0, h = 0, c = 0;
  unsigned char* img = stbi_load(args.pngPath.c_str(), &w, &h, &c, 3);
  check(img != nullptr, "screenshot " + args.pngPath + " reads as an image");
  if (!img) return false;
  auto px = [&](int x, int y) { return img + 3 * (static_cast<std::size_t>(y) * w + x); };
  if (args.cloudPixels >= 0) {
    // Pixels of the 3D view (right of the 340-pixel panel, above the status bar) that are
    // neither background nor grey UI: the coloured cloud.
    long count = 0;
    for (int y = 0; y < h - 30; ++y)
      for (int x = 345; x < w; ++x) {
        const unsigned char* p = px(x, y);
        int diff = std::abs(p[0] - kBackground[0]) + std::abs(p[1] - kBackground[1]) + std::abs(p[2] - kBackground[2]);
        int chroma = std::max({p[0], p[1], p[2]}) - std::min({p[0], p[1], p[2]});
        count += diff > 40 && chroma > 30;
      }
    check(count >= args.cloudPixels, "the cloud covers at least " + std::to_string(args.cloudPixels) + " pixels (got " +
                                         std::to_string(count) + ")");
  }
  if (args.colour[0] >= 0) {
    // Pixels of the 3D view within a small distance of one colour (a drawn tool path, say).
    long count = 0;
    for (int y = 0; y < h - 30; ++y)
      for (int x = 345; x < w; ++x) {
        const unsigned char* p = px(x, y);
        count += std::abs(p[0] - args.colour[0]) + std::abs(p[1] - args.colour[1]) + std::abs(p[2] - args.colour[2]) < 40;
      }
    const std::string what = "pixels of colour " + std::to_string(args.colour[0]) + "," + std::to_string(args.colour[1]) +
                             "," + std::to_string(args.colour[2]) + " (got " + std::to_string(count) + ")";
    if (args.minColourPixels >= 0) check(count >= args.minColourPixels, "at least " + std::to_string(args.minColourPixels) + " " + what);
    if (args.maxColourPixels >= 0) check(count <= args.maxColourPixels, "at most " + std::to_string(args.maxColourPixels) + " " + what);
  }
  if (args.markers && !args.sketchPath.empty()) {
    for (const auto& [id, n] : sk.nodes()) {
      int x = static_cast<int>(std::lround(n.screen.x())), y = static_cast<int>(std::lround(n.screen.y()));
      bool ok = false;
      std::string got = "outside";
      if (x >= 0 && y >= 0 && x < w && y < h) {
        const unsigned char* p = px(x, y);
        got = std::to_string(p[0]) + "," + std::to_string(p[1]) + "," + std::to_string(p[2]);
        for (const auto& m : kMarkers) ok |= std::abs(p[0] - m[0]) + std::abs(p[1] - m[1]) + std::abs(p[2] - m[2]) < 30;
      }
      check(ok, "node " + std::to_string(id) + "'s marker is drawn at (" + std::to_string(x) + ", " +
                    std::to_string(y) + ") (pixel " + got + ")");
    }
  }
  stbi_image_free(img);
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  const Args args = parseArgs(argc, argv);
  try {
    sketch::Sketch sk;
    if (!args.sketchPath.empty()) {
      sk = io::readSketch(args.sketchPath);
      if (args.nodes >= 0)
        check(static_cast<long>(sk.size()) == args.nodes,
              "sketch has " + std::to_string(args.nodes) + " nodes (got " + std::to_string(sk.size()) + ")");
      bool chain = true;
      for (const auto& [id, n] : sk.nodes()) chain &= n.isScreenNode();
      check(chain && sk.root() != sketch::kNoNode, "sketch is one tree of screen nodes");
    }
    if (!args.autosavePath.empty() && !args.sketchPath.empty()) {
      // A window closed with its work saved leaves no autosave to offer back.
      std::error_code ec;
      check(!std::filesystem::exists(args.autosavePath, ec), "the autosave is removed once the sketch is saved");
    }
    if (!args.meshPath.empty()) checkMesh(args);
    if (!args.pngPath.empty() && !checkScreenshot(args, sk)) return 1;
  } catch (const std::exception& e) {
    std::cout << "FAILED: " << e.what() << "\n";
    return 1;
  }
  return failures == 0 ? 0 : 1;
}
