// The stem, tracked upward from its base by circle fits (private to the skeleton module).
//
// Level sets see a thick stem one bin at a time. Where the stem is scanned sparsely (the thesis's
// sphere pattern puts few rays on a trunk's base; a station sees one side of it) a bin's ring
// holds a handful of voxels that the graph does not join: the ring breaks into arcs, each arc goes
// on as a thin chain up the stem's surface ("bark chains"), and the stem's own node sits on
// whichever arc it kept, one-sided: a corkscrew of tubes thinner than the stem. A stem's cross-
// sections, though, are circles, and a slab one radius tall holds enough of them to fit one
// even when no single bin does. So the stem is followed from its base: a circle fitted to the
// slab's voxels (RANSAC, thesis §4.4), a step of one radius along the axis of the last centres,
// the next slab, until the circle no longer explains the slab (the crown's first fork, foliage,
// the top). When the root region shows no stem (a stem under two voxels in radius, or one whose
// lowest branches reach the ground beside and below its foot), the stem is looked for where the
// tree is most continuously vertical, if the root region itself is not (a conifer's branch tips on
// the ground), and followed from there both ways; there, a slab where a whorl's limbs leave the
// stem is looked at again as the first surface seen from the axis (the bark, the limbs behind
// it). level_sets.cpp then joins the voxels of each level set that lie in this tube into one
// piece: one node per level on the stem, centred on its axis, with the stem's radius.
#pragma once

#include <cstdint>
#include <vector>

#include "treesketch/geom/types.h"
#include "treesketch/skeleton/skeleton.h"
#include "treesketch/skeleton/voxel_graph.h"

namespace treesketch::skeleton::detail {

struct StemSample {
  geom::Vec3 centre = geom::Vec3::Zero();
  double radius = 0;
};

/// The tracked stem, from its base up: at least three samples, or none (no ring at the base and no
/// stem found beside the root region: a stem too thin for a ring standing on it, a bush's stems,
/// too few voxels). `root`: the Dijkstra sources (the base region), `up`: the tree's up axis;
/// `besideRoot`, when given, is set to whether the stem was found beside the root region.
std::vector<StemSample> trackStem(const VoxelGraph& g, const std::vector<std::uint32_t>& root, geom::UpAxis up,
                                  bool* besideRoot = nullptr);

/// The stem samples kept in `levels` (GeodesicLevels::stemCentres, stemRadii), base first.
std::vector<StemSample> trackedStem(const GeodesicLevels& levels);

/// Per voxel: 1 when it lies in the tracked stem's tube (within its radius plus a margin of the
/// axis, between the first and last samples' slabs).
std::vector<char> stemTube(const VoxelGraph& g, const std::vector<StemSample>& stem);

/// Whether `p` lies in the tracked stem's tube (as stemTube; `voxel`: the graph's voxel size).
bool inStemTube(const std::vector<StemSample>& stem, double voxel, const geom::Vec3& p);

/// Whether most of the root region's voxels lie in the tracked stem's tube: false when the stem
/// was found beside the root region (a conifer's lowest branches reach below its foot).
bool rootOnStem(const VoxelGraph& g, const std::vector<StemSample>& stem, const std::vector<std::uint32_t>& root);

/// The stem's foot: the voxels of its tube (those marked in `reachable`) within `height` (world
/// units) of the lowest of them along `up`; the Dijkstra sources when the stem stands beside the
/// root region. Empty when no reachable voxel is in the tube.
std::vector<std::uint32_t> stemFoot(const VoxelGraph& g, const std::vector<StemSample>& stem,
                                    const std::vector<char>& reachable, geom::UpAxis up, double height);

/// The point of the tracked stem's axis nearest `p`, with the stem's radius there (between
/// samples linearly; past the ends, on the end segments' lines, with the end's radius).
StemSample stemAt(const std::vector<StemSample>& stem, const geom::Vec3& p);

}  // namespace treesketch::skeleton::detail
