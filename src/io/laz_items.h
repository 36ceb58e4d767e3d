// The item decoders of LAZ: each turns its part of a LAS point record back from the compressed
// stream, predicting from the previous record of the same chunk. Point-wise items (point formats
// 0–5, "version 2"): POINT10, GPSTIME11, RGB12, BYTE share one arithmetic decoder. Layered items
// (point formats 6–10, "version 3"): POINT14, RGB14, RGBNIR14, BYTE14 keep each field group in its
// own layer with its own decoder (laz_items14.cpp). Sources: the LASzip specification and the
// LAS 1.4 R15 record layouts.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "io/laz_arith.h"

namespace treesketch::io::laz {

/// Little-endian fields of a LAS record, read and written in place.
inline std::uint16_t loadU16(const unsigned char* p) { return static_cast<std::uint16_t>(p[0] | p[1] << 8); }
inline std::uint32_t loadU32(const unsigned char* p) {
  return std::uint32_t(p[0]) | std::uint32_t(p[1]) << 8 | std::uint32_t(p[2]) << 16 | std::uint32_t(p[3]) << 24;
}
inline void storeU16(unsigned char* p, std::uint32_t v) {
  p[0] = static_cast<unsigned char>(v);
  p[1] = static_cast<unsigned char>(v >> 8);
}
inline void storeU32(unsigned char* p, std::uint32_t v) {
  for (int i = 0; i < 4; ++i) p[i] = static_cast<unsigned char>(v >> (8 * i));
}

/// LASzip item types (the "type" field of the LASzip VLR's item list).
enum ItemType : std::uint16_t {
  kByte = 0,
  kPoint10 = 6,
  kGpsTime11 = 7,
  kRgb12 = 8,
  kWavePacket13 = 9,
  kPoint14 = 10,
  kRgb14 = 11,
  kRgbNir14 = 12,
  kWavePacket14 = 13,
  kByte14 = 14,
};

struct Item {
  std::uint16_t type = 0, size = 0, version = 0;
};

/// Name of an item type for messages ("POINT10", "BYTE14", "type 99").
std::string itemName(std::uint16_t type);

/// The median of the last five values added (all zero at first), as the format keeps it.
class Median5 {
 public:
  void add(std::int32_t v);
  std::int32_t get() const { return v_[2]; }

 private:
  std::array<std::int32_t, 5> v_{};
  bool high_ = true;
};

/// Decodes one RGB triple (16 bits a channel) predicted from `last` with the models of RGB12 v2
/// and RGB14 v3: a 128-symbol "which bytes changed" model and six 256-symbol byte models.
void decodeRgb(ArithmeticDecoder& dec, SymbolModel& used, std::array<std::unique_ptr<SymbolModel>, 6>& diff,
               const std::array<std::uint32_t, 3>& last, std::array<std::uint32_t, 3>& out);

/// The GPS time predictor of GPSTIME11 v2 and POINT14 v3: up to four interleaved sequences of
/// times (as 64-bit patterns), each predicted from its last difference or a multiple of it.
struct GpsTimeState {
  std::uint32_t cur = 0, next = 0;
  std::array<std::uint64_t, 4> last{};
  std::array<std::int32_t, 4> diff{}, extreme{};
  /// Decodes the next time into last[cur]. `layered`: the codes of version 3 (POINT14), whose
  /// models have 515 and 5 symbols (version 2: 516 and 6).
  void decode(ArithmeticDecoder& dec, SymbolModel& multi, SymbolModel& zeroDiff, IntegerDecompressor& ic, bool layered);
};

/// A point-wise item: `first` takes the raw bytes of a chunk's first record, `next` decodes the
/// following records.
class PointwiseItem {
 public:
  virtual ~PointwiseItem() = default;
  virtual void first(const unsigned char* raw) = 0;
  virtual void next(ArithmeticDecoder& dec, unsigned char* out) = 0;
};

/// The decoder of a point-wise item of version 2 (types POINT10, GPSTIME11, RGB12, BYTE).
/// Precondition: the item was validated (type and version known).
std::unique_ptr<PointwiseItem> makePointwiseItem(const Item& item);

/// A layered item. A chunk gives it the raw bytes of its first record (`first`), then the byte
/// counts of its layers (`readSizes`, from the chunk header), then the layers (`startLayers`
/// takes them from `in` in the same order); `next` decodes each following record. `channel` is
/// the record's scanner channel (0–3): POINT14 sets it, the other items use it.
class LayeredItem {
 public:
  virtual ~LayeredItem() = default;
  virtual void first(const unsigned char* raw, unsigned& channel) = 0;
  virtual void readSizes(ArithmeticDecoder& in) = 0;
  virtual void startLayers(ArithmeticDecoder& in) = 0;
  virtual void next(unsigned char* out, unsigned& channel) = 0;
};

/// The decoder of a layered item of version 3 (POINT14, RGB14, RGBNIR14, BYTE14).
/// Precondition: the item was validated (type and version known).
std::unique_ptr<LayeredItem> makeLayeredItem(const Item& item);

}  // namespace treesketch::io::laz
