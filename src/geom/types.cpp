#include "treesketch/geom/types.h"

#include "treesketch/util/error.h"
#include "treesketch/util/text.h"

namespace treesketch::geom {

UpAxis parseUpAxis(const std::string& s) {
  const std::string l = lowercase(s);
  if (l == "y") return UpAxis::Y;
  if (l == "z") return UpAxis::Z;
  throw OptionsError("up axis must be 'y' or 'z', got '" + s + "'");
}

Vec3 anyPerpendicular(const Vec3& n) {
  Vec3 a = n.normalized();
  Vec3 helper = std::abs(a.x()) < 0.9 ? Vec3(1, 0, 0) : Vec3(0, 1, 0);
  return a.cross(helper).normalized();
}

}  // namespace treesketch::geom
