// Point clouds: positions plus optional per-point attributes from the scanner.
//
// Positions are stored in double precision. Real scans come in projected coordinates (UTM
// eastings ~ 5e5 m, elevations ~ 250 m); a float keeps only ~ 0.03 m at 5e5, a double keeps
// nanometres. Doubles cost 24 bytes a point (29 MB for the thesis's largest 1.18 M-point cloud),
// which is affordable here and saves every algorithm from handling an offset.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <vector>

#include "treesketch/geom/types.h"

namespace treesketch::geom {

struct PointCloud {
  std::vector<Vec3> positions;
  /// Optional: index of the scanner station that produced each point (TLS pattern); empty or
  /// one per point.
  std::vector<std::int32_t> station;
  /// Optional: index of the input mesh each point was sampled from (scanner); empty or one per
  /// point.
  std::vector<std::int32_t> meshId;
  /// Optional: position of the scanner that measured each point (its ray's origin, world
  /// coordinates, after any registration); empty or one per point. Per point rather than per
  /// station because the sphere pattern fires every ray from its own origin, and because that is
  /// how other tools read a sensor position from a PLY (three scalar fields, see io/ply.h).
  std::vector<Vec3> scanner;
  /// Optional: the return's intensity as the file gives it (LAS: 0–65535; a text column or a PLY
  /// `intensity` / `scalar_Intensity` property: its value); empty or one per point.
  std::vector<float> intensity;
  /// Optional: the point's colour, 8 bits a channel (LAS stores 16: see io/las.h for the scaling);
  /// empty or one per point.
  std::vector<std::array<std::uint8_t, 3>> color;
  /// Optional: the ASPRS classification code (LAS; a text column or PLY property named
  /// `classification`); empty or one per point.
  std::vector<std::uint8_t> classification;
  /// Optional: the up axis the file declares (LAS: Z by its specification; a PLY written by
  /// treesketch: its `comment up_axis y|z` line), or the producer's (a synthetic scan of a Y-up
  /// tree). Empty when nothing says; io/up_axis.h then picks the field's convention (Z).
  std::optional<UpAxis> up;

  std::size_t size() const { return positions.size(); }
  bool empty() const { return positions.empty(); }
  BBox bounds() const;
  /// Appends all points (and attributes, when both clouds have them) of `other`.
  void append(const PointCloud& other);
  /// Throws OptionsError when an attribute array is non-empty but not one per point.
  void checkConsistent() const;
};

}  // namespace treesketch::geom
