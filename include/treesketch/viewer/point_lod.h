// The cloud's level of detail while the view moves: the points are uploaded to the GPU in a fixed
// shuffled order, so that any first n of them are a uniform random subsample of the cloud; while
// orbiting, panning or zooming the window draws only the first n (a budget it adapts to the frame
// time), and the whole cloud once the view is still. Plain C++, no GL: the renderer uploads what
// this produces, and the benchmark times it.
#pragma once

#include <cstdint>
#include <vector>

#include "treesketch/geom/point_cloud.h"
#include "treesketch/render/image.h"

namespace treesketch::viewer {

class PointLod {
 public:
  /// A fixed shuffle of `count` points (same seed, same order: frames do not flicker).
  void build(std::size_t count, std::uint64_t seed = 0x5eed);
  std::size_t size() const { return order_.size(); }
  const std::vector<std::uint32_t>& order() const { return order_; }
  /// Positions in the shuffled order, minus `origin` (float precision near the cloud), xyz floats.
  void positions(const geom::PointCloud& cloud, const geom::Vec3& origin, std::vector<float>& out) const;
  /// Colours in the shuffled order (3 bytes a point); `colors` has one per point.
  void colors(const std::vector<render::Rgb>& colors, std::vector<std::uint8_t>& out) const;
  /// The same colours in the shuffled order, kept between calls: a call rewrites only the points
  /// whose colour differs from the last call's (a sequential pass over `colors`, instead of a
  /// gather in random order over all of them; an edit in the distance colouring changes a few
  /// thousand). `colors` has one per point; the first call, or one after build(), fills it all.
  const std::vector<std::uint8_t>& keptColors(const std::vector<render::Rgb>& colors);

 private:
  std::vector<std::uint32_t> order_;
  std::vector<std::uint32_t> place_;  ///< point -> its place in order_
  std::vector<render::Rgb> keptFrom_;  ///< the colours keptColors() was last given
  std::vector<std::uint8_t> kept_;     ///< and them in the shuffled order
};

/// The point budget for the next moving frame: scales `current` by target / measured frame time,
/// within [minPoints, total]; a measured time <= 0 keeps it.
std::size_t adaptPointBudget(std::size_t current, double frameMs, double targetMs, std::size_t minPoints,
                             std::size_t total);

}  // namespace treesketch::viewer
