// A LAS file for the CLI tests whose records carry the ASPRS noise classes and the withheld flag:
// the Y-shaped test tree (turned Z up, millimetre scale) with some of its points marked as noise,
// and points far out that are withheld.
#pragma once

#include <cmath>
#include <cstdint>
#include <string>

#include "io/io_test_util.h"
#include "skeleton/synthetic_tree.h"

namespace treesketch::test {

struct MarkedLas {
  std::string bytes;
  std::size_t treePoints = 0;  ///< the tree's points (the cloud read back)
  std::size_t marked = 0;      ///< of them, classified 7 or 18
  std::size_t withheld = 0;    ///< the far points, flagged withheld
};

/// Every `every`-th point of the tree classified 7 and 18 in turn (the others 1), and five points
/// a kilometre out flagged withheld, in point data record format `format` (LAS 1.2 for 0-5, 1.4
/// for 6-10).
inline MarkedLas markedTreeLas(int format, std::size_t every = 40) {
  const geom::PointCloud tree = sampleCylinders(yTree(), 0.02, 0.003, 7);
  io::testing::LasSpec s;
  s.versionMinor = format >= 6 ? 4 : 2;
  s.pointFormat = format;
  auto mm = [](double v) { return static_cast<std::int32_t>(std::lround(v * 1000)); };
  for (const geom::Vec3& p : tree.positions) s.points.push_back({mm(p.x()), mm(-p.z()), mm(p.y())});  // Y up -> Z up
  MarkedLas out;
  out.treePoints = tree.size();
  out.withheld = 5;
  for (std::size_t k = 0; k < out.withheld; ++k) s.points.push_back({mm(1000.0 + k), 0, mm(1.0 * k)});
  out.bytes = io::testing::buildLas(s);
  for (std::size_t i = 0; i < tree.size(); ++i) {
    std::uint8_t cls = 1;
    if (i % every == 0) cls = (out.marked++ % 2) ? 18 : 7;
    io::testing::setLasClass(out.bytes, s, i, cls);
  }
  for (std::size_t i = tree.size(); i < s.points.size(); ++i)
    io::testing::setLasClass(out.bytes, s, i, 1, io::testing::kLasWithheld);
  return out;
}

}  // namespace treesketch::test
