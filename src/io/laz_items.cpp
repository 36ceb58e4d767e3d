// Point-wise LAZ items, version 2 (point formats 0–5). Each predicts a record from the previous
// one of its chunk; the tables and contexts are the format's (LASzip specification).
#include "io/laz_items.h"

#include <algorithm>
#include <array>
#include <cstring>

namespace treesketch::io::laz {

namespace {


// Context of a point from its return number r and number of returns n ([n][r]): 0–14 for the
// valid pairs, the rest spread over the same range for files that fill them differently.
constexpr unsigned char kReturnContext[8][8] = {{15, 14, 13, 12, 11, 10, 9, 8},  {14, 0, 1, 3, 6, 10, 10, 9},
                                                {13, 1, 2, 4, 7, 11, 11, 10},    {12, 3, 4, 5, 8, 12, 12, 11},
                                                {11, 6, 7, 8, 9, 13, 13, 12},    {10, 10, 11, 12, 13, 14, 14, 13},
                                                {9, 10, 11, 12, 13, 14, 15, 14}, {8, 9, 10, 11, 12, 13, 14, 15}};
// The z context: how far the return is from the last one, |n - r| ([n][r]).
constexpr unsigned char kReturnLevel[8][8] = {
    {0, 1, 2, 3, 4, 5, 6, 7}, {1, 0, 1, 2, 3, 4, 5, 6}, {2, 1, 0, 1, 2, 3, 4, 5}, {3, 2, 1, 0, 1, 2, 3, 4},
    {4, 3, 2, 1, 0, 1, 2, 3}, {5, 4, 3, 2, 1, 0, 1, 2}, {6, 5, 4, 3, 2, 1, 0, 1}, {7, 6, 5, 4, 3, 2, 1, 0}};

constexpr std::uint32_t kGpsMulti = 500;
constexpr std::int32_t kGpsMultiMinus = -10;
constexpr std::uint32_t kGpsMultiUnchanged = kGpsMulti - kGpsMultiMinus + 1;  // 511
constexpr std::uint32_t kGpsMultiCodeFull = kGpsMulti - kGpsMultiMinus + 2;   // 512
constexpr std::uint32_t kGpsMultiTotal = kGpsMulti - kGpsMultiMinus + 6;      // 516

std::int32_t wrapMul(std::int32_t a, std::int32_t b) {
  return static_cast<std::int32_t>(static_cast<std::uint32_t>(a) * static_cast<std::uint32_t>(b));
}

}  // namespace

void Median5::add(std::int32_t v) {
  // v[] stays sorted; `high` says on which side the oldest value is dropped next.
  if (high_) {
    if (v < v_[2]) {
      v_[4] = v_[3];
      v_[3] = v_[2];
      if (v < v_[0]) {
        v_[2] = v_[1];
        v_[1] = v_[0];
        v_[0] = v;
      } else if (v < v_[1]) {
        v_[2] = v_[1];
        v_[1] = v;
      } else {
        v_[2] = v;
      }
    } else {
      if (v < v_[3]) {
        v_[4] = v_[3];
        v_[3] = v;
      } else {
        v_[4] = v;
      }
      high_ = false;
    }
  } else {
    if (v_[2] < v) {
      v_[0] = v_[1];
      v_[1] = v_[2];
      if (v_[4] < v) {
        v_[2] = v_[3];
        v_[3] = v_[4];
        v_[4] = v;
      } else if (v_[3] < v) {
        v_[2] = v_[3];
        v_[3] = v;
      } else {
        v_[2] = v;
      }
    } else {
      if (v_[1] < v) {
        v_[0] = v_[1];
        v_[1] = v;
      } else {
        v_[0] = v;
      }
      high_ = true;
    }
  }
}

std::string itemName(std::uint16_t type) {
  switch (type) {
    case kByte:
      return "BYTE";
    case kPoint10:
      return "POINT10";
    case kGpsTime11:
      return "GPSTIME11";
    case kRgb12:
      return "RGB12";
    case kWavePacket13:
      return "WAVEPACKET13";
    case kPoint14:
      return "POINT14";
    case kRgb14:
      return "RGB14";
    case kRgbNir14:
      return "RGBNIR14";
    case kWavePacket14:
      return "WAVEPACKET14";
    case kByte14:
      return "BYTE14";
    default:
      return "type " + std::to_string(type);
  }
}

namespace {

/// POINT10 (20 bytes: X Y Z int32, intensity, return byte, classification byte, scan angle rank,
/// user data, point source id).
class Point10Item final : public PointwiseItem {
 public:
  Point10Item() : changed_(64), intensity_(16, 4), pointSource_(16), dx_(32, 2), dy_(32, 22), z_(32, 20) {}

  void first(const unsigned char* raw) override { std::memcpy(last_, raw, 20); }

  void next(ArithmeticDecoder& dec, unsigned char* out) override {
    unsigned char* l = last_;
    const std::uint32_t changed = dec.decodeSymbol(changed_);
    if (changed & 32) l[14] = static_cast<unsigned char>(dec.decodeSymbol(lazyModel(returnByte_[l[14]], 256)));
    const std::uint32_t r = l[14] & 7, n = (l[14] >> 3) & 7;
    const std::uint32_t m = kReturnContext[n][r], lvl = kReturnLevel[n][r];
    if (changed & 16)
      lastIntensity_[m] = static_cast<std::uint16_t>(intensity_.decompress(dec, lastIntensity_[m], m < 3 ? m : 3));
    storeU16(l + 12, lastIntensity_[m]);
    if (changed & 8) l[15] = static_cast<unsigned char>(dec.decodeSymbol(lazyModel(classification_[l[15]], 256)));
    if (changed & 4) {
      const std::uint32_t d = dec.decodeSymbol(lazyModel(scanAngle_[(l[14] >> 6) & 1], 256));
      l[16] = static_cast<unsigned char>(d + l[16]);
    }
    if (changed & 2) l[17] = static_cast<unsigned char>(dec.decodeSymbol(lazyModel(userData_[l[17]], 256)));
    if (changed & 1) storeU16(l + 18, static_cast<std::uint32_t>(pointSource_.decompress(dec, loadU16(l + 18), 0)));

    const std::int32_t dx = dx_.decompress(dec, xMedian_[m].get(), n == 1);
    storeU32(l, loadU32(l) + static_cast<std::uint32_t>(dx));
    xMedian_[m].add(dx);
    std::uint32_t kBits = dx_.k();
    const std::int32_t dy = dy_.decompress(dec, yMedian_[m].get(), (n == 1) + (kBits < 20 ? kBits & ~1u : 20));
    storeU32(l + 4, loadU32(l + 4) + static_cast<std::uint32_t>(dy));
    yMedian_[m].add(dy);
    kBits = (dx_.k() + dy_.k()) / 2;
    const std::int32_t z = z_.decompress(dec, lastHeight_[lvl], (n == 1) + (kBits < 18 ? kBits & ~1u : 18));
    storeU32(l + 8, static_cast<std::uint32_t>(z));
    lastHeight_[lvl] = z;
    std::memcpy(out, l, 20);
  }

 private:
  unsigned char last_[20] = {};
  std::array<std::uint16_t, 16> lastIntensity_{};
  std::array<Median5, 16> xMedian_, yMedian_;
  std::array<std::int32_t, 8> lastHeight_{};
  SymbolModel changed_;
  std::array<std::unique_ptr<SymbolModel>, 2> scanAngle_;
  std::array<std::unique_ptr<SymbolModel>, 256> returnByte_, classification_, userData_;
  IntegerDecompressor intensity_, pointSource_, dx_, dy_, z_;
};

/// GPSTIME11 (8 bytes, a double).
class GpsTime11Item final : public PointwiseItem {
 public:
  GpsTime11Item() : multi_(kGpsMultiTotal), zeroDiff_(6), ic_(32, 9) {}

  void first(const unsigned char* raw) override {
    std::uint64_t v = 0;
    for (int i = 7; i >= 0; --i) v = (v << 8) | raw[i];
    state_.last[0] = v;
  }

  void next(ArithmeticDecoder& dec, unsigned char* out) override {
    state_.decode(dec, multi_, zeroDiff_, ic_, false);
    std::uint64_t v = state_.last[state_.cur];
    for (int i = 0; i < 8; ++i, v >>= 8) out[i] = static_cast<unsigned char>(v);
  }

 private:
  SymbolModel multi_, zeroDiff_;
  IntegerDecompressor ic_;
  GpsTimeState state_;
};

std::uint32_t clampByte(std::int32_t v) { return static_cast<std::uint32_t>(std::clamp(v, 0, 255)); }

/// RGB12 (6 bytes, R G B uint16): which bytes changed, then each changed byte as a difference
/// from the previous one (green and blue predicted from red's change).
class Rgb12Item final : public PointwiseItem {
 public:
  Rgb12Item() : used_(128) {
    for (auto& m : diff_) m = std::make_unique<SymbolModel>(256);
  }
  void first(const unsigned char* raw) override {
    for (int k = 0; k < 3; ++k) last_[k] = loadU16(raw + 2 * k);
  }
  void next(ArithmeticDecoder& dec, unsigned char* out) override {
    std::array<std::uint32_t, 3> c{};
    decodeRgb(dec, used_, diff_, last_, c);
    for (int k = 0; k < 3; ++k) {
      last_[k] = c[k];
      storeU16(out + 2 * k, c[k]);
    }
  }

 private:
  SymbolModel used_;
  std::array<std::unique_ptr<SymbolModel>, 6> diff_;
  std::array<std::uint32_t, 3> last_{};
};

/// BYTE (extra bytes): each byte as a difference from the previous record's.
class ByteItem final : public PointwiseItem {
 public:
  explicit ByteItem(std::size_t n) : last_(n) {
    for (std::size_t i = 0; i < n; ++i) models_.push_back(std::make_unique<SymbolModel>(256));
  }
  void first(const unsigned char* raw) override { std::memcpy(last_.data(), raw, last_.size()); }
  void next(ArithmeticDecoder& dec, unsigned char* out) override {
    for (std::size_t i = 0; i < last_.size(); ++i)
      out[i] = last_[i] = static_cast<unsigned char>(last_[i] + dec.decodeSymbol(*models_[i]));
  }

 private:
  std::vector<unsigned char> last_;
  std::vector<std::unique_ptr<SymbolModel>> models_;
};

}  // namespace

void decodeRgb(ArithmeticDecoder& dec, SymbolModel& used, std::array<std::unique_ptr<SymbolModel>, 6>& diff,
               const std::array<std::uint32_t, 3>& last, std::array<std::uint32_t, 3>& c) {
  const std::uint32_t sym = dec.decodeSymbol(used);
  auto lo = [](std::uint32_t v) { return static_cast<std::int32_t>(v & 0xFF); };
  auto hi = [](std::uint32_t v) { return static_cast<std::int32_t>(v >> 8); };
  auto corr = [&](int k, std::uint32_t pred) { return (dec.decodeSymbol(*diff[k]) + pred) & 0xFF; };
  c[0] = (sym & 1) ? corr(0, last[0] & 0xFF) : last[0] & 0xFF;
  c[0] |= (sym & 2) ? corr(1, last[0] >> 8) << 8 : last[0] & 0xFF00;
  if (sym & 64) {
    std::int32_t d = lo(c[0]) - lo(last[0]);
    c[1] = (sym & 4) ? corr(2, clampByte(d + lo(last[1]))) : last[1] & 0xFF;
    if (sym & 16) {
      d = (d + lo(c[1]) - lo(last[1])) / 2;
      c[2] = corr(4, clampByte(d + lo(last[2])));
    } else {
      c[2] = last[2] & 0xFF;
    }
    d = hi(c[0]) - hi(last[0]);
    c[1] |= (sym & 8) ? corr(3, clampByte(d + hi(last[1]))) << 8 : last[1] & 0xFF00;
    if (sym & 32) {
      d = (d + hi(c[1]) - hi(last[1])) / 2;
      c[2] |= corr(5, clampByte(d + hi(last[2]))) << 8;
    } else {
      c[2] |= last[2] & 0xFF00;
    }
  } else {
    c[1] = c[2] = c[0];
  }
}

void GpsTimeState::decode(ArithmeticDecoder& dec, SymbolModel& multiModel, SymbolModel& zeroDiffModel,
                          IntegerDecompressor& ic, bool layered) {
  auto countExtreme = [&](std::int32_t d) {
    if (++extreme[cur] > 3) {
      diff[cur] = d;
      extreme[cur] = 0;
    }
  };
  // A time that starts a new sequence: its high 32 bits predicted from the current one's, the
  // low 32 raw.
  auto fullTime = [&] {
    next = (next + 1) & 3;
    const auto high = static_cast<std::uint32_t>(
        ic.decompress(dec, static_cast<std::int32_t>(static_cast<std::uint32_t>(last[cur] >> 32)), 8));
    last[next] = (std::uint64_t(high) << 32) | dec.readInt();
    cur = next;
    diff[cur] = 0;
    extreme[cur] = 0;
  };
  auto add = [&](std::int32_t d) { last[cur] += static_cast<std::uint64_t>(static_cast<std::int64_t>(d)); };
  // A switch to another sequence is followed by the code for that sequence (a loop, not
  // recursion, so corrupted data cannot exhaust the stack). Version 3 drops the "unchanged"
  // codes of version 2 (0 after a zero difference, 511 otherwise): its codes are mapped onto
  // version 2's.
  for (;;) {
    if (diff[cur] == 0) {
      std::uint32_t multi = dec.decodeSymbol(zeroDiffModel);
      if (layered) ++multi;
      if (multi == 1) {
        diff[cur] = ic.decompress(dec, 0, 0);
        add(diff[cur]);
        extreme[cur] = 0;
      } else if (multi == 2) {
        fullTime();
      } else if (multi > 2) {
        cur = (cur + multi - 2) & 3;
        continue;
      }
    } else {
      std::uint32_t multi = dec.decodeSymbol(multiModel);
      if (layered && multi >= kGpsMultiUnchanged) ++multi;
      if (multi == 1) {
        add(ic.decompress(dec, diff[cur], 1));
        extreme[cur] = 0;
      } else if (multi < kGpsMultiUnchanged) {
        std::int32_t d;
        if (multi == 0) {
          d = ic.decompress(dec, 0, 7);
          countExtreme(d);
        } else if (multi < kGpsMulti) {
          d = ic.decompress(dec, wrapMul(static_cast<std::int32_t>(multi), diff[cur]), multi < 10 ? 2 : 3);
        } else if (multi == kGpsMulti) {
          d = ic.decompress(dec, wrapMul(kGpsMulti, diff[cur]), 4);
          countExtreme(d);
        } else {
          const std::int32_t mm = static_cast<std::int32_t>(kGpsMulti) - static_cast<std::int32_t>(multi);
          if (mm > kGpsMultiMinus) {
            d = ic.decompress(dec, wrapMul(mm, diff[cur]), 5);
          } else {
            d = ic.decompress(dec, wrapMul(kGpsMultiMinus, diff[cur]), 6);
            countExtreme(d);
          }
        }
        add(d);
      } else if (multi == kGpsMultiCodeFull) {
        fullTime();
      } else if (multi > kGpsMultiCodeFull) {
        cur = (cur + multi - kGpsMultiCodeFull) & 3;
        continue;
      }
    }
    return;
  }
}

std::unique_ptr<PointwiseItem> makePointwiseItem(const Item& item) {
  switch (item.type) {
    case kPoint10:
      return std::make_unique<Point10Item>();
    case kGpsTime11:
      return std::make_unique<GpsTime11Item>();
    case kRgb12:
      return std::make_unique<Rgb12Item>();
    default:
      return std::make_unique<ByteItem>(item.size);
  }
}

}  // namespace treesketch::io::laz
