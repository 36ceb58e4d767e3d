// Internal: an open-addressing hash map from packed voxel coordinates to voxel indices, and the
// packing itself. Faster than std::unordered_map for the millions of look-ups a voxel graph makes.
#pragma once

#include <cmath>
#include <cstdint>
#include <vector>

#include "treesketch/geom/types.h"

namespace treesketch::skeleton::detail {

/// Voxel coordinates are packed 21 bits per axis; the grid must be below 2^21 voxels per axis.
constexpr std::int64_t kAxisCells = std::int64_t{1} << 21;

inline std::uint64_t packKey(std::int64_t x, std::int64_t y, std::int64_t z) {
  return (static_cast<std::uint64_t>(x) << 42) | (static_cast<std::uint64_t>(y) << 21) | static_cast<std::uint64_t>(z);
}
inline void unpackKey(std::uint64_t key, std::int64_t& x, std::int64_t& y, std::int64_t& z) {
  x = static_cast<std::int64_t>(key >> 42);
  y = static_cast<std::int64_t>((key >> 21) & (kAxisCells - 1));
  z = static_cast<std::int64_t>(key & (kAxisCells - 1));
}
/// Integer cell of `p` in a grid with corner `origin` and cell size `cell` (p must be ≥ origin).
inline std::uint64_t cellKey(const geom::Vec3& p, const geom::Vec3& origin, double cell) {
  const geom::Vec3 q = (p - origin) / cell;
  return packKey(static_cast<std::int64_t>(q.x()), static_cast<std::int64_t>(q.y()), static_cast<std::int64_t>(q.z()));
}

class VoxelHash {
 public:
  static constexpr std::uint32_t kMissing = 0xffffffffu;
  explicit VoxelHash(std::size_t expected = 1024) {
    std::size_t cap = 16;
    while (cap < 2 * expected) cap *= 2;
    keys_.assign(cap, kEmpty);
    values_.assign(cap, kMissing);
  }
  std::size_t size() const { return size_; }
  /// Index stored for `key`, or kMissing.
  std::uint32_t find(std::uint64_t key) const {
    const std::size_t mask = keys_.size() - 1;
    for (std::size_t i = slot(key);; i = (i + 1) & mask) {
      if (keys_[i] == key) return values_[i];
      if (keys_[i] == kEmpty) return kMissing;
    }
  }
  /// Returns the index stored for `key`; inserts `value` first if the key is new.
  std::uint32_t findOrInsert(std::uint64_t key, std::uint32_t value) {
    if (2 * (size_ + 1) > keys_.size()) grow();
    const std::size_t mask = keys_.size() - 1;
    for (std::size_t i = slot(key);; i = (i + 1) & mask) {
      if (keys_[i] == key) return values_[i];
      if (keys_[i] == kEmpty) {
        keys_[i] = key;
        values_[i] = value;
        ++size_;
        return value;
      }
    }
  }

 private:
  static constexpr std::uint64_t kEmpty = ~std::uint64_t{0};
  std::size_t slot(std::uint64_t key) const {
    return static_cast<std::size_t>((key * 0x9E3779B97F4A7C15ull) >> 20) & (keys_.size() - 1);
  }
  void grow() {
    std::vector<std::uint64_t> oldKeys = std::move(keys_);
    std::vector<std::uint32_t> oldValues = std::move(values_);
    keys_.assign(oldKeys.size() * 2, kEmpty);
    values_.assign(oldKeys.size() * 2, kMissing);
    size_ = 0;
    for (std::size_t i = 0; i < oldKeys.size(); ++i)
      if (oldKeys[i] != kEmpty) findOrInsert(oldKeys[i], oldValues[i]);
  }
  std::vector<std::uint64_t> keys_;
  std::vector<std::uint32_t> values_;
  std::size_t size_ = 0;
};

}  // namespace treesketch::skeleton::detail
