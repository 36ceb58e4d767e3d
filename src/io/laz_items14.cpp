// Layered LAZ items, version 3 (point formats 6–10): a chunk holds its first record raw, the
// number of records, the byte count of every layer, then the layers, each coded on its own. A
// layer of zero bytes means that field never changes within the chunk. Each item keeps separate
// models and predictions for each of the four scanner channels, created when a channel first
// appears from the record before. Source: the LASzip specification (LAS 1.4 point formats).
#include <algorithm>
#include <cstring>

#include "io/laz_items.h"

namespace treesketch::io::laz {

namespace {

/// A layered item's byte count per layer, as the chunk lists them.
template <typename Sizes>
void readLayerSizes(ArithmeticDecoder& in, Sizes& sizes) {
  for (auto& s : sizes) s = in.readRawU32();
}

/// One decoder per layer, in order; an empty layer (the field never changes) is not started.
template <typename Sizes>
void startEveryLayer(ArithmeticDecoder& in, const Sizes& sizes, std::vector<ArithmeticDecoder>& layers) {
  layers.clear();
  for (std::uint32_t s : sizes) {
    layers.push_back(in.layer(s));
    if (s) layers.back().start();
  }
}

std::uint64_t loadU64(const unsigned char* p) {
  std::uint64_t v = 0;
  for (int i = 7; i >= 0; --i) v = (v << 8) | p[i];
  return v;
}
void storeU64(unsigned char* p, std::uint64_t v) {
  for (int i = 0; i < 8; ++i, v >>= 8) p[i] = static_cast<unsigned char>(v);
}

SymbolModel& lazy(std::unique_ptr<SymbolModel>& m, std::uint32_t symbols) { return lazyModel(m, symbols); }

// Context of the x/y predictions from the number of returns n and the return number r ([n][r]).
constexpr unsigned char kReturnContext6[16][16] = {
    {0, 1, 2, 3, 4, 5, 3, 4, 4, 5, 5, 5, 5, 5, 5, 5}, {1, 0, 1, 3, 3, 3, 3, 3, 3, 3, 3, 3, 3, 3, 3, 3},
    {2, 1, 2, 4, 4, 4, 4, 4, 4, 4, 4, 3, 3, 3, 3, 3}, {3, 3, 4, 5, 4, 4, 4, 4, 4, 4, 4, 4, 4, 4, 4, 4},
    {4, 3, 4, 4, 5, 4, 4, 4, 4, 4, 4, 4, 4, 4, 4, 4}, {5, 3, 4, 4, 4, 5, 4, 4, 4, 4, 4, 4, 4, 4, 4, 4},
    {3, 3, 4, 4, 4, 4, 5, 4, 4, 4, 4, 4, 4, 4, 4, 4}, {4, 3, 4, 4, 4, 4, 4, 5, 4, 4, 4, 4, 4, 4, 4, 4},
    {4, 3, 4, 4, 4, 4, 4, 4, 5, 4, 4, 4, 4, 4, 4, 4}, {5, 3, 4, 4, 4, 4, 4, 4, 4, 5, 4, 4, 4, 4, 4, 4},
    {5, 3, 4, 4, 4, 4, 4, 4, 4, 4, 5, 4, 4, 4, 4, 4}, {5, 3, 3, 4, 4, 4, 4, 4, 4, 4, 4, 5, 5, 4, 4, 4},
    {5, 3, 3, 4, 4, 4, 4, 4, 4, 4, 4, 5, 5, 5, 4, 4}, {5, 3, 3, 4, 4, 4, 4, 4, 4, 4, 4, 4, 5, 5, 5, 4},
    {5, 3, 3, 4, 4, 4, 4, 4, 4, 4, 4, 4, 4, 5, 5, 5}, {5, 3, 3, 4, 4, 4, 4, 4, 4, 4, 4, 4, 4, 4, 5, 5}};

/// Context of the z prediction: |n - r| capped at 7.
unsigned returnLevel8(unsigned n, unsigned r) { return std::min(n > r ? n - r : r - n, 7u); }

// POINT14 record (30 bytes): X Y Z int32 (0), intensity (12), returns byte r | n << 4 (14),
// flags byte: class flags 0–3, scanner channel 4–5, scan direction 6, edge of flight line 7 (15),
// classification (16), user data (17), scan angle int16 (18), point source id (20), GPS time (22).
constexpr std::size_t kPoint14Size = 30;

/// One scanner channel's models and predictions for POINT14.
struct Point14Channel {
  Point14Channel()
      : scannerChannel(3),
        rnGpsSame(13),
        gpsMulti(515),
        gpsZeroDiff(5),
        dx(32, 2),
        dy(32, 22),
        z(32, 20),
        intensity(16, 4),
        scanAngle(16, 2),
        pointSource(16),
        gps(32, 9) {}
  std::array<std::unique_ptr<SymbolModel>, 8> changed;
  SymbolModel scannerChannel, rnGpsSame;
  std::array<std::unique_ptr<SymbolModel>, 16> nr, rn;
  std::array<std::unique_ptr<SymbolModel>, 64> classification, flags, userData;
  SymbolModel gpsMulti, gpsZeroDiff;
  IntegerDecompressor dx, dy, z, intensity, scanAngle, pointSource, gps;
  unsigned char last[kPoint14Size] = {};
  std::array<std::uint16_t, 8> lastIntensity{};
  std::array<std::int32_t, 8> lastZ{};
  std::array<Median5, 12> xMedian, yMedian;
  GpsTimeState gpsState;
  bool gpsChanged = false;

  /// Starts from record `rec` (the chunk's first, or the last one of another channel).
  void startFrom(const unsigned char* rec) {
    std::memcpy(last, rec, kPoint14Size);
    lastZ.fill(static_cast<std::int32_t>(loadU32(rec + 8)));
    lastIntensity.fill(loadU16(rec + 12));
    gpsState.last[0] = loadU64(rec + 22);
  }
};

class Point14Item final : public LayeredItem {
 public:
  void first(const unsigned char* raw, unsigned& channel) override {
    channel = (raw[15] >> 4) & 3;
    ch_[channel] = std::make_unique<Point14Channel>();
    ch_[channel]->startFrom(raw);
    current_ = channel;
  }

  void readSizes(ArithmeticDecoder& in) override { readLayerSizes(in, sizes_); }
  void startLayers(ArithmeticDecoder& in) override { startEveryLayer(in, sizes_, layers_); }

  void next(unsigned char* out, unsigned& channel) override {
    ArithmeticDecoder& xy = layers_[kXy];
    Point14Channel& prev = *ch_[current_];
    const unsigned prevR = prev.last[14] & 15, prevN = prev.last[14] >> 4;
    const unsigned lpr = (prevR == 1) | (prevR >= prevN) << 1 | unsigned(prev.gpsChanged) << 2;
    const std::uint32_t changed = xy.decodeSymbol(lazy(prev.changed[lpr], 128));
    unsigned sc = current_;
    if (changed & 64) {
      sc = (sc + xy.decodeSymbol(prev.scannerChannel) + 1) % 4;
      if (!ch_[sc]) {
        ch_[sc] = std::make_unique<Point14Channel>();
        ch_[sc]->startFrom(prev.last);
      }
      current_ = sc;
      channel = sc;  // the other items hear of the channel only when it changes (format v3)
    }
    Point14Channel& c = *ch_[sc];
    unsigned char* l = c.last;
    l[15] = static_cast<unsigned char>((l[15] & ~0x30) | sc << 4);
    const bool gpsChanged = changed & 16;

    // Returns: the number of returns, then the return number (+1, -1 or coded).
    unsigned n = l[14] >> 4, r = l[14] & 15;
    if (changed & 4) n = xy.decodeSymbol(lazy(c.nr[n], 16));
    const bool rnPlus = changed & 1, rnMinus = changed & 2;
    if (rnPlus && !rnMinus) {
      r = (r + 1) % 16;
    } else if (rnMinus && !rnPlus) {
      r = (r + 15) % 16;
    } else if (rnPlus && rnMinus) {
      if (gpsChanged)
        r = xy.decodeSymbol(lazy(c.rn[r], 16));
      else
        r = (r + xy.decodeSymbol(c.rnGpsSame) + 2) % 16;
    }
    l[14] = static_cast<unsigned char>(r | n << 4);

    // X and Y: differences predicted by the median of the last five of their context.
    const unsigned ctx = unsigned(kReturnContext6[n][r]) << 1 | unsigned(gpsChanged);
    const std::int32_t dx = c.dx.decompress(xy, c.xMedian[ctx].get(), n == 1);
    storeU32(l, loadU32(l) + static_cast<std::uint32_t>(dx));
    c.xMedian[ctx].add(dx);
    const std::uint32_t kx = std::min(c.dx.k(), 20u) & ~1u;
    const std::int32_t dy = c.dy.decompress(xy, c.yMedian[ctx].get(), (n == 1) | kx);
    storeU32(l + 4, loadU32(l + 4) + static_cast<std::uint32_t>(dy));
    c.yMedian[ctx].add(dy);

    decodeLayers(c, changed, n, r, sc);
    c.gpsChanged = gpsChanged;
    std::memcpy(out, l, kPoint14Size);
  }

 private:
  /// The fields after X and Y, each from its own layer (skipped when that layer is empty or
  /// `changed` says the field kept its value): Z, classification, flags, intensity, scan angle,
  /// user data, point source and GPS time.
  void decodeLayers(Point14Channel& c, std::uint32_t changed, unsigned n, unsigned r, unsigned sc) {
    unsigned char* l = c.last;
    const bool gpsChanged = changed & 16;
    if (sizes_[kZ]) {
      const std::uint32_t kz = std::min((c.dx.k() + c.dy.k()) / 2, 18u) & ~1u;
      const unsigned lvl = returnLevel8(n, r);
      const std::int32_t z = c.z.decompress(layers_[kZ], c.lastZ[lvl], (n == 1) | kz);
      storeU32(l + 8, static_cast<std::uint32_t>(z));
      c.lastZ[lvl] = z;
    }
    if (sizes_[kClass]) {
      const unsigned cc = unsigned(r == 1 && r >= n) | unsigned(l[16] & 0x1F) << 1;
      l[16] = static_cast<unsigned char>(layers_[kClass].decodeSymbol(lazy(c.classification[cc], 256)));
    }
    if (sizes_[kFlags]) {
      const unsigned merged = (l[15] & 0x0F) | ((l[15] >> 6) & 1) << 4 | ((l[15] >> 7) & 1) << 5;
      const std::uint32_t f = layers_[kFlags].decodeSymbol(lazy(c.flags[merged], 64));
      l[15] = static_cast<unsigned char>((f & 0x0F) | sc << 4 | ((f >> 4) & 1) << 6 | ((f >> 5) & 1) << 7);
    }
    if (sizes_[kIntensity]) {
      const unsigned ic = unsigned(gpsChanged) | unsigned(r >= n) << 1 | unsigned(r == 1) << 2;
      const auto v =
          static_cast<std::uint16_t>(c.intensity.decompress(layers_[kIntensity], c.lastIntensity[ic], ic >> 1));
      c.lastIntensity[ic] = v;
      storeU16(l + 12, v);
    }
    if (changed & 8) {
      const auto prevAngle = static_cast<std::int16_t>(loadU16(l + 18));
      storeU16(l + 18, static_cast<std::uint32_t>(c.scanAngle.decompress(layers_[kScanAngle], prevAngle, gpsChanged)));
    }
    if (sizes_[kUserData])
      l[17] = static_cast<unsigned char>(layers_[kUserData].decodeSymbol(lazy(c.userData[l[17] / 4], 256)));
    if (changed & 32)
      storeU16(l + 20, static_cast<std::uint32_t>(c.pointSource.decompress(layers_[kPointSource], loadU16(l + 20), 0)));
    if (gpsChanged) {
      c.gpsState.decode(layers_[kGps], c.gpsMulti, c.gpsZeroDiff, c.gps, true);
      storeU64(l + 22, c.gpsState.last[c.gpsState.cur]);
    }
  }

  enum Layer { kXy, kZ, kClass, kFlags, kIntensity, kScanAngle, kUserData, kPointSource, kGps, kLayers };
  std::array<std::unique_ptr<Point14Channel>, 4> ch_;
  unsigned current_ = 0;
  std::array<std::uint32_t, kLayers> sizes_{};
  std::vector<ArithmeticDecoder> layers_;
};

/// The context switch of RGB14, RGBNIR14 and BYTE14, as version 3 of the format defines it:
/// `channel` (0 unless POINT14 switched channels at this record) selects whose models code the
/// record; a channel seen for the first time starts from a copy of the current one's last value
/// and predicts from it, while a channel seen before keeps predicting from (and updating) the
/// last value of the channel that was current. Returns that state; `models` is the new channel's.
template <class State>
State& switchChannel(std::array<std::unique_ptr<State>, 4>& ch, unsigned& current, unsigned channel,
                     State*& models) {
  State* last = ch[current].get();
  if (channel != current) {
    current = channel;
    if (!ch[current]) {
      ch[current] = std::make_unique<State>();
      ch[current]->last = last->last;
      last = ch[current].get();
    }
  }
  models = ch[current].get();
  return *last;
}

/// RGB14 and RGBNIR14: per channel, the models and the last R G B (NIR) values.
struct RgbNirState {
  RgbNirState() : used(128), nirUsed(4) {
    for (auto& m : diff) m = std::make_unique<SymbolModel>(256);
  }
  SymbolModel used;
  std::array<std::unique_ptr<SymbolModel>, 6> diff;
  SymbolModel nirUsed;
  std::array<std::unique_ptr<SymbolModel>, 2> nirDiff;
  std::array<std::uint32_t, 4> last{};  // R G B NIR
};

/// RGB14 (6 bytes) and RGBNIR14 (8 bytes: RGB then NIR, each its own layer).
class Rgb14Item final : public LayeredItem {
 public:
  explicit Rgb14Item(bool nir) : nir_(nir) {}

  void first(const unsigned char* raw, unsigned& channel) override {
    current_ = channel;
    ch_[channel] = std::make_unique<RgbNirState>();
    for (int k = 0; k < (nir_ ? 4 : 3); ++k) ch_[channel]->last[k] = loadU16(raw + 2 * k);
  }

  void readSizes(ArithmeticDecoder& in) override {
    rgbSize_ = in.readRawU32();
    if (nir_) nirSize_ = in.readRawU32();
  }

  void startLayers(ArithmeticDecoder& in) override {
    layers_.clear();
    layers_.push_back(in.layer(rgbSize_));
    if (rgbSize_) layers_.back().start();
    if (nir_) {
      layers_.push_back(in.layer(nirSize_));
      if (nirSize_) layers_.back().start();
    }
  }

  void next(unsigned char* out, unsigned& channel) override {
    RgbNirState* m = nullptr;
    RgbNirState& s = switchChannel(ch_, current_, channel, m);
    if (rgbSize_) {
      std::array<std::uint32_t, 3> last{s.last[0], s.last[1], s.last[2]}, v{};
      decodeRgb(layers_[0], m->used, m->diff, last, v);
      for (int k = 0; k < 3; ++k) s.last[k] = v[k];
    }
    for (int k = 0; k < 3; ++k) storeU16(out + 2 * k, s.last[k]);
    if (nir_) {
      if (nirSize_) {
        ArithmeticDecoder& d = layers_[1];
        const std::uint32_t sym = d.decodeSymbol(m->nirUsed);
        const std::uint32_t prev = s.last[3];
        std::uint32_t v = (sym & 1) ? (d.decodeSymbol(lazy(m->nirDiff[0], 256)) + prev) & 0xFF : prev & 0xFF;
        v |= (sym & 2) ? ((d.decodeSymbol(lazy(m->nirDiff[1], 256)) + (prev >> 8)) & 0xFF) << 8 : prev & 0xFF00;
        s.last[3] = v;
      }
      storeU16(out + 6, s.last[3]);
    }
  }

 private:
  bool nir_;
  unsigned current_ = 0;
  std::uint32_t rgbSize_ = 0, nirSize_ = 0;
  std::array<std::unique_ptr<RgbNirState>, 4> ch_;
  std::vector<ArithmeticDecoder> layers_;
};

/// BYTE14: per channel, the models and the last bytes.
struct BytesState {
  std::vector<unsigned char> last;
  std::vector<std::unique_ptr<SymbolModel>> models;
};

/// BYTE14 (extra bytes): each byte its own layer, as a difference from the previous record's.
class Byte14Item final : public LayeredItem {
 public:
  explicit Byte14Item(std::size_t n) : n_(n), sizes_(n) {}

  void first(const unsigned char* raw, unsigned& channel) override {
    current_ = channel;
    ch_[channel] = std::make_unique<BytesState>();
    ch_[channel]->last.assign(raw, raw + n_);
  }

  void readSizes(ArithmeticDecoder& in) override { readLayerSizes(in, sizes_); }
  void startLayers(ArithmeticDecoder& in) override { startEveryLayer(in, sizes_, layers_); }

  void next(unsigned char* out, unsigned& channel) override {
    BytesState* m = nullptr;
    BytesState& s = switchChannel(ch_, current_, channel, m);
    if (m->models.empty()) m->models.resize(n_);
    for (std::size_t i = 0; i < n_; ++i) {
      if (sizes_[i])
        s.last[i] = static_cast<unsigned char>(s.last[i] + layers_[i].decodeSymbol(lazy(m->models[i], 256)));
      out[i] = s.last[i];
    }
  }

 private:
  std::size_t n_;
  unsigned current_ = 0;
  std::vector<std::uint32_t> sizes_;
  std::array<std::unique_ptr<BytesState>, 4> ch_;
  std::vector<ArithmeticDecoder> layers_;
};

}  // namespace

std::unique_ptr<LayeredItem> makeLayeredItem(const Item& item) {
  switch (item.type) {
    case kPoint14:
      return std::make_unique<Point14Item>();
    case kRgb14:
      return std::make_unique<Rgb14Item>(false);
    case kRgbNir14:
      return std::make_unique<Rgb14Item>(true);
    default:
      return std::make_unique<Byte14Item>(item.size);
  }
}

}  // namespace treesketch::io::laz
