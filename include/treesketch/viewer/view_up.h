// The viewer's up direction: any of ±X, ±Y, ±Z, so a cloud whose up is not the one assumed can be
// stood upright from the window without touching the data or the sketch (the view, the presets
// and the height colouring follow it). The library's own up axis (geom::UpAxis: Y or Z, used by
// the automatic sketches and written into sketch files) is the direction's axis when it is +Y or +Z.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "treesketch/geom/point_cloud.h"
#include "treesketch/geom/types.h"
#include "treesketch/render/image.h"

namespace treesketch::viewer {

enum class UpDirection { PosX, NegX, PosY, NegY, PosZ, NegZ };

/// "+x" "-x" "+y" "-y" "+z" "-z".
const char* toString(UpDirection d);
/// Parses the names above (also "x" "y" "z" for the + directions, any case); throws OptionsError.
UpDirection parseUpDirection(const std::string& s);
/// The unit vector of the direction (world frame).
geom::Vec3 upDirectionVector(UpDirection d);
/// +Y or +Z for the library's axis; the others have none (nullopt).
std::optional<geom::UpAxis> libraryUpAxis(UpDirection d);
UpDirection toUpDirection(geom::UpAxis up);

/// The window's choice of up for a loaded cloud: `option` is --up as given ("" when not given;
/// any name parseUpDirection takes). The library's rule decides the axis (io::chooseUpAxis: --up,
/// else the file's declaration, else Z); `demo` (the built-in Y-up tree) makes the default Y. A
/// direction the library has no axis for (-z, +x, ...) sets only the view's up.
struct ViewUpChoice {
  geom::UpAxis axis = geom::UpAxis::Z;  ///< for setCloud
  UpDirection view = UpDirection::PosZ;
  std::string reason;  ///< "--up z", "the file declares y", ...
};
ViewUpChoice chooseViewUp(const std::string& option, const geom::PointCloud& cloud, bool demo);

/// Whether a cloud with these bounds looks lying down under `up`: its extent along up is less
/// than 0.7 times its largest horizontal extent (a standing tree is rarely flatter; a felled or
/// wrongly oriented one is). Returns the warning to show ("" when it looks upright).
/// Empty bounds: "".
std::string lyingDownWarning(const geom::BBox& bounds, UpDirection up);

/// One colour per point by its height along `up` (render::viridis over the cloud's height range,
/// as render::heightColors does for +Y/+Z). `range` (if given) receives [lowest, highest].
std::vector<render::Rgb> heightColorsAlong(const geom::PointCloud& cloud, UpDirection up,
                                           std::pair<double, double>* range = nullptr);

}  // namespace treesketch::viewer
