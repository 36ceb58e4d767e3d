// The camera named by a `--view` argument (the CLI's `sketch auto` and the evaluation): a preset
// view of the cloud's bounding box, or a camera file. It lives in io, not in sketch, because it
// may read a file: sketch is the model and never depends on io (see io/sketch_file.h).
#pragma once

#include <string>

#include "treesketch/geom/camera.h"

namespace treesketch::io {

/// `view` is "front", "side" or "top": geom::presetCamera framing `bounds` (world) with `up`,
/// `viewport` and `orthographic`. Anything else is the path of a camera file
/// ({"view":[16],"projection":[16],"viewport":[4]}, see io/sketch_file.h), read as is (`bounds`,
/// `viewport` and `orthographic` are then ignored). Throws OptionsError for an empty box with a
/// preset, or a `view` that is neither a preset nor an existing file (a typo such as "frnt" is a
/// usage error); InputError for a camera file that cannot be read or is bad.
geom::Camera cameraForView(const std::string& view, const geom::BBox& bounds, geom::UpAxis up,
                           const geom::Viewport& viewport = {}, bool orthographic = false);

}  // namespace treesketch::io
