// LAZ entropy decoding (see laz_arith.h for the sources). The arithmetic coder keeps an interval
// [value, value + length) in 32 bits; a symbol narrows it by its share of the model's
// distribution, and whenever the length falls below 2^24 one more input byte is shifted in.
#include "io/laz_arith.h"

#include <algorithm>

#include "treesketch/util/error.h"

namespace treesketch::io::laz {

namespace {

constexpr std::uint32_t kMinLength = 0x01000000u;  // renormalize below this interval length
constexpr std::uint32_t kBitLengthShift = 13;      // bit models: 13-bit probabilities
constexpr std::uint32_t kBitMaxCount = 1u << kBitLengthShift;
constexpr std::uint32_t kSymLengthShift = 15;  // symbol models: 15-bit distribution
constexpr std::uint32_t kSymMaxCount = 1u << kSymLengthShift;
/// Bytes a decoder may read past its range before the stream counts as truncated: the coder
/// looks up to 4 bytes ahead of the last symbol it needs.
constexpr std::uint32_t kMaxOverrun = 8;

}  // namespace

SymbolModel::SymbolModel(std::uint32_t n) : symbols(n), lastSymbol(n - 1), updateCycle(n) {
  if (n > 16) {
    std::uint32_t tableBits = 3;
    while (n > (1u << (tableBits + 2))) ++tableBits;
    tableSize = 1u << tableBits;
    tableShift = kSymLengthShift - tableBits;
    table.assign(tableSize + 2, 0);
  }
  distribution.assign(n, 0);
  count.assign(n, 1);
  update();
  untilUpdate = updateCycle = (n + 6) >> 1;
}

void SymbolModel::update() {
  totalCount += updateCycle;
  if (totalCount > kSymMaxCount) {
    totalCount = 0;
    for (std::uint32_t k = 0; k < symbols; ++k) totalCount += (count[k] = (count[k] + 1) >> 1);
  }
  const std::uint32_t scale = 0x80000000u / totalCount;
  std::uint32_t sum = 0;
  if (tableSize == 0) {
    for (std::uint32_t k = 0; k < symbols; ++k) {
      distribution[k] = (scale * sum) >> (31 - kSymLengthShift);
      sum += count[k];
    }
  } else {
    std::uint32_t s = 0;
    for (std::uint32_t k = 0; k < symbols; ++k) {
      distribution[k] = (scale * sum) >> (31 - kSymLengthShift);
      sum += count[k];
      const std::uint32_t w = distribution[k] >> tableShift;
      while (s < w) table[++s] = k - 1;
    }
    table[0] = 0;
    while (s <= tableSize) table[++s] = symbols - 1;
  }
  updateCycle = std::min((5 * updateCycle) >> 2, (symbols + 6) << 3);
  untilUpdate = updateCycle;
}

void BitModel::update() {
  bitCount += updateCycle;
  if (bitCount > kBitMaxCount) {
    bitCount = (bitCount + 1) >> 1;
    bit0Count = (bit0Count + 1) >> 1;
    if (bit0Count == bitCount) ++bitCount;
  }
  const std::uint32_t scale = 0x80000000u / bitCount;
  bit0Prob = (bit0Count * scale) >> (31 - kBitLengthShift);
  updateCycle = std::min((5 * updateCycle) >> 2, 64u);
  untilUpdate = updateCycle;
}

ArithmeticDecoder::ArithmeticDecoder(const unsigned char* begin, const unsigned char* end, std::uint64_t fileOffset,
                                     const std::string& source)
    : begin_(begin), p_(begin), end_(end), fileOffset_(fileOffset), source_(&source) {}

ArithmeticDecoder ArithmeticDecoder::layer(std::uint32_t size) {
  if (static_cast<std::size_t>(end_ - p_) < size)
    throw InputError(atOffset(*source_, offset(),
                              "a layer of " + std::to_string(size) + " bytes runs past the chunk's end (" +
                                  std::to_string(end_ - p_) + " bytes left), expected it inside the chunk"));
  ArithmeticDecoder d(p_, p_ + size, offset(), *source_);
  p_ += size;
  return d;
}

unsigned char ArithmeticDecoder::pastEnd() {
  if (++overrun_ > kMaxOverrun)
    throw InputError(atOffset(*source_, offset(),
                              "compressed points end early (truncated or corrupted LAZ data), "
                              "expected more bytes of the chunk"));
  return 0;
}

void ArithmeticDecoder::start() {
  value_ = 0;
  for (int i = 0; i < 4; ++i) value_ = (value_ << 8) | nextByte();
  length_ = 0xFFFFFFFFu;
}

void ArithmeticDecoder::readRaw(unsigned char* out, std::size_t n) {
  if (static_cast<std::size_t>(end_ - p_) < n)
    throw InputError(
        atOffset(*source_, static_cast<std::uint64_t>(fileOffset_ + (end_ - begin_)),
                 "compressed points end early: expected " + std::to_string(n) + " bytes of a chunk's first point"));
  std::copy(p_, p_ + n, out);
  p_ += n;
}

std::uint32_t ArithmeticDecoder::readRawU32() {
  unsigned char b[4];
  readRaw(b, 4);
  return std::uint32_t(b[0]) | std::uint32_t(b[1]) << 8 | std::uint32_t(b[2]) << 16 | std::uint32_t(b[3]) << 24;
}

void ArithmeticDecoder::renormalize() {
  do {
    value_ = (value_ << 8) | nextByte();
  } while ((length_ <<= 8) < kMinLength);
}

std::uint32_t ArithmeticDecoder::decodeBit(BitModel& m) {
  const std::uint32_t x = m.bit0Prob * (length_ >> kBitLengthShift);
  const std::uint32_t bit = value_ >= x;
  if (bit == 0) {
    length_ = x;
    ++m.bit0Count;
  } else {
    value_ -= x;
    length_ -= x;
  }
  if (length_ < kMinLength) renormalize();
  if (--m.untilUpdate == 0) m.update();
  return bit;
}

std::uint32_t ArithmeticDecoder::decodeSymbol(SymbolModel& m) {
  std::uint32_t sym, x, y = length_;
  if (m.tableSize) {
    length_ >>= kSymLengthShift;
    const std::uint32_t dv = value_ / length_;
    // A valid stream keeps value < length, so dv < 2^15; the clamp keeps corrupted data in bounds.
    const std::uint32_t t = std::min(dv >> m.tableShift, m.tableSize);
    sym = m.table[t];
    std::uint32_t n = m.table[t + 1] + 1;
    while (n > sym + 1) {
      const std::uint32_t k = (sym + n) >> 1;
      if (m.distribution[k] > dv)
        n = k;
      else
        sym = k;
    }
    x = m.distribution[sym] * length_;
    if (sym != m.lastSymbol) y = m.distribution[sym + 1] * length_;
  } else {
    x = sym = 0;
    length_ >>= kSymLengthShift;
    std::uint32_t n = m.symbols, k = n >> 1;
    do {
      const std::uint32_t z = length_ * m.distribution[k];
      if (z > value_) {
        n = k;
        y = z;
      } else {
        sym = k;
        x = z;
      }
    } while ((k = (sym + n) >> 1) != sym);
  }
  value_ -= x;
  length_ = y - x;
  if (length_ < kMinLength) renormalize();
  ++m.count[sym];
  if (--m.untilUpdate == 0) m.update();
  return sym;
}

std::uint32_t ArithmeticDecoder::readBits(std::uint32_t bits) {
  if (bits > 19) {
    const std::uint32_t low = readShort();
    return (readBits(bits - 16) << 16) | low;
  }
  const std::uint32_t sym = value_ / (length_ >>= bits);
  value_ -= length_ * sym;
  if (length_ < kMinLength) renormalize();
  return sym;
}

std::uint32_t ArithmeticDecoder::readShort() {
  const std::uint32_t sym = value_ / (length_ >>= 16);
  value_ -= length_ * sym;
  if (length_ < kMinLength) renormalize();
  return sym & 0xFFFFu;
}

std::uint32_t ArithmeticDecoder::readInt() {
  const std::uint32_t low = readShort();
  return (readShort() << 16) | low;
}

IntegerDecompressor::IntegerDecompressor(std::uint32_t bits, std::uint32_t contexts, std::uint32_t bitsHigh,
                                         std::uint32_t range)
    : bitsHigh_(bitsHigh) {
  if (range) {
    corrBits_ = 0;
    corrRange_ = range;
    for (std::uint32_t r = range; r; r >>= 1) ++corrBits_;
    if (corrRange_ == (1u << (corrBits_ - 1))) --corrBits_;
    corrMin_ = -static_cast<std::int32_t>(corrRange_ / 2);
  } else if (bits && bits < 32) {
    corrBits_ = bits;
    corrRange_ = 1u << bits;
    corrMin_ = -static_cast<std::int32_t>(corrRange_ / 2);
  } else {
    corrBits_ = 32;
    corrRange_ = 0;
    corrMin_ = INT32_MIN;
  }
  bitsModels_.resize(contexts);
  correctors_.resize(corrBits_);
}

std::int32_t IntegerDecompressor::decompress(ArithmeticDecoder& dec, std::int32_t pred, std::uint32_t context) {
  // Wrapping arithmetic, as the encoder's: the sum is taken modulo the range of the numbers.
  std::int64_t real =
      static_cast<std::int64_t>(pred) + readCorrector(dec, lazyModel(bitsModels_[context], corrBits_ + 1));
  if (corrRange_) {
    if (real < 0)
      real += corrRange_;
    else if (real >= static_cast<std::int64_t>(corrRange_))
      real -= corrRange_;
  }
  return static_cast<std::int32_t>(static_cast<std::uint32_t>(real));
}

std::int32_t IntegerDecompressor::readCorrector(ArithmeticDecoder& dec, SymbolModel& bitsModel) {
  k_ = dec.decodeSymbol(bitsModel);
  if (k_ == 0) return static_cast<std::int32_t>(dec.decodeBit(corrector0_));  // 0 or 1
  if (k_ >= 32) return corrMin_;
  // The model of k-bit corrections has 2^k symbols, or 2^bitsHigh for the high bits of wider ones.
  SymbolModel& m = lazyModel(correctors_[k_ - 1], 1u << std::min(k_, bitsHigh_));
  std::int64_t c;
  if (k_ <= bitsHigh_) {
    c = dec.decodeSymbol(m);
  } else {
    const std::uint32_t lowBits = k_ - bitsHigh_;
    c = (static_cast<std::int64_t>(dec.decodeSymbol(m)) << lowBits) | dec.readBits(lowBits);
  }
  // c in [0, 2^k): the upper half maps to [2^(k-1) + 1, 2^k], the lower to [-(2^k - 1), -2^(k-1)].
  if (c >= (std::int64_t(1) << (k_ - 1)))
    c += 1;
  else
    c -= (std::int64_t(1) << k_) - 1;
  return static_cast<std::int32_t>(static_cast<std::uint32_t>(c));
}

}  // namespace treesketch::io::laz
