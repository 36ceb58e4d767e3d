// The entropy decoder of LASzip-compressed LAS (LAZ): an arithmetic (range) decoder with 32-bit
// state, adaptive models for multi-symbol alphabets and single bits, and the "integer
// compressor" that codes a number as a correction to a prediction (the number of significant bits
// of the correction first, then its value). Written from the LASzip specification (M. Isenburg,
// "LASzip: lossless compression of LiDAR data", 2013) and A. Said's description of the coder
// ("Introduction to arithmetic coding", HP Labs HPL-2004-76), which LASzip follows; the
// constants below are the format's and must not change.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace treesketch::io::laz {

/// An adaptive model of an alphabet of 2..2048 symbols: counts, their cumulative distribution
/// (15-bit fixed point) and, above 16 symbols, a look-up table to start the symbol search.
struct SymbolModel {
  explicit SymbolModel(std::uint32_t symbols);
  /// Halves the counts when they grow too large, recomputes the distribution and the table and
  /// schedules the next update (more rarely each time).
  void update();

  std::uint32_t symbols, lastSymbol;
  std::uint32_t totalCount = 0, updateCycle, untilUpdate;
  std::uint32_t tableSize = 0, tableShift = 0;
  std::vector<std::uint32_t> distribution, count, table;
};

/// `m`, made with `symbols` symbols if it does not exist yet.
inline SymbolModel& lazyModel(std::unique_ptr<SymbolModel>& m, std::uint32_t symbols) {
  if (!m) m = std::make_unique<SymbolModel>(symbols);
  return *m;
}

/// An adaptive model of one bit.
struct BitModel {
  void update();
  std::uint32_t updateCycle = 4, untilUpdate = 4;
  std::uint32_t bit0Prob = 1u << 12, bit0Count = 1, bitCount = 2;
};

/// Decodes from the bytes [begin, end) of a file. Reading past `end` (a truncated or corrupted
/// stream) yields zero bytes; past a few bytes of that the decoder throws InputError naming
/// `source` and the file offset where the bytes ran out. Every decoded symbol is within its
/// model's alphabet whatever the input, so corrupted data gives wrong values, never a bad access.
class ArithmeticDecoder {
 public:
  ArithmeticDecoder(const unsigned char* begin, const unsigned char* end, std::uint64_t fileOffset,
                    const std::string& source);
  /// Reads the 4 bytes that start the coder (after any raw bytes read with readRaw).
  void start();
  /// Copies `n` bytes verbatim from the input (the raw first point of a chunk).
  void readRaw(unsigned char* out, std::size_t n);
  /// Reads a little-endian uint32 verbatim.
  std::uint32_t readRawU32();
  /// A decoder over the next `size` bytes (one layer of a layered chunk, not yet started), moving
  /// this one past them. InputError when fewer bytes are left.
  ArithmeticDecoder layer(std::uint32_t size);

  std::uint32_t decodeBit(BitModel& m);
  std::uint32_t decodeSymbol(SymbolModel& m);
  /// `bits` raw bits (1..32) with equal probabilities.
  std::uint32_t readBits(std::uint32_t bits);
  std::uint32_t readShort();
  std::uint32_t readInt();

  /// File offset of the next unread byte.
  std::uint64_t offset() const { return fileOffset_ + static_cast<std::uint64_t>(p_ - begin_); }

 private:
  unsigned char nextByte() {
    if (p_ < end_) return *p_++;
    return pastEnd();
  }
  unsigned char pastEnd();
  void renormalize();

  const unsigned char *begin_, *p_, *end_;
  std::uint64_t fileOffset_;
  const std::string* source_;
  std::uint32_t overrun_ = 0;
  std::uint32_t value_ = 0, length_ = 0xFFFFFFFFu;
};

/// Decodes integers coded as prediction + correction, the correction's bit count coded per
/// context. `bits`: width of the numbers (32: no wrap-around); `contexts`: how many bit-count
/// models; `bitsHigh`: corrections wider than this are split into a modelled high part and raw
/// low bits; `range`: numbers lie in [0, range) when non-zero.
class IntegerDecompressor {
 public:
  explicit IntegerDecompressor(std::uint32_t bits = 16, std::uint32_t contexts = 1, std::uint32_t bitsHigh = 8,
                               std::uint32_t range = 0);
  /// The number predicted by `pred`, using bit-count model `context` (< contexts).
  std::int32_t decompress(ArithmeticDecoder& dec, std::int32_t pred, std::uint32_t context);
  /// Bit count of the last correction (a context for the next number in some items).
  std::uint32_t k() const { return k_; }

 private:
  std::int32_t readCorrector(ArithmeticDecoder& dec, SymbolModel& bitsModel);

  std::uint32_t bitsHigh_, corrBits_, corrRange_;
  std::int32_t corrMin_;
  std::uint32_t k_ = 0;
  // Models are made on first use (a fresh model is the same whenever it is made): most contexts
  // and bit counts never occur in a chunk, and making them all would cost more than decoding.
  std::vector<std::unique_ptr<SymbolModel>> bitsModels_;
  BitModel corrector0_;
  std::vector<std::unique_ptr<SymbolModel>> correctors_;
};

}  // namespace treesketch::io::laz
