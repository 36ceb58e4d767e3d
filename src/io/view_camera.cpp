// The camera named by a `--view` argument (see view_camera.h).
#include "treesketch/io/view_camera.h"

#include <filesystem>

#include "treesketch/io/sketch_file.h"
#include "treesketch/util/error.h"

namespace treesketch::io {

geom::Camera cameraForView(const std::string& view, const geom::BBox& bounds, geom::UpAxis up,
                           const geom::Viewport& viewport, bool orthographic) {
  if (view.empty()) throw OptionsError("view: expected 'front', 'side', 'top' or a camera file, got ''");
  if (view == "front" || view == "side" || view == "top")
    return geom::presetCamera(geom::parsePresetView(view), bounds, up, viewport, orthographic);
  std::error_code ec;
  if (!std::filesystem::is_regular_file(view, ec))
    throw OptionsError("view '" + view + "': expected 'front', 'side', 'top' or an existing camera file");
  return readCamera(std::filesystem::path(view));
}

}  // namespace treesketch::io
