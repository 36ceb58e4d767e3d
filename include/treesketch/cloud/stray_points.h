// Stray points: the points of a tree's cloud that lie far from the tree (a return off a bird, a
// dust particle, a mis-registered station, a coordinate typed wrong), set aside before modelling,
// as TreeQSM's filtering and CloudCompare's noise filters do. Two rules, both at a distance
// derived from the cloud's own point spacing (nothing assumes a scanner or metres):
//   1. connected components: points closer than the linking distance are joined; the components
//      holding the bulk of the points (the largest, and any with a set share of them) are kept,
//      and so is any other component within a few linking distances of them (a twig behind an
//      occlusion gap); every other component is far from the tree;
//   2. a radius rule (optional, off by default): a component of fewer than a few points is set
//      aside even near the tree.
// Everything is done on hashed grids in O(n): no k-d tree over millions of points. Points the
// file itself marks as noise (ASPRS classes 7 and 18, as vendors' pipelines write them) are set
// aside on the file's word, before any rule is measured (findMarkedNoise), and so are points that
// repeat an earlier point's position exactly (findRepeatedPoints).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "treesketch/geom/point_cloud.h"

namespace treesketch::cloud {

struct StrayPointOptions {
  bool enabled = true;
  /// The spacing is measured inside the box of the [q, 1 − q] quantiles of each coordinate, so
  /// that strays (far fewer than 1 % of the points) cannot stretch it.
  double coreQuantile = 0.01;
  /// The spacing's measuring cells are the core box's diagonal over this: coarse enough to hold
  /// many points each, fine enough to follow the tree's surfaces.
  double spacingCellsPerDiagonal = 256.0;
  /// Linking distance = this many point spacings. 20: a scanned surface is joined across a
  /// missed scan line or two and across the sparse side of a branch; a real tree is one or a few
  /// large components at this distance.
  double linkSpacings = 20.0;
  /// A component holding at least this share of the points is part of the tree wherever it is
  /// (a second stem, a limb cut off by an occlusion).
  double bulkShare = 0.01;
  /// A smaller component is kept when it lies within this many linking distances of the bulk
  /// (a twig past an occlusion gap), and set aside beyond.
  double nearLinks = 5.0;
  /// The radius rule (CloudCompare's and PCL's radius outlier removal): a component of fewer
  /// points than this is set aside even near the tree. 1 = off, the default: on the thesis's
  /// sparse sphere scans a lone point near the tree is a real twig's return (3 set aside 35 of
  /// 25,144 points of a clean scan, 2 set aside 19, and the model's stem moved), and a point that
  /// near does not stretch the model as a far one does.
  int minComponentPoints = 1;
  /// When the rules would set aside more than this share of the points, the cloud is sparser than
  /// its measured spacing says (scattered returns, not a scanned surface) and nothing is set aside:
  /// strays are a handful of points, never a tenth of a tree.
  double maxShare = 0.1;
};

/// ASPRS classification codes (LAS 1.4 R15, table 17) a file uses for noise: 7 "low point
/// (noise)" (also LAS 1.0–1.3) and 18 "high noise" (LAS 1.4).
inline constexpr std::uint8_t kLowNoiseClass = 7;
inline constexpr std::uint8_t kHighNoiseClass = 18;

struct MarkedNoiseOptions {
  /// Set aside the points the file classifies as noise (kLowNoiseClass, kHighNoiseClass). On by
  /// default: a vendor's pipeline marks returns off dust, birds and multipath this way, and a
  /// low point under the terrain or a high one over the crown stretches the model as a stray does.
  bool enabled = true;
};

/// Why a point was set aside: far from the tree, isolated near it, the ground under it (ground.h),
/// marked as noise by the file (findMarkedNoise), or a repeat of an earlier point (findRepeatedPoints).
enum class StrayReason : std::uint8_t { Far, Isolated, Ground, MarkedNoise, Repeated };

struct StrayPoints {
  /// Indices into the input cloud, increasing: the points set aside, and why (one per index).
  std::vector<std::uint32_t> setAside;
  std::vector<StrayReason> reasons;
  std::size_t far = 0, isolated = 0, ground = 0, markedNoise = 0, repeated = 0;  ///< counts by reason
  /// The measured point spacing and the linking distance, in the cloud's units (0 when nothing
  /// was measured: the rule was off, or the cloud too small or of zero extent).
  double spacing = 0, linkDistance = 0;
  std::size_t components = 0;  ///< connected components at the linking distance
  /// The rules would have set aside more than maxShare of the points, so none was.
  bool tooSparse = false;
  std::size_t count() const { return setAside.size(); }
  bool empty() const { return setAside.empty(); }
};

/// Finds the stray points of `cloud` (positions in any units; the rules scale with its spacing).
/// A cloud of fewer than 16 points, of zero extent, or with the rule off
/// gives no stray point, and so does one where the rules would set aside more than maxShare of the
/// points (tooSparse). Never sets aside the largest component. Non-finite positions are not
/// expected (the readers refuse them); such a point is set aside as far. Throws OptionsError for
/// an option out of range.
StrayPoints findStrayPoints(const geom::PointCloud& cloud, const StrayPointOptions& options = {});

/// The points of `cloud` whose classification is kLowNoiseClass or kHighNoiseClass (indices,
/// increasing). None when the cloud carries no classification or the option is off.
std::vector<std::uint32_t> findMarkedNoise(const geom::PointCloud& cloud, const MarkedNoiseOptions& options = {});

/// The points of `cloud` at exactly the position of an earlier point (indices, increasing; the
/// first of each position is kept). A repeat tells nothing of the surface: a file written twice, a
/// merged scan's overlap copied, two returns rounded to one position by a LAS file's scale. Left
/// in, repeats made a cloud look denser than its surfaces are sampled, and the automatic model's
/// voxels, set by that density, finer: four leaf-off clouds written twice got other models (2-14
/// points more of their points within 2 cm, 3-21 % less volume).
std::vector<std::uint32_t> findRepeatedPoints(const geom::PointCloud& cloud);

/// Adds `points` (indices into the same cloud, increasing) to the points set aside, for `reason`
/// (counted under it); a point already set aside keeps its reason.
void addSetAside(StrayPoints& strays, const std::vector<std::uint32_t>& points, StrayReason reason);
/// addSetAside(strays, ground, StrayReason::Ground).
void addGround(StrayPoints& strays, const std::vector<std::uint32_t>& ground);
/// The points set aside for `reason` (indices, increasing).
std::vector<std::uint32_t> setAsideFor(const StrayPoints& strays, StrayReason reason);

/// The cloud's point spacing as findStrayPoints measures it (0 for a cloud of zero extent).
double measurePointSpacing(const geom::PointCloud& cloud, const StrayPointOptions& options = {});

/// The points of `cloud` at `indices` (increasing), with their attributes and the cloud's up.
geom::PointCloud selectPoints(const geom::PointCloud& cloud, const std::vector<std::uint32_t>& indices);

/// The points of `cloud` not in `strays.setAside` (the cloud itself when none is).
geom::PointCloud keptPoints(const geom::PointCloud& cloud, const StrayPoints& strays);

/// One line for a person: "N stray points set aside (F far from the tree, I isolated; linking
/// distance L)", with the points marked as noise and the ground first when there are any
/// ("N points set aside (M marked as noise by the file, G on the ground, ...)"), or "no stray
/// point set aside".
std::string strayPointsLine(const StrayPoints& strays);

}  // namespace treesketch::cloud
