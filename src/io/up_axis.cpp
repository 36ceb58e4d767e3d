// The up-axis rule (see the header).
#include "treesketch/io/up_axis.h"

namespace treesketch::io {

UpAxisChoice chooseUpAxis(const std::string& option, const geom::PointCloud& cloud) {
  UpAxisChoice c;
  if (!option.empty()) {
    c.up = geom::parseUpAxis(option);
    c.reason = std::string("--up ") + geom::toString(c.up);
  } else if (cloud.up) {
    c.up = *cloud.up;
    c.reason = std::string(geom::toString(c.up)) + ", as the file declares";
  } else {
    c.up = geom::UpAxis::Z;
    c.reason = "z, the default for clouds that do not declare their up (field convention; --up y to change)";
  }
  return c;
}

}  // namespace treesketch::io
