// `treesketch info FILE`: what a point cloud or mesh file holds — format details, counts,
// bounds, bounding-box diagonal and (meshes) surface area.
#include <cstdio>
#include <memory>
#include <string>

#include "commands.h"
#include "treesketch/cloud/ground.h"
#include "treesketch/cloud/scale_check.h"
#include "treesketch/io/file_info.h"

namespace treesketch::cli {

namespace {

void printBounds(const geom::BBox& b) {
  if (b.empty()) {
    std::printf("bounds: empty\n");
    return;
  }
  std::printf("bounds min: %.6f %.6f %.6f\n", b.min.x(), b.min.y(), b.min.z());
  std::printf("bounds max: %.6f %.6f %.6f\n", b.max.x(), b.max.y(), b.max.z());
  geom::Vec3 e = b.extent();
  std::printf("extent: %.6f x %.6f x %.6f\n", e.x(), e.y(), e.z());
  std::printf("bbox diagonal: %.6f\n", b.diagonal());
}

void runInfo(const std::string& file) {
  io::FileInfo info = io::inspectFile(file);
  std::printf("file: %s\n", file.c_str());
  std::printf("format: %s\n", info.format.c_str());
  for (const auto& [key, value] : info.details) std::printf("%s: %s\n", key.c_str(), value.c_str());
  if (info.isMesh) {
    std::printf("vertices: %zu\n", info.mesh.vertices.size());
    std::printf("triangles: %zu\n", info.mesh.triangles.size());
    if (!info.mesh.colors.empty()) std::printf("per-vertex colour: yes\n");
    if (!info.mesh.quality.empty()) std::printf("per-vertex quality: yes\n");
    printBounds(info.mesh.bounds());
    std::printf("surface area: %.6f\n", info.mesh.area());
  } else {
    std::printf("points: %zu\n", info.cloud.size());
    if (!info.cloud.station.empty()) std::printf("per-point station: yes\n");
    if (!info.cloud.meshId.empty()) std::printf("per-point mesh id: yes\n");
    if (!info.cloud.scanner.empty()) std::printf("per-point scanner position: yes\n");
    if (!info.cloud.intensity.empty()) std::printf("per-point intensity: yes\n");
    if (!info.cloud.color.empty()) std::printf("per-point colour (RGB): yes\n");
    if (!info.cloud.classification.empty()) std::printf("per-point classification: yes\n");
    printBounds(info.cloud.bounds());
    const cloud::StrayPoints strays =
        cloud::findStrayAndGroundPoints(info.cloud, info.cloud.up.value_or(geom::UpAxis::Z));
    if (strays.spacing > 0) std::printf("point spacing: %.6g\n", strays.spacing);
    std::printf("%s\n", cloud::strayPointsLine(strays).c_str());
    for (const std::string& w : cloud::checkScale(info.cloud, strays).warnings) std::printf("warning: %s\n", w.c_str());
  }
}

}  // namespace

void registerInfo(CLI::App& app, Action& action) {
  auto* sub = app.add_subcommand("info", "Print a point cloud or mesh file's format, counts, bounds and size");
  auto file = std::make_shared<std::string>();
  sub->add_option("file", *file, "Point cloud (.ply .xyz .txt .csv .pts .asc .las .laz) or mesh (.obj .ply)")
      ->required();
  sub->callback([file, &action] { action = [file] { runInfo(*file); }; });
}

}  // namespace treesketch::cli
